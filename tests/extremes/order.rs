//! Order ladder: every method's observed order on a problem with an exact
//! solution, the harmonic oscillator written with the macro.
//!
//! Fixed-step methods: the global error at `t = T` against `h`. Adaptive
//! methods: their dense output (the state between steps), first one step
//! from the exact state, where nothing but the interpolant is measured, then
//! across whole adaptive runs, where it is what a user sampling densely
//! gets. Each test prints its figures:
//! `cargo test --release --test suite -- extremes::order:: --nocapture`.

use crate::support::fit::{log_slope, sci};
use lagrange::models::Oscillator;
use lagrange::nalgebra::Vector1;
use lagrange::prelude::*;

/// The harmonic oscillator, `c = 0`. Exact Jacobians, so that Newton's
/// iteration on this linear problem solves the stage equations exactly.
fn oscillator(m: f64, k: f64) -> Oscillator {
    Oscillator::new(m, k, 0.0)
}

/// The oscillator of the fixed-step ladder: `ω = 2`, released off its
/// extremes so that neither `x` nor `ẋ` starts at zero.
const LADDER: (f64, f64, f64, f64) = (0.5, 2.0, 1.0, 0.6);

/// Run length of the ladder: about two thirds of a period at `ω = 2`, long
/// enough that the error is the accumulated one, short enough that a
/// first-order method's error is still far from O(1).
const T: f64 = 2.0;

fn omega(m: f64, k: f64) -> f64 {
    (k / m).sqrt()
}

/// The exact `(x, ẋ)` at `t` from `(x₀, v₀)` at 0.
fn exact(w: f64, x0: f64, v0: f64, t: f64) -> (f64, f64) {
    let (s, c) = (w * t).sin_cos();
    (x0 * c + v0 / w * s, -x0 * w * s + v0 * c)
}

/// The error in units of the amplitude `A = √(x₀² + (v₀/ω)²)`: the largest of
/// `|Δx| / A` and `|Δẋ| / (ω A)`, so position and velocity count alike
/// whatever `ω`.
fn relative_error(w: f64, x0: f64, v0: f64, t: f64, x: f64, v: f64) -> f64 {
    let amplitude = x0.hypot(v0 / w);
    let (xe, ve) = exact(w, x0, v0, t);
    ((x - xe).abs() / amplitude).max((v - ve).abs() / (w * amplitude))
}

/// Round-off floor for the fits: an error after `steps` steps must be at
/// least `100 · steps · ε` (states of size one). Each step rounds by at
/// most about `10 ε`: a few ε of arithmetic, and the implicit methods'
/// Newton iteration stops once its correction is below `10 ε` of the state.
/// Added up with no cancellation that is `steps · 10 ε`, a tenth of the
/// floor: it moves an error by at most 10 % (0.1 in its logarithm), and a
/// fitted order `p` by at most `0.1 p / D`, with `D` the spread of
/// `ln(error)` across the fit: ≤ 0.05 on the fixed-step ladder (`D = p ln 8`),
/// ≤ 0.17 at worst over whole Dop853 runs (`p = 8`, `D = ln 100`), whose
/// errors sit more than 10× above the floor, so ≤ 0.02 in fact.
fn floor(steps: usize) -> f64 {
    100.0 * steps as f64 * f64::EPSILON
}

/// Global error at `T` of a fixed-step method, relative to the amplitude,
/// and the steps taken.
fn fixed_step_error<I: Integrator<f64>>(method: &I) -> (f64, usize) {
    let (m, k, x0, v0) = LADDER;
    let model = oscillator(m, k);
    let traj = method
        .integrate(&model, 0.0, Vector1::new(x0), Vector1::new(v0), &[T])
        .unwrap();
    let end = traj.last().unwrap();
    let error = relative_error(omega(m, k), x0, v0, T, end.q[0], end.qdot[0]);
    (error, traj.stats().steps_accepted)
}

