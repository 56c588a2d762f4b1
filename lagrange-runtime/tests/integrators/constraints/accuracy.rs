//! The Cartesian pendulum is the pendulum: its angle converges at each
//! method's order, and its multiplier is the rod's tension.

use super::{angle_error, angle_reference, every, pendulum, start};
use lagrange::Method;
use lagrange_runtime::constraints::annotate;
use lagrange_runtime::prelude::*;

/// Every method, with projection (the default), follows `θ(t)` of the
/// pendulum in its angle over a swing, with an error that falls at the
/// method's order `p`: halving `h` divides it by `2^p`, up to the next
/// term of the error expansion, for which 30 % is allowed. The projection
/// after each step keeps the order of the method it follows (Hairer,
/// Lubich & Wanner, GNI IV.4). Adaptive methods, which have no `h`, keep
/// the global error within 100 tolerances over the swing (the local error
/// is held to the tolerance, and a swing takes ~100 steps whose errors
/// partly cancel).
#[test]
fn every_method_follows_the_pendulum_angle_at_its_order() {
    let (q0, qdot0) = start();
    let times = every(0.25, 2.0);
    let reference = angle_reference(&times);
    let error = |integrator: lagrange::AnyIntegrator<f64>| {
        let run = integrator.integrate(&pendulum(), 0.0, q0, qdot0, &times);
        angle_error(&run.unwrap(), &reference)
    };
    for method in Method::ALL {
        if method.is_adaptive() {
            let tol = 1e-10;
            let err = error(method.with_tolerance(tol));
            assert!(err < 100.0 * tol, "{method:?}: angle error {err:e}");
            continue;
        }
        // Steps where the error is well above rounding and in the
        // asymptotic range: the first-order methods need small ones.
        let h = match method {
            Method::ExplicitEuler | Method::SymplecticEuler => 1e-3,
            Method::GaussLegendre3 => 0.05,
            _ => 0.02,
        };
        let (coarse, fine) = (error(method.with_step(h)), error(method.with_step(h / 2.0)));
        let gain = coarse / fine;
        let expected = 2f64.powi(method.order() as i32);
        assert!(
            gain > 0.7 * expected && gain < 1.3 * expected,
            "{method:?}: errors {coarse:e} at h = {h}, {fine:e} at h/2 (gain {gain:.2})"
        );
    }
}

/// The multiplier of `φ = x² + y² − l²` is the rod's tension over `2 l`
/// (`−Gᵀ λ = −2 λ (x, y)`), and the tension of the pendulum is
/// `m (g cos θ + l θ̇²)`. At a tolerance of `1e-12` the adaptive methods'
/// state is off by ~1e-11 over a swing, which changes the tension by
/// `m (g |δθ| + 2 l |θ̇| |δθ̇|)`, ~20 times that: 1e-9 bounds it with room.
/// (Radau5 holds its local error to `rtol^(2/3)`-scaled tolerances and
/// interpolates samples at third order, so it runs at `1e-14`.)
#[test]
fn multiplier_is_the_rod_tension() {
    let model = pendulum();
    let (q0, qdot0) = start();
    let times = every(0.25, 2.0);
    let reference = angle_reference(&times);
    for (method, tol) in [
        (Method::Dopri5, 1e-12),
        (Method::Dop853, 1e-12),
        (Method::Radau5, 1e-14),
    ] {
        let run = method
            .with_tolerance(tol)
            .integrate(&model, 0.0, q0, qdot0, &times)
            .unwrap();
        for (sample, exact) in annotate(&model, &run).unwrap().iter().zip(&reference) {
            let tension = model.tension(exact.q[0], exact.qdot[0]);
            let from_multiplier = 2.0 * model.l * sample.multipliers[0];
            assert!(
                (from_multiplier - tension).abs() < 1e-9,
                "{method:?} at t = {}: 2 l λ = {from_multiplier}, tension {tension}",
                sample.t
            );
        }
    }
}
