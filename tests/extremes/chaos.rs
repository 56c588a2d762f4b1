//! Chaos: the double pendulum at high energy, where any error grows like
//! `e^{λt}`.
//!
//! Within a few Lyapunov times a tight run can still be checked state by
//! state against the 25-digit reference (`tests/data/double_pendulum.json`);
//! beyond, no float64 run can follow the true motion, and only conserved
//! quantities are left to check. In between, how long a run stays within a
//! given distance of the truth (its agreement horizon) grows only
//! logarithmically with the tolerance: `ln(100)/λ` per 100× tighter.
//! Figures: `cargo test --release --test suite -- extremes::chaos:: --nocapture`.

use crate::support::fit::slope;
use crate::support::reference::Reference;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

/// The largest Lyapunov exponent, as the least-squares slope of
/// `ln(growth)` against `t` over the reference's samples (through the
/// origin would force growth 1 at t = 0; a free intercept absorbs the
/// transient before perturbations align with the unstable direction).
fn lyapunov_exponent(r: &Reference) -> f64 {
    let (t, growth): (Vec<f64>, Vec<f64>) = r.samples.iter().map(|s| (s.t, s.growth.ln())).unzip();
    slope(&t, &growth)
}

type Run = Trajectory<f64, 2>;
type State = lagrange::Sample<f64, 2>;

/// Largest `|Δq|`, `|Δq̇|` component between two states.
fn distance(a: &State, b: &State) -> f64 {
    (a.q - b.q).amax().max((a.qdot - b.qdot).amax())
}

/// The distance that ends agreement: 1 % of a state whose angles and rates
/// are of order one to ten, where the two motions are still recognisably
/// the same but about to part (at `λ ≈ 2 /s` a 1e-2 gap reaches O(1) within
/// about two seconds).
const AGREEMENT: f64 = 1e-2;

/// The horizon window and its sampling: every 0.01 s to 15 s, past the
/// tightest horizon measured (≈ 14 s at 1e-12).
const END: f64 = 15.0;
const DT: f64 = 0.01;

fn dense_times() -> Vec<f64> {
    (1..=(END / DT).round() as usize)
        .map(|i| i as f64 * DT)
        .collect()
}

fn dop853(tol: f64) -> Dop853<f64> {
    Dop853::new().rtol(tol).atol(tol).max_steps(1_000_000)
}

fn dopri5(tol: f64) -> Dopri5<f64> {
    Dopri5::new().rtol(tol).atol(tol).max_steps(1_000_000)
}

fn solve<I: Integrator<f64>>(r: &Reference, method: &I, times: &[f64]) -> Run {
    method
        .integrate(&r.double_pendulum_model(), 0.0, r.q0, r.qdot0, times)
        .unwrap()
}

/// The stand-in for the truth between and beyond the reference samples:
/// Dop853 at 1e-13, checked against the reference in
/// [`tight_dop853_follows_the_reference_while_chaos_allows_and_keeps_energy_after`].
const TRUTH_TOL: f64 = 1e-13;

/// The first sample time at which `run` is more than [`AGREEMENT`] from
/// `truth` (both on [`dense_times`]), or `None` if it never is.
fn horizon(run: &Run, truth: &Run) -> Option<f64> {
    run.iter()
        .zip(truth.iter())
        .find(|(a, b)| distance(a, b) > AGREEMENT)
        .map(|(a, _)| a.t)
}

/// The state's size: `max(1, |q|, |q̇|)`.
fn scale(s: &State) -> f64 {
    1f64.max(s.q.amax()).max(s.qdot.amax())
}

