//! The midpoint variational integrator: second order, the momentum of a
//! symmetry kept to round-off (discrete Noether), energy without drift,
//! forces at the right rate, and its failures typed.

use crate::models::{CoupledOscillator, DrivenOscillator, ExponentialWell, Without};
use lagrange::models::{Kepler, Oscillator, Pendulum, PolarKepler};
use lagrange_runtime::InvalidInput;
use lagrange_runtime::nalgebra::{Vector1, Vector2};
use lagrange_runtime::prelude::*;

const EPS: f64 = f64::EPSILON;

fn pendulum() -> Pendulum {
    Pendulum::new(1.0, 1.0, 9.81)
}

/// Every 0.5 up to t = 10.
fn every_half_second() -> Vec<f64> {
    (1..=20).map(|i| 0.5 * i as f64).collect()
}

/// Largest difference in `q` or `q̇` between two trajectories at the same
/// sample times.
fn max_gap<const N: usize>(a: &Trajectory<f64, N>, b: &Trajectory<f64, N>) -> f64 {
    assert_eq!(a.times(), b.times());
    a.iter().zip(b).fold(0.0, |worst, (a, b)| {
        worst.max((a.q - b.q).amax()).max((a.qdot - b.qdot).amax())
    })
}

/// An orbit of eccentricity 0.6 (semi-major axis 1, period 2π), from
/// perihelion r = 0.4 with speed √(μ (1 + e) / r) = 2.
const PERIHELION: f64 = 0.4;
const PERIHELION_SPEED: f64 = 2.0;

/// 160 orbits, sampled every 0.25 (5 steps of 0.05).
fn long_run() -> Vec<f64> {
    (1..=4000).map(|i| 0.25 * i as f64).collect()
}

#[test]
fn variational_pendulum_error_falls_as_h_squared() {
    let model = pendulum();
    let (q0, qdot0) = (Vector1::new(1.0), Vector1::new(0.0));
    let times = every_half_second();
    let reference = Dopri5::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    let errors: Vec<f64> = [0.02, 0.01, 0.005, 0.0025]
        .iter()
        .map(|&h| {
            let trajectory = Variational::new(h)
                .integrate(&model, 0.0, q0, qdot0, &times)
                .unwrap();
            max_gap(&trajectory, &reference)
        })
        .collect();
    for pair in errors.windows(2) {
        let order = (pair[0] / pair[1]).log2();
        // The midpoint rule is symmetric, so its global error is C h² + O(h⁴)
        // and the observed order is 2 to within (h/T)² ≪ 0.2; the reference
        // (~1e-10) is far below the smallest error (~3e-4). ±0.2 rejects a
        // first-order slip (a wrong t̄, or p_{k+1} from the wrong end) and a
        // method that is secretly higher order.
        assert!(
            (order - 2.0).abs() < 0.2,
            "observed order {order}, errors {errors:?}"
        );
    }
}

#[test]
fn variational_takes_one_jacobian_and_two_or_three_iterations_per_step() {
    let (q0, qdot0) = (Vector1::new(1.0), Vector1::new(0.0));
    let trajectory = Variational::new(0.01)
        .integrate(&pendulum(), 0.0, q0, qdot0, &every_half_second())
        .unwrap();
    let stats = trajectory.stats();
    assert_eq!(stats.steps_accepted, 1000);
    // The extrapolated predictor is O(h²) off, ~1e-3 relative. The chord
    // iteration contracts by the relative error of its Jacobian: √ε ≈ 1e-8
    // from the differences (r is linear in v̄ but for O(h²) terms), plus the
    // O(h³) change of ∂r/∂v̄ between predictor and solution. So the first
    // correction leaves ~1e-11, and the ratio of the second to the first
    // shows the rest is below 10 ε: no refresh, two iterations per step,
    // three at most where the predictor is poor.
    assert_eq!(stats.jacobian_evals, stats.steps_accepted);
    assert_eq!(stats.linear_solves, stats.newton_iterations);
    assert!(
        stats.newton_iterations <= 3 * stats.steps_accepted,
        "{stats:?}"
    );
    // Per step: the predictor, N = 1 difference for the Jacobian, one per
    // iteration; plus p₀ and q̇ at each of the 20 samples.
    let per_step = 2 * stats.steps_accepted + stats.newton_iterations;
    assert_eq!(stats.rhs_evals, per_step + 1 + 20);
}

