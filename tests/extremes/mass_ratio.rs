//! Numerical stability at the extremes: a double pendulum whose bobs differ
//! in mass by a factor of 10⁶, either way.
//!
//! `M = [[(m1 + m2) l1², m2 l1 l2 c], [m2 l1 l2 c, m2 l2²]]` with
//! `c = cos(θ1 − θ2)` has a condition number of ~10⁶ at both extremes, for
//! different reasons:
//!
//! - **light outer bob** (`m2/m1 = 10⁻⁶`): the second row is 10⁻⁶ of the
//!   first. Nothing is stiff: the outer bob barely pulls on the inner one,
//!   which swings as a simple pendulum of length `l1` (to relative
//!   `O(m2/m1)`), while the outer one is a pendulum hanging from that moving
//!   support.
//! - **heavy outer bob** (`m2/m1 = 10⁶`): the two rows are nearly equal
//!   when the rods are aligned (`det M = m2 l1² l2² (m1 + m2 sin²(θ1 − θ2))`).
//!   The light joint has almost no inertia, so it cannot bend the chain: a
//!   kink `θ1 − θ2` is pulled straight by the tension `≈ m2 g` acting on the
//!   mass `m1`, a vibration of frequency
//!   `ω_k ≈ √(m2/m1 · g cos Θ (l1 + l2)/(l1 l2)) ≈ 4.1·10³ rad/s`, while the
//!   straight chain swings as a simple pendulum of length `l1 + l2`. The
//!   physically right limit is that pendulum (the massless chain of two rods
//!   stays straight while in tension, which it is at these amplitudes), and
//!   the model is **stiff**: explicit methods must resolve `ω_k`.
//!
//! Every test prints the figures quoted in STABILITY.md; run with
//! `cargo test --release --test extremes -- mass_ratio:: --nocapture`.

use lagrange::models::{DoublePendulum, Pendulum};
use lagrange::nalgebra::{Vector1, Vector2};
use lagrange::prelude::*;
use lagrange::solve::{pivot_ratio, solve_mass_matrix};
use lagrange::{IntegrationResult, Stats};

lagrangian! {
    /// The limit `m2/m1 → 0` of the double pendulum: `θ1` a simple pendulum
    /// of length `l1`, unaffected by the outer bob; `θ2` a pendulum of length
    /// `l2` hanging from the moving inner bob (its Euler–Lagrange equation
    /// divided by `m2`, with `θ̈1 = −(g/l1) sin θ1` substituted).
    pub struct LightOuterLimit {
        coordinates: theta1, theta2;
        parameters: l1, l2, g;
        kinetic: (dot(theta1)^2 + dot(theta2)^2)/2;
        potential: -g/l1*cos(theta1);
        forces: theta2 = (g*cos(theta1 - theta2)*sin(theta1)
                          + l1*sin(theta1 - theta2)*dot(theta1)^2 - g*sin(theta2))/l2;
    }
}

const G: f64 = 9.81;
const END: f64 = 5.0;

/// Unit rods, the given masses.
fn chain(m1: f64, m2: f64) -> DoublePendulum {
    DoublePendulum::new(m1, m2, 1.0, 1.0, G)
}

/// Light outer bob: both rods swinging, at moderate amplitude (not chaotic
/// over 5 s).
fn light_start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(0.5, 0.3), Vector2::zeros())
}

/// Heavy outer bob: released from rest with the chain straight at 0.5 rad.
fn heavy_start() -> (Vector2<f64>, Vector2<f64>) {
    (Vector2::new(0.5, 0.5), Vector2::zeros())
}

/// Samples every 0.01 s: dense enough to see the kink vibration's amplitude
/// (period 1.5 ms, sampled at unrelated phases) and every swing.
fn sample_times() -> Vec<f64> {
    (1..=500).map(|k| 0.01 * k as f64).collect()
}

/// Dop853 at 1e-13, our reference for each extreme: its error is ≈ 10 ×
/// tol × growth (README, accuracy), below 1e-8 even with the heavy chain's
/// growth of ~2300 (measured below), far below every error it judges.
fn reference(model: &DoublePendulum, start: (Vector2<f64>, Vector2<f64>)) -> Trajectory<f64, 2> {
    Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .max_steps(2_000_000)
        .integrate(model, 0.0, start.0, start.1, &sample_times())
        .expect("the reference run")
}

/// Largest state difference `max |Δq|, |Δq̇|` over all samples.
fn max_distance(a: &Trajectory<f64, 2>, b: &Trajectory<f64, 2>) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b.iter())
        .map(|(x, y)| (x.q - y.q).amax().max((x.qdot - y.qdot).amax()))
        .fold(0.0, f64::max)
}

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