/// The reference check, where chaos allows one. Dop853 with per-step error
/// control makes local errors of about `tol · scale`; the flow amplifies
/// them by at most the reference's `perturbation_growth`, so the state
/// error is within `100 · tol · growth · scale` (the factor 100 as in
/// `tests/trajectories/reference_trajectories.rs`: ten times the ≈ 9× that error-per-step
/// control measures on a smooth problem). A sample is checked state by state
/// only where that bound is below [`AGREEMENT`]: beyond it the bound says
/// no more than chaos does (at t = 10, growth 1.1e9, it is ≈ 0.1).
///
/// Energy is checked at every sample: it is conserved, so its error is the
/// sum of each step's energy error, not amplified by the flow (see
/// [`energy_bound`]).
#[test]
fn tight_dop853_follows_the_reference_while_chaos_allows_and_keeps_energy_after() {
    let r = Reference::double_pendulum();
    let times: Vec<f64> = r.samples.iter().map(|s| s.t).collect();
    let run = solve(&r, &dop853(TRUTH_TOL), &times);
    let model = r.double_pendulum_model::<f64>();
    let lambda = lyapunov_exponent(&r);
    let gradient = energy_gradient_bound(&r);
    println!(
        "chaos | Lyapunov exponent from perturbation_growth {lambda:.3} /s (Lyapunov time {:.3} s) \
         | ln(100)/λ = {:.3} s | largest |∇E|₁ along the motion {gradient:.1}",
        1.0 / lambda,
        100f64.ln() / lambda
    );
    let mut state_checked = 0;
    for (got, s) in run.iter().zip(&r.samples) {
        let want = State {
            t: s.t,
            q: s.q,
            qdot: s.qdot,
        };
        let error = distance(&got, &want);
        let bound = 100.0 * TRUTH_TOL * s.growth * scale(&want);
        let energy_error = (model.energy(got.t, &got.q, &got.qdot) - s.energy).abs();
        let e_bound = energy_bound(TRUTH_TOL, gradient);
        let checked = bound < AGREEMENT;
        println!(
            "chaos | Dop853 {TRUTH_TOL:e} vs reference | t {:>4} | growth {:.2e} | state error {error:.2e} \
             | bound {bound:.2e} ({}) | energy error {energy_error:.2e} (bound {e_bound:.2e})",
            s.t,
            s.growth,
            if checked { "checked" } else { "energy only" }
        );
        if checked {
            state_checked += 1;
            assert!(
                error <= bound,
                "t = {}: state error {error:.2e} > {bound:.2e}",
                s.t
            );
        }
        assert!(
            energy_error <= e_bound,
            "t = {}: energy error {energy_error:.2e} > {e_bound:.2e}",
            s.t
        );
    }
    // The reference has samples where the bound means something (t ≤ 5) and
    // one where only energy does (t = 10).
    assert_eq!(
        state_checked, 4,
        "the split between state and energy checks moved"
    );
}

/// The energy error bound of a run at tolerance `tol`, to any time up to
/// [`END`]. The energy is conserved, so
/// `E(y_N) − E(y_0) = Σ [E(y_{n+1}) − E(φ_h(y_n))]`: the local errors
/// dotted with `∇E`, with no amplification by the flow, chaotic or not.
/// Their sum is what the global error of a non-expanding flow adds up to,
/// and error-per-step control keeps that within `C tol · scale` with
/// `C = 100` (`tests/trajectories/reference_trajectories.rs`: ten times the ≈ 9×
/// measured on smooth problems). Each component counts with its weight
/// `|∂E/∂yᵢ|` (measured along the motion, [`energy_gradient_bound`]) and
/// scale `1 + |y| ≤ 10` here: `100 · tol · 10 · |∇E|₁`. So the energy holds
/// to the tolerance level, whatever the state does.
fn energy_bound(tol: f64, gradient: f64) -> f64 {
    100.0 * tol * 10.0 * gradient
}