#[test]
fn variational_lands_on_sample_times_between_steps() {
    let model = pendulum();
    let (q0, qdot0) = (Vector1::new(1.0), Vector1::new(0.0));
    let h = 0.01;
    let uneven = [0.255, 0.3, 1.0];
    let trajectory = Variational::new(h)
        .integrate(&model, 0.0, q0, qdot0, &uneven)
        .unwrap();
    assert_eq!(trajectory.times(), &uneven);
    // 26 steps of 0.0098, 5 of 0.009, 70 of 0.01.
    assert_eq!(trajectory.stats().steps_accepted, 26 + 5 + 70);

    let even = Variational::new(h)
        .integrate(&model, 0.0, q0, qdot0, &[1.0])
        .unwrap();
    let reference = Dopri5::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&model, 0.0, q0, qdot0, &[1.0])
        .unwrap();
    let error = |trajectory: &Trajectory<f64, 1>| {
        let (s, r) = (trajectory.last().unwrap(), reference.last().unwrap());
        (s.q - r.q).amax().max((s.qdot - r.qdot).amax())
    };
    // Steps of 0.9 h to h have the same O(h²) error constant as steps of h,
    // up to (0.9)², so the errors at t = 1 agree within a factor 2; a
    // shortened step handled to first order only would be O(h) ≈ 100× off.
    let (uneven_error, even_error) = (error(&trajectory), error(&even));
    assert!(
        uneven_error < 2.0 * even_error,
        "{uneven_error:e} vs {even_error:e}"
    );
}

#[test]
fn polar_kepler_angular_momentum_is_kept_bit_for_bit_by_variational() {
    let model = PolarKepler::new(1.0);
    let q0 = Vector2::new(PERIHELION, 0.0);
    let qdot0 = Vector2::new(0.0, PERIHELION_SPEED / PERIHELION);
    let l0 = PolarKepler::angular_momentum(&q0, &qdot0);
    let drift = |trajectory: &Trajectory<f64, 2>| {
        trajectory.iter().fold(0.0, |worst: f64, s| {
            worst.max((PolarKepler::angular_momentum(&s.q, &s.qdot) - l0).abs() / l0)
        })
    };

    let h = 0.05;
    let variational = Variational::new(h)
        .integrate(&model, 0.0, q0, qdot0, &long_run())
        .unwrap();
    assert_eq!(variational.stats().steps_accepted, 20_000);
    // φ is cyclic, so p_{k+1} = p_k + h (∂L/∂q + Q) never changes p_φ: the
    // integrator carries it exactly over all 20 000 steps. What rounding is
    // left comes from the boundaries only, once per sample and not
    // accumulating: q̇ = M⁻¹ p (a Cholesky solve of diag(m, m r²): a square
    // root, whose error counts twice as it is squared, and two divisions)
    // and back m r² φ̇ here (three products), each within ε/2: 3.5 ε in all.
    let kept = drift(&variational);
    assert!(kept <= 4.0 * EPS, "relative drift {kept:e}");

    // RK4 at the same step conserves it only to its truncation error.
    let rk4 = Rk4::new(h)
        .integrate(&model, 0.0, q0, qdot0, &long_run())
        .unwrap();
    assert!(drift(&rk4) > 1e6 * EPS, "RK4 drift {:e}", drift(&rk4));
}

#[test]
fn cartesian_kepler_angular_momentum_is_conserved_to_round_off_by_variational() {
    // No coordinate is cyclic here: x p_y − y p_x is conserved because L, and
    // with it L_d (midpoint and difference quotient rotate like q and q̇),
    // is invariant under rotations: the discrete Noether theorem.
    let model = Kepler::new(1.0);
    let q0 = Vector2::new(PERIHELION, 0.0);
    let qdot0 = Vector2::new(0.0, PERIHELION_SPEED);
    let l0 = Kepler::angular_momentum(&q0, &qdot0);
    let drift = |trajectory: &Trajectory<f64, 2>| {
        trajectory.iter().fold(0.0, |worst: f64, s| {
            worst.max((Kepler::angular_momentum(&s.q, &s.qdot) - l0).abs() / l0)
        })
    };

    let h = 0.05;
    let variational = Variational::new(h)
        .integrate(&model, 0.0, q0, qdot0, &long_run())
        .unwrap();
    let steps = variational.stats().steps_accepted as f64;
    // Each step leaves a few ε of rounding in q × p and at most 10 ε of
    // Newton tolerance in v̄. Those errors have no preferred sign, so they
    // add up like a random walk, a few √K ε ≈ 500 ε after K = 20 000 steps;
    // K ε allows 40× that, and is still 10⁸ times below RK4's drift.
    let kept = drift(&variational);
    assert!(
        kept <= steps * EPS,
        "relative drift {kept:e} over {steps} steps"
    );

    let rk4 = Rk4::new(h)
        .integrate(&model, 0.0, q0, qdot0, &long_run())
        .unwrap();
    assert!(
        drift(&rk4) > 1e3 * steps * EPS,
        "RK4 drift {:e}",
        drift(&rk4)
    );
}

