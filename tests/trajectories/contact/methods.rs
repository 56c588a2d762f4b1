//! Every method on the contact scenes, or the reason it cannot take them.

use lagrange::contact::Switch;
use lagrange::contact::{self, Cause, ContactError, ContactSettings};
use lagrange::models::{BallOnFloor, BlockOnBelt, Ladder, SlidingBall};
use lagrange::nalgebra::{SVector, Vector1, Vector3};
use lagrange::prelude::*;
use lagrange::Method;

/// The fixed-step methods' step.
const H: f64 = 1e-3;

/// The error of the time the ball (restitution 1/2, dropped from 1 m)
/// comes to rest, by `method` at step `h`.
fn rest_error(method: Method, h: f64) -> Result<f64, String> {
    let ball = BallOnFloor::new(1.0, 9.81, 0.5);
    // A first-order method holds the bounces at flights of a few steps
    // (explicit Euler gains energy on every flight): they settle only with
    // a shortest flight of that size, which the run cannot know.
    let first_order = matches!(method, Method::ExplicitEuler | Method::SymplecticEuler);
    let settings = ContactSettings {
        shortest_flight: if first_order { 4.0 * h } else { 1e-10 },
        ..ContactSettings::default()
    };
    let run = contact::integrate(
        &method.with_step(h),
        &ball,
        0.0,
        Vector1::new(1.0),
        Vector1::new(0.0),
        &[2.0],
        settings,
    )
    .map_err(|f| f.error.to_string())?;
    let rest = run.switches().last().expect("it bounces");
    assert_eq!(rest.cause, Cause::Settled, "{method:?}");
    Ok(rest.t - ball.rest_time(1.0))
}

#[test]
fn every_method_settles_the_ball_and_rolls_the_sliding_ball_or_says_why_not() {
    let sliding = SlidingBall::new(0.3, 0.05, 9.81, 0.2);
    let (q, v) = sliding.thrown(2.0);
    println!("method             rest time error   rolling time error");
    for method in Method::ALL {
        let roll = contact::integrate(
            &method.with_step(H),
            &sliding,
            0.0,
            Vector3::from(q),
            Vector3::from(v),
            &[1.0],
            ContactSettings::default(),
        );
        if method == Method::Variational {
            // Its discrete Euler–Lagrange equations see no force solved
            // from the state: refused before the first step.
            let failure = roll.unwrap_err();
            assert!(
                matches!(failure.error, ContactError::Integration(_)),
                "{}",
                failure.error
            );
            println!("{:<18} refused: {}", method.id(), failure.error);
            assert!(rest_error(method, H).is_err());
            continue;
        }
        let roll = roll.unwrap_or_else(|f| panic!("{method:?}: {}", f.error));
        let rolling = roll
            .switches()
            .iter()
            .find(|s| s.cause == Cause::SlideStopped)
            .expect("it rolls");
        let roll_error = rolling.t - sliding.rolling_time(2.0);
        let rest = rest_error(method, H).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        println!("{:<18} {rest:>17.1e} {roll_error:>19.1e}", method.id());
        // A constant deceleration is linear in the slip velocity: every
        // method is exact on it up to rounding and the location.
        assert!(
            roll_error.abs() < 1e-10,
            "{method:?}: rolling time off by {roll_error:e}"
        );
        if matches!(method, Method::ExplicitEuler | Method::SymplecticEuler) {
            // First order: the bounces' errors halve with the step.
            let finer = rest_error(method, H / 2.0).unwrap();
            let ratio = rest / finer;
            println!("{:<18} {finer:>17.1e} at h / 2: ratio {ratio:.2}", "");
            assert!(
                (1.5..2.5).contains(&ratio.abs()),
                "{method:?}: {rest:e} / {finer:e}"
            );
        } else {
            // Free fall is quadratic in t: every other method is exact on
            // it, so the rest time carries the location's few ulps per
            // bounce and the flights cut off (1e-10 / (1 − e)).
            assert!(rest.abs() < 1e-9, "{method:?}: rest time off by {rest:e}");
        }
    }
}