/// The largest `|∇E|₁ = Σ |∂E/∂qᵢ| + |∂E/∂q̇ᵢ|` along the motion (every
/// 0.01 s to 15 s, Dop853 at 1e-10), by central differences: the motion
/// keeps to its energy surface, so its `∇E` is that of any run that does.
fn energy_gradient_bound(r: &Reference) -> f64 {
    let run = solve(r, &dop853(1e-10), &dense_times());
    let d = 1e-6;
    let model = r.double_pendulum_model::<f64>();
    let e = |q: Vector2<f64>, v: Vector2<f64>| model.energy(0.0, &q, &v);
    run.iter()
        .map(|s| {
            (0..2)
                .map(|i| {
                    let dq = Vector2::ith(i, d);
                    let (eq, ev) = (
                        (e(s.q + dq, s.qdot) - e(s.q - dq, s.qdot)) / (2.0 * d),
                        (e(s.q, s.qdot + dq) - e(s.q, s.qdot - dq)) / (2.0 * d),
                    );
                    eq.abs() + ev.abs()
                })
                .sum::<f64>()
        })
        .fold(0.0, f64::max)
}

/// The truth on the dense grid: Dop853 at [`TRUTH_TOL`], and the same at a
/// tenth of it, whose gap to the truth at a horizon measures the truth's own
/// error there.
struct Truth {
    run: Run,
    tighter: Run,
}

fn truth(r: &Reference) -> Truth {
    let times = dense_times();
    Truth {
        run: solve(r, &dop853(TRUTH_TOL), &times),
        tighter: solve(r, &dop853(TRUTH_TOL / 10.0), &times),
    }
}

/// A run's agreement horizon against the truth, and the truth's own
/// uncertainty there (its gap to the tighter run at that sample).
fn horizon_and_gap(run: &Run, truth: &Truth) -> (f64, f64) {
    let t = horizon(run, &truth.run)
        .unwrap_or_else(|| panic!("agreement lasts past t = {END}: widen the window"));
    let k = (t / DT).round() as usize - 1;
    let gap = distance(&truth.run.get(k).unwrap(), &truth.tighter.get(k).unwrap());
    (t, gap)
}

/// The tolerance ladder of the horizon and energy checks: 100× apart.
const LADDER: [f64; 4] = [1e-6, 1e-8, 1e-10, 1e-12];

/// One rung: a run at `tol` on the dense grid, measured against the truth.
struct Rung {
    tol: f64,
    horizon: f64,
    /// The truth's own uncertainty at the horizon.
    gap: f64,
    steps: usize,
    /// At t = 10, the last reference sample.
    state_error_10: f64,
    energy_error_10: f64,
}

fn ladder<I: Integrator<f64>>(r: &Reference, truth: &Truth, make: impl Fn(f64) -> I) -> Vec<Rung> {
    let model = r.double_pendulum_model::<f64>();
    let ten = (10.0 / DT).round() as usize - 1;
    LADDER
        .iter()
        .map(|&tol| {
            let run = solve(r, &make(tol), &dense_times());
            let (horizon, gap) = horizon_and_gap(&run, truth);
            let at_10 = run.get(ten).unwrap();
            assert_eq!(at_10.t, 10.0);
            Rung {
                tol,
                horizon,
                gap,
                steps: run.stats().steps_accepted,
                state_error_10: distance(&at_10, &truth.run.get(ten).unwrap()),
                energy_error_10: (model.energy(at_10.t, &at_10.q, &at_10.qdot) - r.energy0).abs(),
            }
        })
        .collect()
}