/// Fits the order over four halvings of `h` and checks it is within ±0.2 of
/// `order` (the acceptance bound). The step lists are chosen in the
/// asymptotic range: `hω ≤ 0.8`, where the next term of the error expansion
/// is a fraction `O(hω)` of the leading one and moves the fitted slope by
/// less than 0.1, and every error above its [`floor`] (checked).
fn assert_fixed_order<I: Integrator<f64>>(
    name: &str,
    order: f64,
    hs: &[f64],
    make: impl Fn(f64) -> I,
) {
    let runs: Vec<(f64, usize)> = hs.iter().map(|&h| fixed_step_error(&make(h))).collect();
    let errors: Vec<f64> = runs.iter().map(|r| r.0).collect();
    let p = log_slope(hs, &errors);
    println!(
        "order ladder | {name:<18} | theory {order} | observed {p:.3} | h {} | error {}",
        sci(hs),
        sci(&errors)
    );
    assert!(
        runs.iter().all(|&(e, steps)| e > floor(steps)),
        "{name}: errors {} reach round-off",
        sci(&errors)
    );
    assert!(
        (p - order).abs() <= 0.2,
        "{name}: observed order {p:.3}, theory {order}"
    );
}

/// Explicit Euler is first order: its global error falls as `h`.
#[test]
fn explicit_euler_is_first_order_on_the_oscillator() {
    let hs = [2e-3, 1e-3, 5e-4, 2.5e-4];
    assert_fixed_order("explicit Euler", 1.0, &hs, ExplicitEuler::new);
}

/// Symplectic Euler is first order too: its energy error stays bounded but
/// the state error, an O(h) distortion of the orbit, still falls only as
/// `h`.
#[test]
fn symplectic_euler_is_first_order_on_the_oscillator() {
    let hs = [2e-3, 1e-3, 5e-4, 2.5e-4];
    assert_fixed_order("symplectic Euler", 1.0, &hs, SymplecticEuler::new);
}

/// Classical Runge–Kutta is fourth order.
#[test]
fn rk4_is_fourth_order_on_the_oscillator() {
    let hs = [0.04, 0.02, 0.01, 0.005];
    assert_fixed_order("RK4", 4.0, &hs, Rk4::new);
}

/// The implicit midpoint rule (one-stage Gauss) is second order.
#[test]
fn implicit_midpoint_is_second_order_on_the_oscillator() {
    let hs = [0.02, 0.01, 0.005, 0.0025];
    assert_fixed_order("implicit midpoint", 2.0, &hs, ImplicitMidpoint::new);
}

/// Two-stage Gauss–Legendre is fourth order (2s with s = 2).
#[test]
fn gauss_legendre_two_stage_is_fourth_order_on_the_oscillator() {
    let hs = [0.1, 0.05, 0.025, 0.0125];
    assert_fixed_order("Gauss-Legendre 2", 4.0, &hs, GaussLegendre::two_stage);
}

/// Three-stage Gauss–Legendre is sixth order (2s with s = 3).
#[test]
fn gauss_legendre_three_stage_is_sixth_order_on_the_oscillator() {
    let hs = [0.4, 0.2, 0.1, 0.05];
    assert_fixed_order("Gauss-Legendre 3", 6.0, &hs, GaussLegendre::three_stage);
}

/// The variational (discrete Euler–Lagrange, midpoint) integrator is second
/// order, including its conversions between `q̇` and `p` at the ends.
#[test]
fn variational_is_second_order_on_the_oscillator() {
    let hs = [0.02, 0.01, 0.005, 0.0025];
    assert_fixed_order("variational", 2.0, &hs, Variational::new);
}

// --- Dense output -------------------------------------------------------

/// Samples per step for the one-step fixture: θ = k/16, k = 1..16.
const PER_STEP: usize = 16;

