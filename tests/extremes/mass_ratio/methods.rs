//! The integrators on both extremes: adaptive ones within their tolerance,
//! fixed-step ones at their order, and RK4 stopped beyond its stability
//! limit.

use super::{chain, heavy_start, light_start, max_distance, reference, sample_times};
use lagrange::models::DoublePendulum;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;
use lagrange::{IntegrationResult, Stats};

/// How much the flow amplifies a perturbation of the start: each initial
/// component moved by 1e-7 in turn, the largest resulting state change over
/// the samples, divided by 1e-7 (from reference runs, whose own error is
/// 1e-6 of the perturbation's effect).
fn perturbation_growth(model: &DoublePendulum, start: (Vector2<f64>, Vector2<f64>)) -> f64 {
    let base = reference(model, start);
    let delta = 1e-7;
    let mut growth: f64 = 1.0;
    for k in 0..4 {
        let (mut q0, mut v0) = start;
        if k < 2 {
            q0[k] += delta;
        } else {
            v0[k - 2] += delta;
        }
        let moved = reference(model, (q0, v0));
        growth = growth.max(max_distance(&base, &moved) / delta);
    }
    growth
}

/// The state's size over the run, for relative tolerances: max(1, |y|).
fn scale(t: &Trajectory<f64, 2>) -> f64 {
    t.iter()
        .map(|s| s.q.amax().max(s.qdot.amax()))
        .fold(1.0, f64::max)
}

/// One end of the scale, with its reference trajectory.
struct Extreme {
    name: &'static str,
    model: DoublePendulum,
    start: (Vector2<f64>, Vector2<f64>),
    reference: Trajectory<f64, 2>,
}

impl Extreme {
    fn light() -> Self {
        Self::new("m2/m1 = 1e-6", chain(1.0, 1e-6), light_start())
    }

    fn heavy() -> Self {
        Self::new("m2/m1 = 1e6", chain(1e-6, 1.0), heavy_start())
    }

    fn new(name: &'static str, model: DoublePendulum, start: (Vector2<f64>, Vector2<f64>)) -> Self {
        let reference = reference(&model, start);
        Self {
            name,
            model,
            start,
            reference,
        }
    }

    fn run<I: Integrator<f64>>(&self, method: &I) -> IntegrationResult<f64, 2> {
        let (q0, v0) = self.start;
        method.integrate(&self.model, 0.0, q0, v0, &sample_times())
    }

    /// A method's largest error against the reference over the samples,
    /// and its work; every sample finite.
    fn error_of<I: Integrator<f64>>(&self, method: &I) -> (f64, Stats) {
        let run = self
            .run(method)
            .unwrap_or_else(|failure| panic!("{}: {failure}", self.name));
        assert!(
            run.iter()
                .all(|s| s.q.iter().chain(s.qdot.iter()).all(|x| x.is_finite()))
        );
        (max_distance(&run, &self.reference), run.stats())
    }

    fn report(&self, method: &str, error: f64, bound: f64, stats: Stats) {
        println!(
            "{}: {method:<26} error {error:.2e} (bound {bound:.1e}), {} steps, {} rhs, {} rejected",
            self.name, stats.steps_accepted, stats.rhs_evals, stats.steps_rejected
        );
        assert!(
            error <= bound,
            "{} {method}: {error:e} > {bound:e}",
            self.name
        );
    }
}

/// The adaptive methods at tol = 1e-8 on both extremes, against the
/// reference: finite, and within the tolerance's reach. Dormand–Prince
/// keeps the global error within `C tol · growth · scale` (`C = 100`, as in
/// the reference tests; growth is the flow's perturbation growth, measured:
/// ~30 for the light bob, ~2300 for the heavy one, whose kink vibration
/// turns a 1e-7 displacement into a velocity of ω_k · 1e-7). Radau5 is
/// measured against `rtol^(5/6)`, its documented global error law.
///
/// The heavy extreme is stiff: the explicit methods' steps are set by the
/// kink, Radau5 at 1e-8 must resolve the kink's 1e-6 amplitude too, and
/// only at a tolerance above that amplitude (1e-4) does it step over it,
/// in ~40 steps.
#[test]
fn adaptive_methods_meet_their_tolerance_at_both_extremes() {
    for extreme in [Extreme::light(), Extreme::heavy()] {
        let growth = perturbation_growth(&extreme.model, extreme.start);
        let scale = scale(&extreme.reference);
        println!(
            "{}: perturbation growth {growth:.2e}, state scale {scale:.1}",
            extreme.name
        );
        let tol: f64 = 1e-8;
        let bound = 100.0 * tol * growth * scale;
        let (error, stats) = extreme.error_of(&Dopri5::new().rtol(tol).atol(tol));
        extreme.report("Dopri5 1e-8", error, bound, stats);
        let (error, stats) = extreme.error_of(&Dop853::new().rtol(tol).atol(tol));
        extreme.report("Dop853 1e-8", error, bound, stats);
        for tol in [1e-8, 1e-4] {
            let bound = 100.0 * f64::powf(tol, 5.0 / 6.0) * growth * scale;
            let (error, stats) = extreme.error_of(&Radau5::new().rtol(tol).atol(tol));
            extreme.report(&format!("Radau5 {tol:.0e}"), error, bound, stats);
        }
    }
}