/// How long a run agrees with the truth (to [`AGREEMENT`]) as its
/// tolerance tightens 100× at a time.
///
/// Expected: an error of `≈ C tol` that grows as `e^{λt}` reaches the
/// threshold at `t ≈ ln(AGREEMENT / (C tol)) / λ`, so each 100× buys
/// `ln(100)/λ` (2.26 s with λ from the reference's `perturbation_growth`),
/// never less than nothing: the horizon must not decrease.
///
/// Asserted: non-decreasing horizons, and a mean gain per 100× over the
/// ladder within a factor 2 of `ln(100)/λ`. Not each gain: λ is a
/// finite-time average over a trajectory whose stretching comes in bursts
/// (the reference's growth gives 1.5 /s over the first 5 s, 2.7 /s over the
/// next 5, a ratio of 1.8), and a method's error is not exactly
/// proportional to its tolerance at loose ones; a factor 2 covers that
/// spread. Each horizon is trusted only if the truth's own error there is
/// below a fifth of the threshold (so the crossing moves by at most
/// `ln(1.25)/λ ≈ 0.1 s`).
fn assert_horizon_grows(name: &str, rungs: &[Rung], lambda: f64) {
    let expected = 100f64.ln() / lambda;
    for rung in rungs {
        println!(
            "chaos horizon | {name:<6} | tol {:.0e} | agreement to {AGREEMENT:.0e} until t = {:.2} s \
             | truth's own error there {:.1e} | steps to {END} s {}",
            rung.tol, rung.horizon, rung.gap, rung.steps
        );
        assert!(
            rung.gap <= AGREEMENT / 5.0,
            "{name} {:.0e}: the truth is uncertain at the horizon ({:.1e})",
            rung.tol,
            rung.gap
        );
    }
    let gains: Vec<f64> = rungs
        .windows(2)
        .map(|w| w[1].horizon - w[0].horizon)
        .collect();
    let mean = (rungs[rungs.len() - 1].horizon - rungs[0].horizon) / gains.len() as f64;
    println!(
        "chaos horizon | {name:<6} | gain per 100× {} s | mean {mean:.2} s | ln(100)/λ {expected:.2} s \
         | ratio {:.2} | λ implied by the horizons {:.2} /s",
        gains
            .iter()
            .map(|g| format!("{g:.2}"))
            .collect::<Vec<_>>()
            .join(", "),
        mean / expected,
        100f64.ln() / mean
    );
    assert!(
        gains.iter().all(|&g| g >= 0.0),
        "{name}: a tighter tolerance shortened the horizon: gains {gains:?}"
    );
    assert!(
        (0.5..=2.0).contains(&(mean / expected)),
        "{name}: mean gain {mean:.2} s per 100×, expected ≈ {expected:.2} s"
    );
}

#[test]
fn dop853_agreement_horizon_grows_by_ln100_over_lambda_per_100x_tolerance() {
    let r = Reference::double_pendulum();
    let rungs = ladder(&r, &truth(&r), dop853);
    assert_horizon_grows("Dop853", &rungs, lyapunov_exponent(&r));
}

#[test]
fn dopri5_agreement_horizon_grows_by_ln100_over_lambda_per_100x_tolerance() {
    let r = Reference::double_pendulum();
    let rungs = ladder(&r, &truth(&r), dopri5);
    assert_horizon_grows("Dopri5", &rungs, lyapunov_exponent(&r));
}

/// Past the horizon the state is lost, but the energy is not: at t = 10 the
/// runs at 1e-6 to 1e-10 are past their horizons, up to O(1) away from the
/// truth, while their energy error stays
/// at the tolerance level, within [`energy_bound`] (no chaotic
/// amplification: a conserved quantity only accumulates each step's error).
/// Printed in units of `tol · |E|`.
#[test]
fn energy_holds_to_the_tolerance_at_t10_even_past_the_agreement_horizon() {
    let r = Reference::double_pendulum();
    let truth = truth(&r);
    let gradient = energy_gradient_bound(&r);
    let methods: [(&str, Vec<Rung>); 2] = [
        ("Dop853", ladder(&r, &truth, dop853)),
        ("Dopri5", ladder(&r, &truth, dopri5)),
    ];
    for (name, rungs) in &methods {
        for rung in rungs {
            let bound = energy_bound(rung.tol, gradient);
            println!(
                "chaos energy | {name:<6} | tol {:.0e} | t = 10: state error {:.1e}, energy error {:.1e} \
                 = {:.1} tol·|E| | bound {bound:.1e}",
                rung.tol,
                rung.state_error_10,
                rung.energy_error_10,
                rung.energy_error_10 / (rung.tol * r.energy0.abs())
            );
            assert!(
                rung.energy_error_10 <= bound,
                "{name} {:.0e}: energy error {:.2e} > {bound:.2e}",
                rung.tol,
                rung.energy_error_10
            );
        }
    }
}