/// One step of an adaptive method over `[0, H]` from the exact state, with
/// samples at `θH`: the largest relative error strictly inside (the
/// interpolant alone, since the step starts exact) and the error at `H`
/// (the step's own solution).
///
/// It is one step only if the method's first step covers `[0, H]`:
/// checked, not assumed. The tolerance is loose enough that the error test
/// accepts it, and plays no other part: nothing else is adapted, and on this
/// linear problem with exact Jacobians Radau5's simplified Newton iteration
/// is exact at its first iterate, whatever its stopping rule.
fn one_step_errors<I: Integrator<f64>>(method: &I, (m, k): (f64, f64), h: f64) -> (f64, f64) {
    let (x0, v0) = (1.0, 0.0);
    let model = oscillator(m, k);
    let w = omega(m, k);
    let times: Vec<f64> = (1..=PER_STEP)
        .map(|i| h * i as f64 / PER_STEP as f64)
        .collect();
    let traj = method
        .integrate(&model, 0.0, Vector1::new(x0), Vector1::new(v0), &times)
        .unwrap();
    let stats = traj.stats();
    assert!(
        stats.steps_accepted == 1 && stats.steps_rejected == 0,
        "phase {:.3}: not a single step ({stats:?}); the fixture measures nothing",
        w * h
    );
    let errors: Vec<f64> = traj
        .iter()
        .map(|s| relative_error(w, x0, v0, s.t, s.q[0], s.qdot[0]))
        .collect();
    let inside = errors[..PER_STEP - 1].iter().copied().fold(0.0, f64::max);
    (inside, errors[PER_STEP - 1])
}

/// The local order check of an interpolant of order `p*` (local error
/// `O(h^{p*+1})`): over a geometric sequence of step phases `ωH ≤ 0.8`,
/// the largest in-step error must fall with slope `p* + 1 ± 0.2` (the
/// ladder's bound; the θ grid is the same at every `H`, so in the asymptotic
/// range the ratio of maxima is exactly the ratio of `H^{p*+1}`). The step's
/// own end error (local order `p + 1`) is printed beside it, fitted over the
/// phases where it is above the one step's [`floor`].
fn assert_dense_order<I: Integrator<f64>>(
    name: &str,
    dense_order: f64,
    step_order: f64,
    (m, k): (f64, f64),
    phases: &[f64],
    method: &I,
) {
    let w = omega(m, k);
    let (inside, ends): (Vec<f64>, Vec<f64>) = phases
        .iter()
        .map(|&phase| one_step_errors(method, (m, k), phase / w))
        .unzip();
    let p_dense = log_slope(phases, &inside);
    let ends_fit: Vec<(f64, f64)> = phases
        .iter()
        .zip(&ends)
        .filter(|&(_, &e)| e > floor(1))
        .map(|(&p, &e)| (p, e))
        .collect();
    let (fit_phases, fit_ends): (Vec<f64>, Vec<f64>) = ends_fit.into_iter().unzip();
    let p_end = if fit_phases.len() >= 2 {
        format!("{:.3}", log_slope(&fit_phases, &fit_ends))
    } else {
        "below round-off".into()
    };
    println!(
        "dense output, one step | {name:<7} | interpolant local order theory {} observed {p_dense:.3} \
         | step end local order theory {} observed {p_end} | phase ωH {} | in-step error {} | end error {}",
        dense_order + 1.0,
        step_order + 1.0,
        sci(phases),
        sci(&inside),
        sci(&ends)
    );
    assert!(
        inside.iter().all(|&e| e > floor(1)),
        "{name}: in-step errors {} reach round-off",
        sci(&inside)
    );
    assert!(
        (p_dense - (dense_order + 1.0)).abs() <= 0.2,
        "{name}: interpolant local order {p_dense:.3}, theory {}",
        dense_order + 1.0
    );
}

/// `(m, k)` for the explicit methods' one-step fixture: `ω = 1/2`. Hairer's
/// first step is `min(100 h₀, h₁)` with `h₀` 1 % of `|y|/|ẏ|` (in the
/// tolerance's norm) and `h₁^p |ẏ| ≈ 0.01`: released from rest at `x = 1`,
/// with `rtol = atol = 10³` (accepted whatever the step, yet not so loose
/// that the guess degenerates to 1e-6), both exceed a phase of 0.8.
const EXPLICIT_FIXTURE: (f64, f64) = (4.0, 1.0);

