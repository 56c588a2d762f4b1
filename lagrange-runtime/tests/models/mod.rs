//! Hand-written models of the runtime's tests, each chosen for a known
//! exact solution, a hand-derived Jacobian or a known way of breaking, and
//! written without the macro where that is the point. Problems that are
//! only needed as such (Kepler, the pendulums, the damped oscillator) are
//! the shared ones of `lagrange::models`.
#![allow(dead_code)]

mod breaking;
mod cart_pole;
mod constrained;
mod contact;
mod elastic_pendulum;
mod light_joint;
mod oscillators;
mod stiff_chain;
mod without;

pub use breaking::{BlowUp, ExponentialWell, ForcingBreaksDown, InertiaVanishes};
pub use cart_pole::CartPole;
pub use constrained::{CartesianPendulum, ParallelAtOne, VanishingGradient};
pub use contact::{Ladder, OnSphere, STOP};
pub use elastic_pendulum::ElasticPendulum;
pub use light_joint::LightJoint;
pub use oscillators::{CoupledOscillator, DrivenOscillator};
pub use stiff_chain::StiffChain;
pub use without::Without;

use lagrange::Method;
use lagrange_runtime::nalgebra::{RealField, SVector, Vector2};
use lagrange_runtime::{IntegrationError, Integrator};

/// The stages `s` of a Gauss method (order `2s`): the right-hand sides each
/// Newton iteration evaluates.
pub fn stages(method: Method) -> usize {
    assert!(
        Method::GAUSS.contains(&method),
        "{method:?} is no Gauss method"
    );
    method.order() / 2
}

/// Largest `|state - exact|` (max norm over `q` and `q̇`) over a trajectory of
/// the coupled oscillator started at `(q0, q̇0)` at `t = 0`.
pub fn max_error<S: RealField + Copy>(
    model: &CoupledOscillator<S>,
    trajectory: &lagrange_runtime::Trajectory<S, 2>,
    q0: SVector<S, 2>,
    qdot0: SVector<S, 2>,
) -> S {
    trajectory.iter().fold(S::zero(), |worst, s| {
        let (q, qdot) = model.exact(s.t, q0, qdot0);
        worst.max((s.q - q).amax()).max((s.qdot - qdot).amax())
    })
}

/// Largest `|a - b|` (max norm over `q` and `q̇`) between two trajectories
/// sampled at the same times.
pub fn max_difference<const N: usize>(
    a: &lagrange_runtime::Trajectory<f64, N>,
    b: &lagrange_runtime::Trajectory<f64, N>,
) -> f64 {
    assert_eq!(a.times(), b.times());
    a.iter().zip(b).fold(0.0, |worst, (a, b)| {
        worst.max((a.q - b.q).amax()).max((a.qdot - b.qdot).amax())
    })
}

/// Least-squares slope of `log error` against `log h`: the observed order
/// of convergence over all the step sizes at once.
pub fn observed_order(hs: &[f64], errors: &[f64]) -> f64 {
    let (x, y): (Vec<f64>, Vec<f64>) = hs.iter().zip(errors).map(|(h, e)| (h.ln(), e.ln())).unzip();
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = x.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// An adaptive method, `with_budget(budget)`, on the coupled oscillator
/// (`ω = 2`, samples at 0.1 … 0.4 and 100): `TooManySteps` stating the
/// budget, after exactly that many attempts, keeping exactly the samples
/// those steps passed.
pub fn assert_exhausted_budget_keeps_the_samples<I: Integrator<f64>>(
    budget: usize,
    with_budget: impl Fn(usize) -> I,
) {
    let model = CoupledOscillator { omega: 2.0 };
    let (q0, qdot0) = (Vector2::new(1.0, 0.0), Vector2::zeros());
    let times = [0.1, 0.2, 0.3, 0.4, 100.0];
    let failure = with_budget(budget)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap_err();
    let IntegrationError::TooManySteps { t, max_steps, .. } = failure.error else {
        panic!("expected too many steps, got {}", failure.error);
    };
    let stats = failure.trajectory.stats();
    assert_eq!(max_steps, budget);
    assert_eq!(stats.steps_accepted + stats.steps_rejected, budget);
    let kept = failure.trajectory.times();
    assert!(!kept.is_empty() && kept.len() < times.len());
    assert!(kept.iter().all(|&s| s <= t) && times[kept.len()] > t);
}
