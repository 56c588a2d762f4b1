//! How close a located event is to the exact one, against the method's
//! tolerance: the zeros of `x = cos t`, the unit harmonic oscillator.

use std::f64::consts::PI;

use lagrange::Method;
use lagrange::models::Oscillator;
use lagrange_runtime::nalgebra::Vector1;
use lagrange_runtime::prelude::*;

/// Until t = 20: the zeros π/2 + kπ, k = 0..5.
const END: f64 = 20.0;

fn zero_crossings(method: Method, h: f64, tol: f64) -> Vec<f64> {
    let spring = Oscillator::new(1.0, 1.0, 0.0);
    let x = Event::new("x = 0", |_, q: &Vector1<f64>, _: &Vector1<f64>| q[0]);
    let events = Events::new().with(x);
    let (q0, v0) = (Vector1::new(1.0), Vector1::new(0.0));
    let run = method
        .integrator(h, tol)
        .max_steps(10_000_000)
        .integrate_with_events(&spring, 0.0, q0, v0, &[END], &events)
        .unwrap();
    run.events().iter().map(|event| event.t).collect()
}

/// The largest `|t_event − t_exact|` over the six zeros.
fn location_error(method: Method, h: f64, tol: f64) -> f64 {
    let found = zero_crossings(method, h, tol);
    assert_eq!(found.len(), 6, "{method:?} at h = {h}, tol = {tol}");
    found
        .iter()
        .enumerate()
        .map(|(k, t)| (t - (PI / 2.0 + k as f64 * PI)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn adaptive_methods_locate_events_to_their_own_accuracy() {
    println!("tolerance  |t_event - t_exact| over six zeros to t = 20");
    println!("           dopri5    dop853    radau5");
    for tol in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
        let errors = Method::ADAPTIVE.map(|method| location_error(method, 0.0, tol));
        println!(
            "{tol:<9.0e}  {:.1e}   {:.1e}   {:.1e}",
            errors[0], errors[1], errors[2]
        );
        for (method, error) in Method::ADAPTIVE.into_iter().zip(errors) {
            // At a zero |ẋ| = 1, so the time error is the error of the
            // interpolated x there, plus the root finder's 4 ε t. The
            // methods' global error on this oscillator grows by up to about
            // one tolerance per unit time (the crate docs: `rtol` over five
            // periods for Dopri5/Dop853; Radau5 `rtol^(5/6)`, 10 `rtol` at
            // 1e-10), so 20 tol over t = 20, and Radau5's dense output is
            // only as good as its local error `0.1 rtol^(2/3)` (see
            // `Radau5`), which dominates at tight tolerances.
            let dense = if method == Method::Radau5 {
                0.1 * tol.powf(2.0 / 3.0)
            } else {
                0.0
            };
            let bound = 20.0 * tol + dense + 1e-13;
            assert!(
                error < bound,
                "{method:?} at {tol:e}: {error:e} > {bound:e}"
            );
        }
    }
}

#[test]
fn fixed_steps_locate_events_to_the_hermite_interpolant_s_order() {
    println!("h        |t_event - t_exact| (Rk4, cubic Hermite)  bound");
    let mut previous: Option<f64> = None;
    for h in [0.1, 0.05, 0.025, 0.0125] {
        let error = location_error(Method::Rk4, h, 0.0);
        // Two errors, both O(h⁴): the cubic Hermite interpolant's,
        // h⁴/384 max|x⁗| = h⁴/384 at mid-step, and RK4's global phase
        // error on the oscillator, h⁴ t / 120 (its local error h⁵/120).
        let bound = h.powi(4) * (1.0 / 384.0 + END / 120.0);
        println!("{h:<8} {error:.2e}                              {bound:.2e}");
        assert!(error < bound, "h = {h}: {error:e}");
        if let Some(coarse) = previous {
            // Fourth order: 16 per halving, 12 allowing for the next term.
            assert!(coarse / error > 12.0, "h = {h}: {coarse:e} / {error:e}");
        }
        previous = Some(error);
    }
}