/// Dopri5's continuous extension is of order 4: its error inside one step
/// from an exact start falls as `H⁵`.
#[test]
fn dopri5_dense_output_is_fourth_order_within_a_step() {
    let method = Dopri5::new().rtol(1e3).atol(1e3);
    let phases = [0.8, 0.4, 0.2, 0.1];
    assert_dense_order("Dopri5", 4.0, 5.0, EXPLICIT_FIXTURE, &phases, &method);
}

/// Dop853's continuous extension (`contd8`, three extra stages) is of order
/// 7: its error inside one step falls as `H⁸`.
#[test]
fn dop853_dense_output_is_seventh_order_within_a_step() {
    let method = Dop853::new().rtol(1e3).atol(1e3);
    // Ratios of √2, not 2: at order 8 a phase of 0.1 already puts the
    // in-step error (~1e-14) at round-off.
    let phases = [0.8, 0.566, 0.4, 0.283, 0.2];
    assert_dense_order("Dop853", 7.0, 8.0, EXPLICIT_FIXTURE, &phases, &method);
}

/// Radau5's dense output is its collocation polynomial, of degree 3: order
/// 3, error inside a step `O(H⁴)`, while the step end is of order 5.
#[test]
fn radau5_dense_output_is_third_order_within_a_step() {
    // RADAU5's first step is 1 % of |y|/|ẏ| (no factor 100): released from
    // rest at x = 1 that is 0.005/ω², a phase of 0.005/ω. A slow oscillator,
    // ω = 1/200, makes it one radian, enough to cover every phase below.
    let method = Radau5::new().rtol(1e-3).atol(1e-3);
    let phases = [0.8, 0.4, 0.2, 0.1];
    assert_dense_order("Radau5", 3.0, 5.0, (40_000.0, 1.0), &phases, &method);
}

/// Length of the adaptive runs: over three periods at `ω = 2`.
const RUN: f64 = 10.0;

/// Samples per adaptive run, at `t = RUN (i − ½)/1000`: many per step at
/// every tolerance below, none on a step end but by accident, and the last
/// sample `RUN`, which the last step always lands on.
const RUN_SAMPLES: usize = 1000;

/// What one adaptive run measured.
struct RunErrors {
    /// The largest error over the samples between steps.
    between: f64,
    /// The error at `RUN`, a step end.
    end: f64,
    steps: usize,
}

/// One adaptive run of the ladder's oscillator over `[0, RUN]`.
fn run_errors<I: Integrator<f64>>(method: &I) -> RunErrors {
    let (m, k, x0, v0) = LADDER;
    let model = oscillator(m, k);
    let w = omega(m, k);
    let mut times: Vec<f64> = (1..=RUN_SAMPLES)
        .map(|i| RUN * (i as f64 - 0.5) / RUN_SAMPLES as f64)
        .collect();
    times.push(RUN);
    let traj = method
        .integrate(&model, 0.0, Vector1::new(x0), Vector1::new(v0), &times)
        .unwrap();
    let errors: Vec<f64> = traj
        .iter()
        .map(|s| relative_error(w, x0, v0, s.t, s.q[0], s.qdot[0]))
        .collect();
    RunErrors {
        between: errors[..RUN_SAMPLES].iter().copied().fold(0.0, f64::max),
        end: errors[RUN_SAMPLES],
        steps: traj.stats().steps_accepted,
    }
}