/// `(slope, largest |E − E₀|)` of the energy error along a trajectory, the
/// slope by least squares.
fn energy_trend(model: &PolarKepler, trajectory: &Trajectory<f64, 2>) -> (f64, f64) {
    let (q0, qdot0) = (
        Vector2::new(PERIHELION, 0.0),
        Vector2::new(0.0, PERIHELION_SPEED / PERIHELION),
    );
    let e0 = model.energy(0.0, &q0, &qdot0);
    let errors: Vec<f64> = trajectory
        .iter()
        .map(|s| model.energy(s.t, &s.q, &s.qdot) - e0)
        .collect();
    let n = errors.len() as f64;
    let t_mean = trajectory.times().iter().sum::<f64>() / n;
    let e_mean = errors.iter().sum::<f64>() / n;
    let (mut covariance, mut variance) = (0.0, 0.0);
    for (t, e) in trajectory.times().iter().zip(&errors) {
        covariance += (t - t_mean) * (e - e_mean);
        variance += (t - t_mean) * (t - t_mean);
    }
    let largest = errors.iter().fold(0.0, |worst: f64, e| worst.max(e.abs()));
    (covariance / variance, largest)
}

#[test]
fn polar_kepler_energy_has_no_drift_with_variational_but_drifts_with_rk4() {
    // M = diag(m, m r²) depends on q, so this is not the constant-mass case
    // where many methods happen to behave.
    let model = PolarKepler::new(1.0);
    let q0 = Vector2::new(PERIHELION, 0.0);
    let qdot0 = Vector2::new(0.0, PERIHELION_SPEED / PERIHELION);
    let times = long_run();
    let span = times[times.len() - 1];
    let orbits = span / std::f64::consts::TAU;

    let h = 0.05;
    let variational = Variational::new(h)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    let (slope, largest) = energy_trend(&model, &variational);
    // A symplectic method's energy error is bounded: it oscillates with
    // the orbit (whose period the method shifts by O(h²)), within A. The
    // least-squares slope of any function periodic with period P and bounded
    // by A, fitted over n periods, is at most 6 A / (n² P) (the numerator
    // ∫ (t − t̄) s dt is n ∫₀ᴾ τ s̃ dτ ≤ n A P² / 2, the denominator
    // (nP)³ / 12), so the fitted drift over the run, slope · n P, is at most
    // 6 A / n ≈ 0.04 A for these 160 orbits. A secular drift shows a fitted
    // drift comparable to the largest error itself.
    let bound = 6.0 * largest / orbits;
    assert!(
        (slope * span).abs() <= bound,
        "drift {:e} over the run, largest error {largest:e}",
        slope * span
    );

    // RK4's error at the same step is all drift: it fails the same test by
    // far (measured: drift ≈ the largest error).
    let rk4 = Rk4::new(h)
        .integrate(&model, 0.0, q0, qdot0, &times)
        .unwrap();
    let (slope, largest) = energy_trend(&model, &rk4);
    assert!(
        (slope * span).abs() > 0.5 * largest,
        "RK4 drift {:e} over the run, largest error {largest:e}",
        slope * span
    );
}

#[test]
fn damped_oscillator_energy_decays_at_the_exact_rate_to_second_order() {
    // ζ = c / (2 √(m k)) = 0.1: the energy falls by 50× over t = 10.
    let model = Oscillator::new(1.0, 4.0, 0.4);
    let (x0, v0) = (1.0, 0.0);
    let times = every_half_second();
    let errors: Vec<f64> = [0.1, 0.05, 0.025, 0.0125]
        .iter()
        .map(|&h| {
            let trajectory = Variational::new(h)
                .integrate(&model, 0.0, Vector1::new(x0), Vector1::new(v0), &times)
                .unwrap();
            trajectory.iter().fold(0.0, |worst: f64, s| {
                let (x, v) = model.exact(s.t, x0, v0);
                let exact = model.energy(s.t, &Vector1::new(x), &Vector1::new(v));
                worst.max((model.energy(s.t, &s.q, &s.qdot) - exact).abs())
            })
        })
        .collect();
    for pair in errors.windows(2) {
        // The forces enter at the midpoint, symmetric like the rest, so the
        // energy error is C h² + O(h⁴); a force impulse taken at one end of
        // the step (h Q(q_k, q̇_k)) would make it O(h) and fail by 1.
        let order = (pair[0] / pair[1]).log2();
        assert!(
            (order - 2.0).abs() < 0.2,
            "observed order {order}, errors {errors:?}"
        );
    }
}