/// The switches of a scene by `method` at step `h` (its defaults where
/// adaptive), after the start's.
fn switches<L, const N: usize, const K: usize>(
    method: &impl Integrator<f64>,
    model: &L,
    (q0, v0): ([f64; N], [f64; N]),
    end: f64,
) -> Result<Vec<Switch<f64, N>>, String>
where
    L: lagrange::contact::Contacts<N, K, Scalar = f64> + Sync,
{
    let run = contact::integrate(
        method,
        model,
        0.0,
        SVector::from(q0),
        SVector::from(v0),
        &[end],
        ContactSettings::default(),
    )
    .map_err(|f| f.error.to_string())?;
    Ok(run
        .switches()
        .iter()
        .filter(|s| s.cause != Cause::Start)
        .copied()
        .collect())
}

#[test]
fn every_method_finds_the_ladders_release_and_the_belts_stick_slip_switches() {
    // Against Dop853 at 1e-12: the same switches, contact by contact and
    // cause by cause, at times within the method's own error.
    let ladder = Ladder::new(5.0, 3.0, 9.81);
    let belt = BlockOnBelt::new(1.0, 9.81, 40.0, 0.3, 0.6, 0.4);
    let reference = Dop853::new().rtol(1e-12).atol(1e-12);
    let ladder_start = ladder.at_rest(1.0);
    let belt_start = ([0.0, 0.0], [0.3, 0.0]);
    let ladder_exact = switches(&reference, &ladder, ladder_start, 1.0).unwrap();
    let belt_exact = switches(&reference, &belt, belt_start, 3.0).unwrap();
    println!("method             ladder release   belt switches (worst)");
    for method in Method::ALL {
        let integrator = method.with_step(H);
        let ladder_run = switches(&integrator, &ladder, ladder_start, 1.0);
        let belt_run = switches(&integrator, &belt, belt_start, 3.0);
        if method == Method::Variational {
            assert!(ladder_run.is_err() && belt_run.is_err());
            continue;
        }
        let (ladder_run, belt_run) = (ladder_run.unwrap(), belt_run.unwrap());
        let worst = |run: &[Switch<f64, 2>], exact: &[Switch<f64, 2>]| {
            assert_eq!(run.len(), exact.len(), "{method:?}");
            run.iter()
                .zip(exact)
                .map(|(a, b)| {
                    assert_eq!(
                        (a.contact, a.cause, a.to),
                        (b.contact, b.cause, b.to),
                        "{method:?}"
                    );
                    (a.t - b.t).abs()
                })
                .fold(0.0, f64::max)
        };
        assert_eq!(ladder_run.len(), ladder_exact.len(), "{method:?}");
        let release = (ladder_run[0].t - ladder_exact[0].t).abs();
        assert_eq!(
            (ladder_run[0].name, ladder_run[0].cause),
            ("wall", Cause::Release)
        );
        let belt_error = worst(&belt_run, &belt_exact);
        println!("{:<18} {release:>14.1e} {belt_error:>23.1e}", method.id());
        // Each within its method's error over these runs (measured when
        // this was written: first order 4.9e-3, the midpoint rule 4.9e-6,
        // the fourth order and higher 1.8e-11, the adaptive ones at their
        // default tolerance of 1e-8 up to 1.6e-7 over 3 s and five
        // switches): the switches are located on each method's own
        // trajectory.
        let bound = match method {
            Method::ExplicitEuler | Method::SymplecticEuler => 10.0 * H,
            Method::ImplicitMidpoint => 10.0 * H * H,
            Method::Rk4 | Method::GaussLegendre2 | Method::GaussLegendre3 => 1e-9,
            _ => 1e-5,
        };
        assert!(
            release.max(belt_error) < bound,
            "{method:?}: {release:e}, {belt_error:e}"
        );
    }
}