/// Dense output in use: over whole adaptive runs at several tolerances, the
/// largest error of the samples between steps against the mean step
/// `h̄ = RUN / steps`. Between steps the error is the global error carried
/// to the step start, `O(h̄^p)`, plus the interpolant's local error,
/// `O(h̄^{p*+1})`: the fit measures `min(p, p* + 1)`. The error at the end
/// (a step end, `O(h̄^p)`) is fitted beside it. The step-size profile along
/// the orbit has the same shape at every tolerance (it follows the local
/// error norm), so both errors are powers of `h̄`.
///
/// Both orders must be within ±0.2 of theory, the ladder's bound, over
/// tolerances where the fit is asymptotic: steps short against the period
/// (`h̄ω ≤ 0.5`; the next term of the error expansion is a fraction `O(h̄ω)`
/// of the leading one, as on the ladder) and every error above the run's
/// [`floor`] (checked). Looser tolerances are not asymptotic: Dop853's
/// blended estimate behaves as `h⁸` only for small steps, and from `1e-7`
/// to `1e-11` the same fits give 8.3 and 8.5.
fn assert_run_order<I: Integrator<f64>>(
    name: &str,
    (dense_order, end_order): (f64, f64),
    tolerances: &[f64],
    make: impl Fn(f64) -> I,
) {
    let runs: Vec<RunErrors> = tolerances
        .iter()
        .map(|&tol| run_errors(&make(tol)))
        .collect();
    let dense: Vec<f64> = runs.iter().map(|r| r.between).collect();
    let ends: Vec<f64> = runs.iter().map(|r| r.end).collect();
    let hs: Vec<f64> = runs.iter().map(|r| RUN / r.steps as f64).collect();
    let (p_dense, p_end) = (log_slope(&hs, &dense), log_slope(&hs, &ends));
    let ratio: Vec<f64> = dense.iter().zip(&ends).map(|(d, e)| d / e).collect();
    println!(
        "dense output, adaptive runs | {name:<7} | between-step error order theory {dense_order} observed {p_dense:.3} \
         | step-end error order theory {end_order} observed {p_end:.3} | tol {} | mean h {} | between-step error {} \
         | end error {} | between/end {}",
        sci(tolerances),
        sci(&hs),
        sci(&dense),
        sci(&ends),
        sci(&ratio)
    );
    assert!(
        runs.iter().all(|r| r.between.min(r.end) > floor(r.steps)),
        "{name}: errors reach round-off"
    );
    assert!(
        (p_dense - dense_order).abs() <= 0.2,
        "{name}: between-step error order {p_dense:.3}, theory {dense_order}"
    );
    assert!(
        (p_end - end_order).abs() <= 0.2,
        "{name}: step-end error order {p_end:.3}, theory {end_order}"
    );
}

/// Dopri5: fifth-order steps, fourth-order interpolant: `min(5, 4 + 1) = 5`,
/// so samples between steps are as accurate as the step ends (within a
/// constant factor, printed).
#[test]
fn dopri5_dense_output_keeps_fifth_order_accuracy_over_a_run() {
    let tolerances = [1e-7, 1e-8, 1e-9, 1e-10];
    assert_run_order("Dopri5", (5.0, 5.0), &tolerances, |tol| {
        Dopri5::new().rtol(tol).atol(tol)
    });
}

/// Dop853: eighth-order steps, seventh-order interpolant: `min(8, 7 + 1)
/// = 8`, samples between steps as accurate as the step ends.
#[test]
fn dop853_dense_output_keeps_eighth_order_accuracy_over_a_run() {
    // At 1e-12 the end error (2e-12 after ~100 steps) is under the floor.
    let tolerances = [1e-9, 1e-10, 1e-11];
    assert_run_order("Dop853", (8.0, 8.0), &tolerances, |tol| {
        Dop853::new().rtol(tol).atol(tol)
    });
}

/// Radau5: fifth-order steps, third-order collocation polynomial:
/// `min(5, 3 + 1) = 4` between steps against 5 at the step ends, so its
/// samples between steps lose ground as the tolerance tightens (the ratio,
/// printed, grows as `1/h̄`).
#[test]
fn radau5_dense_output_is_a_fourth_order_between_fifth_order_step_ends() {
    let tolerances = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
    assert_run_order("Radau5", (4.0, 5.0), &tolerances, |tol| {
        Radau5::new().rtol(tol).atol(tol)
    });
}