/// Fixed-step error estimated by Richardson extrapolation from the same
/// method at `h` and `h/2`: for order `p` the error at `h` is
/// `≈ 2^p/(2^p − 1) · |y_h − y_{h/2}|` once `h` is in the asymptotic range.
/// The measured error must be within 2× that estimate (plus the round-off
/// of `n` steps, `n · 10 ε · scale`): the method behaves at its order even
/// with `cond(M) ~ 10⁶`.
fn assert_at_its_order<I: Integrator<f64>>(
    extreme: &Extreme,
    (name, order): (&str, i32),
    make: impl Fn(f64) -> I,
    h: f64,
) {
    let (coarse, fine) = match (extreme.run(&make(h)), extreme.run(&make(h / 2.0))) {
        (Ok(c), Ok(f)) => (c, f),
        (c, f) => panic!(
            "{} {name}: {:?} / {:?}",
            extreme.name,
            c.err().map(|e| e.to_string()),
            f.err().map(|e| e.to_string())
        ),
    };
    let factor = 2f64.powi(order) / (2f64.powi(order) - 1.0);
    let estimate = factor * max_distance(&coarse, &fine);
    let steps = coarse.stats().steps_accepted as f64;
    let bound = 2.0 * estimate + steps * 10.0 * f64::EPSILON * scale(&extreme.reference);
    let error = max_distance(&coarse, &extreme.reference);
    extreme.report(&format!("{name} h = {h:.0e}"), error, bound, coarse.stats());
}

/// The fixed-step methods on both extremes, at steps that resolve the
/// motion (for the heavy bob `h ω_k ≈ 0.4`): each at its order (Richardson
/// check above). The implicit ones rely on Newton's noise floor growing
/// with `κ(M)`: before it did, Gauss–Legendre and the midpoint rule called
/// the converged iteration at `t = 0` of the heavy chain divergent, and the
/// variational integrator failed from `m2/m1 = 10⁴` at any step.
#[test]
fn fixed_step_methods_keep_their_order_at_both_extremes() {
    for (extreme, h) in [(Extreme::light(), 2e-3), (Extreme::heavy(), 1e-4)] {
        assert_at_its_order(&extreme, ("Rk4", 4), Rk4::new, h);
        assert_at_its_order(
            &extreme,
            ("GaussLegendre 2", 4),
            GaussLegendre::two_stage,
            h,
        );
        assert_at_its_order(&extreme, ("ImplicitMidpoint", 2), ImplicitMidpoint::new, h);
        assert_at_its_order(&extreme, ("Variational", 2), Variational::new, h);
    }
}

/// The heavy chain's kink makes `h = 1e-3` (`h ω_k ≈ 4.1`) too long for
/// RK4, whose stability interval on the imaginary axis ends at 2.83: the
/// kink, 1e-6 of the state at first, grows ~9× per step, overtakes the
/// swing after a few steps and then blows up faster than geometrically.
/// That must end in the typed `Unstable` error, at a finite state, within
/// the first hundredth of a second, not in an overflowing forcing (what it
/// was before the growth guard judged the total growth of a run of steps).
/// The A-stable implicit methods step over the kink at the same `h` and
/// stay within a few kink amplitudes (`~m1/m2`) plus their truncation of
/// the swing of the reference.
#[test]
fn a_step_beyond_the_kink_vibrations_stability_limit_is_unstable_for_rk4_only() {
    let extreme = Extreme::heavy();
    let failure = extreme.run(&Rk4::new(1e-3)).unwrap_err();
    let IntegrationError::Unstable {
        t, steps, q, qdot, ..
    } = failure.error
    else {
        panic!("expected Unstable, got {}", failure.error);
    };
    println!(
        "m2/m1 = 1e6: Rk4 h = 1e-3 stops Unstable at t = {t} after {steps} growing steps, \
         |y| = {:.1e}",
        q.amax().max(qdot.amax())
    );
    assert!(t < 0.01, "caught late: t = {t}");
    assert!(q.iter().chain(qdot.iter()).all(|x| x.is_finite()));

    for (name, run) in [
        (
            "GaussLegendre 2 h = 1e-3",
            extreme.run(&GaussLegendre::two_stage(1e-3)),
        ),
        (
            "ImplicitMidpoint h = 1e-3",
            extreme.run(&ImplicitMidpoint::new(1e-3)),
        ),
    ] {
        let run = run.unwrap_or_else(|f| panic!("{name}: {f}"));
        // The swing's truncation: midpoint (h ω_swing)² / 24 per unit of
        // phase over ~5 swings of ω ≈ 2.2, well below 1e-3; the kink's
        // unresolved phase errs by at most its amplitude, ~1e-6.
        let error = run
            .positions()
            .iter()
            .zip(extreme.reference.positions())
            .map(|(a, b)| (a - b).amax())
            .fold(0.0, f64::max);
        let stats = run.stats();
        println!(
            "m2/m1 = 1e6: {name}: max angle error {error:.2e}, {} Newton iterations in {} steps",
            stats.newton_iterations, stats.steps_accepted
        );
        assert!(error < 1e-3, "{name}: {error:e}");
    }
}
