//! Every method on the contact scenes, or the reason it cannot take them.
//!
//! The scenes are those with two coordinates and one contact (the ball,
//! the belt, the string), so that every method's loop is compiled once for
//! all three (contact runs are compiled per scalar, `N` and `K`): between
//! them they make every kind of switch (an impact, a settling, a release,
//! a plastic snap, a stick limit, a slide stopping).

use lagrange::Method;
use lagrange::contact::{self, Cause, ContactError, ContactSettings, Contacts, Switch};
use lagrange::models::{BallOnFloor, BlockOnBelt, BobOnString};
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

/// The fixed-step methods' step.
const H: f64 = 1e-3;

/// The switches after the start of a scene from `(q0, v0)` to `end`, by
/// `method` with `settings`.
fn switches<L>(
    method: &impl StepMethod<f64>,
    model: &L,
    (q0, v0): ([f64; 2], [f64; 2]),
    end: f64,
    settings: ContactSettings<f64>,
) -> Result<Vec<Switch<f64, 2>>, ContactError<f64, 2>>
where
    L: Contacts<2, 1, Scalar = f64> + Sync,
{
    let (q0, v0) = (Vector2::from(q0), Vector2::from(v0));
    let run =
        contact::integrate(method, model, 0.0, q0, v0, &[end], settings).map_err(|f| f.error)?;
    Ok(run
        .switches()
        .iter()
        .filter(|s| s.cause != Cause::Start)
        .copied()
        .collect())
}

/// The worst time difference of `run`'s switches from `exact`'s, which
/// they must match contact by contact, cause by cause.
fn worst(method: Method, run: &[Switch<f64, 2>], exact: &[Switch<f64, 2>]) -> f64 {
    assert_eq!(run.len(), exact.len(), "{method:?}");
    let mut worst = 0.0f64;
    for (a, b) in run.iter().zip(exact) {
        assert_eq!(
            (a.contact, a.cause, a.to),
            (b.contact, b.cause, b.to),
            "{method:?}"
        );
        worst = worst.max((a.t - b.t).abs());
    }
    worst
}

#[test]
fn every_method_makes_every_kind_of_switch_within_its_own_error_or_says_why_not() {
    let ball = BallOnFloor::new(1.0, 9.81, 0.5);
    let belt = BlockOnBelt::new(1.0, 9.81, 40.0, 0.3, 0.6, 0.4);
    let bob = BobOnString::new(0.5, 9.81, 1.2);
    let dropped = ([0.0, 1.0], [0.0, 0.0]);
    let riding = ([0.0, 0.0], [0.3, 0.0]);
    let v0 = (3.5f64 * 9.81 * 1.2).sqrt();
    let whirled = (bob.whirled(v0).0, bob.whirled(v0).1);
    let reference = Dop853::new().rtol(1e-12).atol(1e-12);
    let defaults = ContactSettings::default();
    let belt_exact = switches(&reference, &belt, riding, 3.0, defaults).unwrap();
    let bob_exact = switches(&reference, &bob, whirled, 2.0, defaults).unwrap();
    println!("method             ball's rest   belt (worst)   string (worst)");
    for method in Method::ALL {
        let integrator = method.with_step(H);
        // A first-order method holds the bounces at flights of a few steps
        // (explicit Euler gains energy on every flight): they settle only
        // with a shortest flight of that size, which the run cannot know.
        let first_order = matches!(method, Method::ExplicitEuler | Method::SymplecticEuler);
        let settle = ContactSettings {
            shortest_flight: if first_order { 4.0 * H } else { 1e-10 },
            ..defaults
        };
        let ball_run = switches(&integrator, &ball, dropped, 2.0, settle);
        if method == Method::Variational {
            // Its discrete Euler–Lagrange equations need the model's
            // momenta, which a run with forces solved from the state does
            // not offer: refused before the first step.
            let error = ball_run.unwrap_err();
            assert!(matches!(error, ContactError::Integration(_)), "{error}");
            println!("{:<18} refused: {error}", method.id());
            continue;
        }
        let ball_run = ball_run.unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let rest = ball_run.last().expect("it bounces");
        assert_eq!(rest.cause, Cause::Settled, "{method:?}");
        let rest_error = rest.t - ball.rest_time(1.0);
        let belt_run = switches(&integrator, &belt, riding, 3.0, defaults).unwrap();
        let bob_run = switches(&integrator, &bob, whirled, 2.0, defaults).unwrap();
        let (belt_error, bob_error) = (
            worst(method, &belt_run, &belt_exact),
            worst(method, &bob_run, &bob_exact),
        );
        println!(
            "{:<18} {rest_error:>11.1e} {belt_error:>14.1e} {bob_error:>16.1e}",
            method.id()
        );
        // Each within its method's error (measured when this was written:
        // first order 2.6e-2 on the bounces, whose errors add up, and
        // 4.9e-3 elsewhere; the midpoint rule 4.9e-6; fourth order and
        // higher 1.8e-11; the adaptive methods at their default tolerance
        // of 1e-8 up to 1.6e-7 over these runs). Free fall is quadratic in
        // t, on which every method but the first-order ones is exact: the
        // ball's rest then carries only the locations and the flights cut
        // off (1e-10 / (1 − e)).
        let (bound, rest_bound) = match method {
            Method::ExplicitEuler | Method::SymplecticEuler => (10.0 * H, 50.0 * H),
            Method::ImplicitMidpoint => (10.0 * H * H, 1e-9),
            Method::Rk4 | Method::GaussLegendre2 | Method::GaussLegendre3 => (1e-9, 1e-9),
            _ => (1e-5, 1e-9),
        };
        assert!(
            rest_error.abs() < rest_bound,
            "{method:?}: rest off by {rest_error:e}"
        );
        assert!(
            belt_error.max(bob_error) < bound,
            "{method:?}: {belt_error:e}, {bob_error:e}"
        );
    }
}
