//! Every method on the contact scenes, or the reason it cannot take them.

use lagrange::contact::{self, Cause, ContactError, ContactSettings};
use lagrange::models::{BallOnFloor, SlidingBall};
use lagrange::nalgebra::{Vector1, Vector3};
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