/// A backward-stable Cholesky solve of `M x = f` has a relative error of at
/// most `c N ε κ(M)` (Higham, *Accuracy and Stability*, Thm. 10.4, with
/// `c` a small constant; 10 N here). Along both extreme trajectories the
/// 2-norm condition number reaches ~10⁶ (light: 1e6, heavy: 4e6), the
/// factorization is Cholesky (positive pivots, ratio far above the `N ε`
/// the solve refuses), and the solve meets that bound: the conditioning is
/// handled, not refused and not turned into noise.
#[test]
fn mass_matrices_with_condition_near_1e6_are_solved_to_their_conditioning() {
    for (name, model, start) in [
        ("m2/m1 = 1e-6", chain(1.0, 1e-6), light_start()),
        ("m2/m1 = 1e6", chain(1e-6, 1.0), heavy_start()),
    ] {
        let trajectory = reference(&model, start);
        let (mut worst_kappa, mut worst_ratio, mut worst_error): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for s in &trajectory {
            let m = model.mass_matrix(s.t, &s.q);
            let eigen = m.symmetric_eigenvalues();
            let kappa = eigen.max() / eigen.min();
            let pivots = pivot_ratio(&m).expect("M is positive definite: Cholesky");
            assert!(
                pivots > 1.0 && pivots < 1e-3 / f64::EPSILON,
                "{name}: pivot ratio {pivots:e} at t = {}",
                s.t
            );
            // A known answer with components along both eigenvectors.
            let expected = Vector2::new(0.3, -0.7);
            let solved = solve_mass_matrix(&m, &(m * expected)).expect("solvable");
            let error = (solved - expected).norm() / expected.norm();
            let bound = 10.0 * 2.0 * f64::EPSILON * kappa;
            assert!(
                error <= bound,
                "{name}: relative error {error:e} > {bound:e} (κ = {kappa:e}) at t = {}",
                s.t
            );
            worst_kappa = worst_kappa.max(kappa);
            worst_ratio = worst_ratio.max(pivots);
            worst_error = worst_error.max(error / (f64::EPSILON * kappa));
        }
        println!(
            "{name}: cond(M) up to {worst_kappa:.2e}, Cholesky pivot ratio up to \
             {worst_ratio:.2e}, solve error up to {worst_error:.2} κ ε (bound 20 κ ε)"
        );
        assert!(worst_kappa > 5e5, "{name}: not the conditioning we meant");
    }
}

/// `m2/m1 = 10⁻⁶`: the inner link is a simple pendulum of length `l1` and
/// the outer one a pendulum on a moving support ([`LightOuterLimit`]), up
/// to `O(μ)`, `μ = m2/(m1 + m2)`: the outer bob's reaction enters the inner
/// equation as `θ̈1 = −(g/l1) sin θ1 − μ (l2/l1)(cos Δ θ̈2 + sin Δ θ̇2²)`.
///
/// Two checks of that claim. The inner deviation is bounded by the forcing
/// it gets: a linear oscillator of frequency at least
/// `ω_min = √(g/l1 · cos θ_max)` driven by at most `μ F` drifts by at most
/// `μ F t / ω_min` (Duhamel's integral), doubled for the frequency's
/// variation along the swing. And the whole state's deviation is first
/// order in `μ`: from `μ = 10⁻⁶` to `10⁻⁵` it grows by 10 within 1 %
/// (the `O(μ²)` term is 10⁻⁵ of it; the references' errors 10⁻⁵).
#[test]
fn light_outer_bob_leaves_the_inner_link_a_simple_pendulum() {
    let (q0, v0) = light_start();
    let limit = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(
            &LightOuterLimit::new(1.0, 1.0, G),
            0.0,
            q0,
            v0,
            &sample_times(),
        )
        .unwrap();
    // The limit's θ1 is the simple pendulum of length l1 itself.
    let simple = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(
            &Pendulum::new(1.0, 1.0, G),
            0.0,
            Vector1::new(q0[0]),
            Vector1::new(v0[0]),
            &sample_times(),
        )
        .unwrap();
    for (a, b) in limit.iter().zip(simple.iter()) {
        assert!((a.q[0] - b.q[0]).abs() < 1e-10);
    }

    let deviation = |ratio: f64| {
        let model = chain(1.0, ratio);
        let run = reference(&model, (q0, v0));
        let mu = ratio / (1.0 + ratio);
        let inner = run
            .iter()
            .zip(limit.iter())
            .map(|(s, l)| (s.q[0] - l.q[0]).abs().max((s.qdot[0] - l.qdot[0]).abs()))
            .fold(0.0, f64::max);
        (mu, inner, max_distance(&run, &limit))
    };
    let (mu, inner, whole) = deviation(1e-6);
    let (mu10, _, whole10) = deviation(1e-5);

    // The forcing μ F of the inner link, along the limit motion.
    let model = LightOuterLimit::new(1.0, 1.0, G);
    let forcing = limit
        .iter()
        .map(|s| {
            let qdd = model.forcing(s.t, &s.q, &s.qdot); // M = I
            let d = s.q[0] - s.q[1];
            (d.cos() * qdd[1] + d.sin() * s.qdot[1].powi(2)).abs()
        })
        .fold(0.0, f64::max);
    let omega_min = (G * q0[0].cos()).sqrt();
    let bound = 2.0 * mu * forcing * END / omega_min;
    let linearity = (whole10 / mu10) / (whole / mu);
    println!(
        "light outer bob (m2/m1 = 1e-6): θ1 deviates from the simple pendulum by {inner:.2e} \
         = {:.2} μ (Duhamel bound {bound:.2e}); whole state {whole:.2e} = {:.2} μ; \
         deviation(1e-5)/deviation(1e-6) = {:.4} × 10",
        inner / mu,
        whole / mu,
        linearity
    );
    assert!(inner <= bound, "θ1 deviation {inner:e} > {bound:e}");
    assert!(
        (linearity - 1.0).abs() < 0.01,
        "deviation not first order in μ: {linearity}"
    );
}

