//! The generated code's sines and cosines (`lagrange::trig`): an angle whose
//! cosine is taken of a sine is computed after it, arguments beyond the
//! kernel's range and non-finite ones are the platform's, and an `f32`
//! model takes `f32`'s own functions.

use lagrange::lagrangian;
use lagrange::nalgebra::Vector1;

lagrangian! {
    /// `V = cos θ + cos(sin θ)`: the lane of `sin θ` feeds a second call.
    pub struct NestedCosine {
        coordinates: theta;
        kinetic: dot(theta)^2 / 2;
        potential: cos(theta) + cos(sin(theta));
    }
}

/// `f = −dV/dθ = sin θ + sin(sin θ) cos θ`.
fn forcing(theta: f64) -> f64 {
    theta.sin() + theta.sin().sin() * theta.cos()
}

#[test]
fn a_cosine_of_a_sine_is_computed_after_the_sine() {
    let model = NestedCosine::<f64>::new();
    let zero = Vector1::new(0.0);
    // Inside the kernel's range, at and near multiples of π/2, and beyond
    // it (1e6, 1e300: the platform's reduction).
    let half_pi = core::f64::consts::FRAC_PI_2;
    for theta in [0.3, -2.0, 7.5, half_pi, 3.0 * half_pi, 1e-300, 1e6, 1e300] {
        let q = Vector1::new(theta);
        let f = model.forcing(0.0, &q, &zero)[0];
        let v = model.potential_energy(0.0, &q);
        // Each side's sines and cosines are within an ulp of exact, so
        // the two agree to a few ε of the terms' size (at most 2).
        let (f0, v0) = (forcing(theta), theta.cos() + theta.sin().cos());
        assert!(
            (f - f0).abs() <= 8.0 * f64::EPSILON,
            "θ = {theta:e}: f = {f}, {f0}"
        );
        assert!(
            (v - v0).abs() <= 8.0 * f64::EPSILON,
            "θ = {theta:e}: V = {v}, {v0}"
        );
    }
    for theta in [f64::NAN, f64::INFINITY] {
        let f = model.forcing(0.0, &Vector1::new(theta), &zero)[0];
        assert!(f.is_nan(), "θ = {theta}: f = {f}");
    }
}

#[test]
fn an_f32_model_takes_sines_and_cosines_rounded_once_from_f64() {
    let model = NestedCosine::<f32>::new();
    let theta = 0.7_f32;
    let f = model.forcing(0.0, &Vector1::new(theta), &Vector1::new(0.0))[0];
    // The kernel's f64 values rounded to f32 (`lagrange::trig`): here the
    // f64 functions' rounded once, as no value is near a tie.
    let (sin, cos) = lagrange::trig::sin_cos(theta);
    let once = |x: f32| ((x as f64).sin() as f32, (x as f64).cos() as f32);
    assert_eq!((sin, cos), once(theta));
    assert_eq!(lagrange::trig::sin(sin), once(sin).0);
    // The expression may round differently (a multiply-add where the
    // target has FMA): within 2 ε of its size.
    let f0 = once(theta).0 + once(once(theta).0).0 * once(theta).1;
    assert!((f - f0).abs() <= 2.0 * f32::EPSILON, "{f} vs {f0}");
}