#[test]
fn driven_oscillator_with_time_dependent_lagrangian_is_second_order() {
    let model = DrivenOscillator {
        force: 1.0,
        omega: 2.0,
    };
    let times = every_half_second();
    let errors: Vec<f64> = [0.05, 0.025, 0.0125]
        .iter()
        .map(|&h| {
            let trajectory = Variational::new(h)
                .integrate(&model, 0.0, Vector1::zeros(), Vector1::zeros(), &times)
                .unwrap();
            trajectory.iter().fold(0.0, |worst: f64, s| {
                let (x, v) = model.exact(s.t);
                worst.max((s.q[0] - x).abs()).max((s.qdot[0] - v).abs())
            })
        })
        .collect();
    for pair in errors.windows(2) {
        // L depends on t, evaluated at t̄ = t_k + h/2 like q̄ and v̄: the
        // scheme stays symmetric and second order (C h² + O(h⁴)). L at t_k
        // instead would be an O(h) error in the drive, order 1.
        let order = (pair[0] / pair[1]).log2();
        assert!(
            (order - 2.0).abs() < 0.2,
            "observed order {order}, errors {errors:?}"
        );
    }
}

#[test]
fn model_without_variational_methods_is_refused_before_any_work() {
    let refused = |result: lagrange_runtime::IntegrationResult<f64, 1>| {
        let failure = result.unwrap_err();
        assert!(failure.trajectory.is_empty());
        assert_eq!(failure.trajectory.stats().rhs_evals, 0);
        match failure.error {
            IntegrationError::InvalidInput(InvalidInput::ModelLacks { method, needs }) => {
                assert_eq!(method, "Variational");
                needs
            }
            other => panic!("expected ModelLacks, got {other}"),
        }
    };
    let (q0, qdot0) = (Vector1::new(1.0), Vector1::new(0.0));
    let without = |momentum, gradient, forces| Without {
        inner: pendulum(),
        lacks_momentum: momentum,
        lacks_gradient: gradient,
        lacks_forces: forces,
    };
    let variational = Variational::new(0.01);
    // A sample at t0 too: refused even though that one needs no step.
    let times = [0.0, 1.0];
    for (model, needs) in [
        (without(true, true, true), "momentum"),
        (without(false, true, false), "lagrangian_gradient"),
        (without(false, false, true), "nonconservative_forces"),
    ] {
        assert_eq!(
            refused(variational.integrate(&model, 0.0, q0, qdot0, &times)),
            needs
        );
    }
    // The message says which method, and what is missing.
    let coupled = CoupledOscillator { omega: 2.0 };
    let failure = variational
        .integrate(
            &coupled,
            0.0,
            Vector2::new(1.0, 0.0),
            Vector2::zeros(),
            &times,
        )
        .unwrap_err();
    assert_eq!(
        failure.to_string(),
        "invalid input: Variational needs `Lagrangian::momentum`, which this model does not \
         provide (0 samples kept)"
    );
}

#[test]
fn absurd_step_is_newton_divergence_with_the_samples_before() {
    // q̈ = e^q from rest, q = −2 ln cos(t/√2). The first two intervals are
    // 0.1 long and go through; the last is one step of 4.8, for which the
    // discrete equation has no solution at all:
    // r(v) ≥ p + (2/h)(1 + ln(h²/4) + q) ≈ 1.35 > 0.
    let variational = Variational::new(10.0);
    let times = [0.1, 0.2, 5.0];
    let failure = variational
        .integrate(
            &ExponentialWell,
            0.0,
            Vector1::zeros(),
            Vector1::zeros(),
            &times,
        )
        .unwrap_err();
    let IntegrationError::NewtonDivergence {
        t,
        h,
        iterations,
        q,
        qdot,
    } = failure.error
    else {
        panic!("expected Newton divergence, got {}", failure.error);
    };
    assert_eq!(t, 0.2);
    assert!((h - 4.8).abs() < 1e-15, "h = {h}");
    assert!((1..=10).contains(&iterations), "{iterations} iterations");
    assert_eq!(failure.trajectory.times(), &times[..2]);
    // The state reported is the last sample's, where the failing step began.
    let last = failure.trajectory.last().unwrap();
    assert_eq!((q, qdot), (last.q, last.qdot));
    // The samples before are sound: each step's midpoint impulse h e^{q̄}
    // overshoots by ~h²/4 relative, a few 1e-3 of q(0.2) ≈ 0.02.
    let exact = -2.0 * (0.2 / 2f64.sqrt()).cos().ln();
    assert!((last.q[0] - exact).abs() < 1e-4, "q(0.2) = {}", last.q[0]);
}