/// `m2/m1 = 10⁶`: the chain stays straight and swings as a simple pendulum
/// of length `l1 + l2`. The light joint sags by an angle `~m1/m2` (its
/// weight against the tension), the chain's inertia and effective length
/// differ by relative `O(m1/m2)`, and the straight release starts a kink
/// vibration of amplitude `O(m1/m2)`; so both angles follow the pendulum to
/// `O(m1/m2)`. The angular *velocities* follow it only to `O(√(m1/m2))`:
/// the kink's frequency is `O(√(m2/m1))`, its rate amplitude the product.
/// Checked by the scaling from `m1/m2 = 10⁻⁶` to `10⁻⁵`: the angle deviation
/// grows ×10 and the velocity deviation ×√10, each within 5 % (the maxima
/// are read off samples at unrelated phases of the vibration, whose
/// frequency changes by √10 between the runs), and the angle deviation is
/// `O(1) · m1/m2` (below 10 m1/m2).
#[test]
fn heavy_outer_bob_makes_the_chain_a_pendulum_of_length_l1_plus_l2() {
    let (q0, v0) = heavy_start();
    let straight = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(
            &Pendulum::new(1.0, 2.0, G),
            0.0,
            Vector1::new(q0[0]),
            Vector1::new(v0[0]),
            &sample_times(),
        )
        .unwrap();
    let worst = |chain: &[Vector2<f64>], single: &[Vector1<f64>]| {
        chain
            .iter()
            .zip(single)
            .map(|(c, p)| (c - Vector2::repeat(p[0])).amax())
            .fold(0.0, f64::max)
    };
    let deviation = |light: f64| {
        let run = reference(&chain(light, 1.0), (q0, v0));
        let angles = worst(run.positions(), straight.positions());
        let rates = worst(run.velocities(), straight.velocities());
        let kink = run
            .positions()
            .iter()
            .map(|q| (q[0] - q[1]).abs())
            .fold(0.0, f64::max);
        (angles, rates, kink, run.stats())
    };
    let (angles, rates, kink, stats) = deviation(1e-6);
    let (angles10, rates10, _, _) = deviation(1e-5);
    let angle_scaling = angles10 / angles / 10.0;
    let rate_scaling = rates10 / rates / 10f64.sqrt();
    println!(
        "heavy outer bob (m2/m1 = 1e6): angles deviate from the pendulum of length l1 + l2 by \
         {angles:.2e} = {:.2} m1/m2 (kink up to {kink:.1e}), rates by {rates:.2e} = {:.2} \
         √(m1/m2); from m1/m2 = 1e-6 to 1e-5 they grow {angle_scaling:.3} × 10 and \
         {rate_scaling:.3} × √10; the reference needed {} steps ({} rejected) for 5 s",
        angles / 1e-6,
        rates / 1e-3,
        stats.steps_accepted,
        stats.steps_rejected
    );
    assert!(
        (angle_scaling - 1.0).abs() < 0.05,
        "angle deviation not first order in m1/m2: {angle_scaling}"
    );
    assert!(
        (rate_scaling - 1.0).abs() < 0.05,
        "rate deviation not of order √(m1/m2): {rate_scaling}"
    );
    assert!(angles < 10.0 * 1e-6, "angle deviation {angles:e}");
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
        assert!(run
            .iter()
            .all(|s| s.q.iter().chain(s.qdot.iter()).all(|x| x.is_finite())));
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
