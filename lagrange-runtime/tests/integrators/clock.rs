//! The clock advances with the state: an adaptive step moves `t` to
//! `fl(t + h)`, so the state must move by that same representable step, or
//! the two drift apart by up to half an ulp of `t` per step.
//!
//! Far from `t = 0` an ulp of `t` is large (`2⁻²³ s ≈ 1.2e-7 s` at
//! `t = 2³⁰ s`), so a run started there shows in a few hundred steps the
//! drift that near `t = 70` took 10⁵ steps to show: the harmonic
//! oscillator's phase, against `cos(t − t0)`.

use lagrange_runtime::StepMethod;
use lagrange_runtime::nalgebra::Vector2;
use lagrange_runtime::prelude::*;

use crate::models::CoupledOscillator;

/// The times and positions a run reached.
type Run = Vec<(f64, Vector2<f64>)>;

const T0: f64 = 1_073_741_824.0; // 2³⁰
const SPAN: f64 = 20.0;
const TOL: f64 = 1e-12;

/// The largest error against the exact motion over 20 s (about three
/// periods), sampled every second from `t0`.
fn worst_error(run: impl Fn(&CoupledOscillator<f64>, f64, &[f64]) -> Run, t0: f64) -> f64 {
    let model = CoupledOscillator { omega: 1.0 };
    let (q0, v0) = (Vector2::new(1.0, -0.5), Vector2::new(0.0, 0.3));
    // t0 + k is exact for these t0 and k, and so is its difference with t0.
    let times: Vec<f64> = (1..=SPAN as usize).map(|k| t0 + k as f64).collect();
    run(&model, t0, &times)
        .into_iter()
        .map(|(t, q)| (q - model.exact(t - t0, q0, v0).0).amax())
        .fold(0.0, f64::max)
}

fn integrated<I: Integrator<f64>>(
    method: I,
) -> impl Fn(&CoupledOscillator<f64>, f64, &[f64]) -> Run {
    move |model, t0, times| {
        let (q0, v0) = (Vector2::new(1.0, -0.5), Vector2::new(0.0, 0.3));
        let run = method
            .integrate(model, t0, q0, v0, times)
            .expect("integrates");
        run.iter().map(|s| (s.t, s.q)).collect()
    }
}

fn stepped<M: StepMethod<f64> + Copy>(
    method: M,
) -> impl Fn(&CoupledOscillator<f64>, f64, &[f64]) -> Run {
    move |model, t0, times| {
        let (q0, v0) = (Vector2::new(1.0, -0.5), Vector2::new(0.0, 0.3));
        let model = CoupledOscillator { omega: model.omega };
        let mut stepper = Stepper::new(model, method, t0, q0, v0).expect("starts");
        times
            .iter()
            .map(|&t| {
                stepper.advance_to(t).expect("steps");
                (stepper.t(), *stepper.q())
            })
            .collect()
    }
}

/// Far from zero the error is the method's own, as near zero: at
/// `rtol = atol = 1e-12` the global error of the explicit pairs over these
/// 20 s stays within 10 tol per second of run, 1e-10 (measured 7e-12 and
/// 4e-12); Radau5 controls `rtol' = 0.1 rtol^(2/3)` and its global error
/// grows like `rtol^(5/6) = 1e-10` per unit of time scale (its docs), so
/// 10× that (measured 3.4e-10). The clock adds nothing once the state
/// advances by the step the clock takes. Before, the clock's rounding, up
/// to 6e-8 s per step at `2³⁰ s`, put a phase error of 3.3e-6 here.
#[test]
fn an_adaptive_clock_far_from_zero_keeps_the_phase() {
    type Worst = Box<dyn Fn(f64) -> f64>;
    let runs: [(&str, Worst, f64); 5] = [
        (
            "dopri5",
            Box::new(|t0| worst_error(integrated(Dopri5::new().rtol(TOL).atol(TOL)), t0)),
            1e-10,
        ),
        (
            "dop853",
            Box::new(|t0| worst_error(integrated(Dop853::new().rtol(TOL).atol(TOL)), t0)),
            1e-10,
        ),
        (
            "radau5",
            Box::new(|t0| worst_error(integrated(Radau5::new().rtol(TOL).atol(TOL)), t0)),
            1e-9,
        ),
        (
            "stepper dopri5",
            Box::new(|t0| worst_error(stepped(Dopri5::new().rtol(TOL).atol(TOL)), t0)),
            1e-10,
        ),
        (
            "stepper dop853",
            Box::new(|t0| worst_error(stepped(Dop853::new().rtol(TOL).atol(TOL)), t0)),
            1e-10,
        ),
    ];
    for (name, run, bound) in runs {
        let (near, far) = (run(0.0), run(T0));
        println!("{name}: worst error {near:.1e} from t0 = 0, {far:.1e} from t0 = 2^30");
        assert!(near < bound, "{name}: {near:e} from t0 = 0");
        assert!(far < bound, "{name}: {far:e} from t0 = 2^30");
    }
}
