//! Numerical stability at the extremes: a stiff spring chain, stiffness
//! ratio 10⁶ and 10⁸.
//!
//! Two unit masses between walls on soft springs (`k1 = 2`, `k2 = 1`), joined
//! by a spring `kc = ratio · k2`. The slow mode (ω ≈ 1.22, the masses moving
//! together) is the motion of interest; the fast one (ω ≈ √(2 kc): 1414 and
//! 14 142) is the stiff spring ringing. No damping, so that what each
//! method does to the fast mode (keep, damp or alias it) shows against an
//! exact solution that keeps it. Every method here is a (partitioned)
//! Runge–Kutta method, the variational one included (on this model it is
//! the implicit midpoint rule), and those commute with linear changes of
//! variables: each advances each mode separately by its stability function,
//! `z ↦ R(i ω h) z` for the modal amplitude `z = η̇ + i ω η`. So a two-mode
//! chain shows all there is, and the exact solution is the modal one, in
//! closed form.
//!
//! Every test prints its figures; `cargo test --release --test extremes --
//! stiff:: --nocapture --test-threads=1` shows them in order.

use lagrange::nalgebra::{Complex, Matrix2, Matrix4, Vector2, Vector4};
use lagrange::prelude::*;
use lagrange::IntegrationResult;
use std::f64::consts::PI;

lagrangian! {
    /// Two unit masses between walls, on soft springs `k1` and `k2`, joined
    /// by a stiff spring `kc`.
    #[lagrange(jacobians)]
    pub struct StiffPair {
        coordinates: x1, x2;
        parameters: k1, k2, kc;
        kinetic: (dot(x1)^2 + dot(x2)^2)/2;
        potential: k1/2*x1^2 + kc/2*(x2 - x1)^2 + k2/2*x2^2;
    }
}

/// The stiffness ratios of the scenario.
const RATIOS: [f64; 2] = [1e6, 1e8];
/// Time span: two slow periods.
const T: f64 = 10.0;
const EPS: f64 = f64::EPSILON;

fn chain(ratio: f64) -> StiffPair {
    StiffPair::new(2.0, 1.0, ratio)
}

/// Every 0.5 up to `T`.
fn samples() -> Vec<f64> {
    (1..=20).map(|k| 0.5 * k as f64).collect()
}

type C = Complex<f64>;

/// The exact solution, mode by mode.
///
/// `K = [[k1 + kc, −kc], [−kc, k2 + kc]]` has eigenvalues `m ∓ ρ` with
/// `m = (k1 + k2)/2 + kc`, `δ = (k1 − k2)/2`, `ρ = √(kc² + δ²)`. The slow one
/// is written `(k1 + k2)/2 − δ²/(kc + ρ)`, which cancels nothing, and the
/// mode shapes `(kc, δ + ρ)` and `(−(δ + ρ), kc)` need no subtraction of
/// nearly equal numbers either: every quantity is good to a few ε relative.
/// A generic route loses digits at 10⁸: an eigensolver or the matrix
/// exponential errs by ε‖K‖ ≈ 2e-8 absolute, relative 1e-8 on the slow
/// eigenvalue (see `modal_reference_is_exact_where_the_matrix_exponential_is_not`).
struct Modes {
    /// Orthonormal shapes: slow, fast.
    shape: [Vector2<f64>; 2],
    omega: [f64; 2],
}

impl Modes {
    const SLOW: usize = 0;
    const FAST: usize = 1;

    fn of(chain: &StiffPair) -> Self {
        let (k1, k2, kc) = (chain.k1, chain.k2, chain.kc);
        let delta = (k1 - k2) / 2.0;
        let rho = kc.hypot(delta);
        let slow = (k1 + k2) / 2.0 - delta * delta / (kc + rho);
        let fast = (k1 + k2) / 2.0 + kc + rho;
        let shape = Vector2::new(kc, delta + rho).normalize();
        Modes {
            shape: [shape, Vector2::new(-shape[1], shape[0])],
            omega: [slow.sqrt(), fast.sqrt()],
        }
    }

    /// The modal amplitudes `z = η̇ + i ω η` of a state.
    fn amplitudes(&self, q: &Vector2<f64>, qdot: &Vector2<f64>) -> [C; 2] {
        [0, 1].map(|i| {
            C::new(
                self.shape[i].dot(qdot),
                self.omega[i] * self.shape[i].dot(q),
            )
        })
    }

    fn state(&self, z: [C; 2]) -> (Vector2<f64>, Vector2<f64>) {
        let q =
            self.shape[0] * (z[0].im / self.omega[0]) + self.shape[1] * (z[1].im / self.omega[1]);
        let qdot = self.shape[0] * z[0].re + self.shape[1] * z[1].re;
        (q, qdot)
    }

    /// `z(t) = e^{iωt} z(0)`; the phase `ωt` is rounded to ε ωt
    /// (3e-11 rad for the fast mode at 10⁸, t = 10).
    fn exact_amplitudes(&self, t: f64, z0: [C; 2]) -> [C; 2] {
        [0, 1].map(|i| z0[i] * C::from_polar(1.0, self.omega[i] * t))
    }

    /// The slow mode alone, `x ≈ (0.1, 0.1)`, at rest: the stiff spring is
    /// at its quasi-static stretch, and only rounding excites the fast mode.
    fn slow_start(&self) -> (Vector2<f64>, Vector2<f64>) {
        (
            self.shape[Self::SLOW] * (0.1 * 2f64.sqrt()),
            Vector2::zeros(),
        )
    }

    /// The slow start plus the fast mode displaced by 1e-6: the stiff spring
    /// rings with velocity amplitude 1e-6 ω (1.4e-3 and 1.4e-2).
    fn ringing_start(&self) -> (Vector2<f64>, Vector2<f64>) {
        let (q, qdot) = self.slow_start();
        (q + self.shape[Self::FAST] * 1e-6, qdot)
    }
}

/// What a run did to each mode, against the exact solution.
#[derive(Debug)]
struct Measured {
    /// Worst `|z_slow − exact| / |z_slow(0)|` over the samples.
    slow_error: f64,
    /// `|z_slow − exact|` at the last sample, where every method ends a step.
    end_slow_error: f64,
    /// `max(|q − exact|, |q̇ − exact|)` at the last sample.
    end_error: f64,
    /// Worst `|q − exact|` and `|q̇ − exact|` over the samples.
    q_error: f64,
    qdot_error: f64,
    /// The fast mode's displacement amplitude `|z_fast| / ω` at the end.
    fast_amplitude: f64,
}

fn measure(
    modes: &Modes,
    start: (Vector2<f64>, Vector2<f64>),
    run: &Trajectory<f64, 2>,
) -> Measured {
    let z0 = modes.amplitudes(&start.0, &start.1);
    let mut m = Measured {
        slow_error: 0.0,
        end_slow_error: 0.0,
        end_error: 0.0,
        q_error: 0.0,
        qdot_error: 0.0,
        fast_amplitude: 0.0,
    };
    for s in run {
        let exact = modes.exact_amplitudes(s.t, z0);
        let z = modes.amplitudes(&s.q, &s.qdot);
        let (q, qdot) = modes.state(exact);
        m.end_slow_error = (z[0] - exact[0]).norm();
        m.slow_error = m.slow_error.max(m.end_slow_error / z0[0].norm());
        m.end_error = (s.q - q).amax().max((s.qdot - qdot).amax());
        m.q_error = m.q_error.max((s.q - q).amax());
        m.qdot_error = m.qdot_error.max((s.qdot - qdot).amax());
        m.fast_amplitude = z[1].norm() / modes.omega[1];
    }
    m
}

fn ratio_name(ratio: f64) -> &'static str {
    if ratio == 1e6 {
        "1e6"
    } else {
        "1e8"
    }
}

/// The reference. Its eigenvalues must satisfy `λs λf = det K` and
/// `λs + λf = tr K`, both exact in floating point for these integers, which
/// pins the slow eigenvalue to a few ε relative, where a generic
/// eigensolver's ε‖K‖ would be 1e-8 relative at 10⁸; and its shapes are
/// eigenvectors of `K` as the model computes it (`f = −K q`).
///
/// The matrix exponential of the first-order system (the work–precision
/// study's reference) is printed beside it: within the `ε ‖A‖ T |y|` that
/// scaling and squaring may lose (6e-10 at 10⁶, 6e-8 at 10⁸), it differs by
/// 7e-12 and 2e-9, above what Radau5 reaches at tolerance 1e-10 (4e-10,
/// `radau5_crosses_the_stiff_chain_in_few_steps`): at 10⁸ it could not judge
/// that run, and the modal solution can.
#[test]
fn modal_reference_is_exact_where_the_matrix_exponential_is_not() {
    for ratio in RATIOS {
        let chain = chain(ratio);
        let modes = Modes::of(&chain);
        let (ls, lf) = (modes.omega[0].powi(2), modes.omega[1].powi(2));
        let (k1, k2, kc) = (chain.k1, chain.k2, chain.kc);
        let det = k1 * k2 + kc * (k1 + k2);
        assert!(
            (ls * lf - det).abs() <= 8.0 * EPS * det,
            "λs λf = {}",
            ls * lf
        );
        assert!(((ls + lf) - (k1 + k2 + 2.0 * kc)).abs() <= 8.0 * EPS * lf);
        // The shapes are eigenvectors, K v = λ v to rounding of ‖K‖, of K
        // as the model computes it.
        let at = |q: Vector2<f64>| -chain.forcing(0.0, &q, &Vector2::zeros());
        let k = Matrix2::from_columns(&[at(Vector2::x()), at(Vector2::y())]);
        for i in 0..2 {
            let residual = (k * modes.shape[i] - modes.shape[i] * modes.omega[i].powi(2)).amax();
            assert!(
                residual <= 8.0 * EPS * (k1 + k2 + 2.0 * kc),
                "mode {i}: {residual:e}"
            );
        }

        let start = modes.slow_start();
        let z0 = modes.amplitudes(&start.0, &start.1);
        let (q, qdot) = modes.state(modes.exact_amplitudes(T, z0));
        let mut a = Matrix4::<f64>::zeros();
        a.fixed_view_mut::<2, 2>(0, 2).fill_with_identity();
        a.fixed_view_mut::<2, 2>(2, 0).copy_from(&-k);
        let y0 = Vector4::new(start.0[0], start.0[1], start.1[0], start.1[1]);
        let y = (a * T).exp() * y0;
        let expm = (Vector2::new(y[0], y[1]) - q)
            .amax()
            .max((Vector2::new(y[2], y[3]) - qdot).amax());
        println!(
            "stiff {}: ω_slow = {:.6}, ω_fast = {:.1}; matrix exponential vs modal at t = {T}: {expm:.1e}",
            ratio_name(ratio),
            modes.omega[0],
            modes.omega[1]
        );
        // ‖A‖∞ = 2 kc + k1 (the row sums of K), |y0| ≤ 0.15.
        let allowed = EPS * (2.0 * kc + k1) * T * 0.15;
        assert!(expm <= allowed, "expm off by {expm:e}, allowed {allowed:e}");
    }
}

/// Far beyond the explicit stability limit (h = 0.01: hω_fast = 14 and 141,
/// against 2√2 for RK4, 2 for symplectic Euler, and no interval at all for
/// explicit Euler), the round-off in the fast mode grows by |R(iωh)| per
/// step: from 14 (explicit Euler at 10⁶) to 10⁸ (RK4 at 10⁸). Each explicit
/// fixed-step method must stop with `Unstable`, with a finite state, never
/// inf, and early: the fast mode starts at rounding (a velocity of ~1e-14)
/// and must pass the guard's floor (1000× the starting scale, here 1000),
/// a factor 1e17 that takes at most 15 steps at 14× per step, plus up to 8
/// for the guard to be sure: 30 steps at most. At half its limit RK4 runs
/// through, for the price.
#[test]
fn explicit_fixed_steps_beyond_their_limit_stop_with_unstable() {
    for ratio in RATIOS {
        let chain = chain(ratio);
        let modes = Modes::of(&chain);
        let start = modes.slow_start();
        let runs: [(&str, IntegrationResult<f64, 2>); 3] = [
            (
                "ExplicitEuler",
                ExplicitEuler::new(0.01).integrate(&chain, 0.0, start.0, start.1, &samples()),
            ),
            (
                "SymplecticEuler",
                SymplecticEuler::new(0.01).integrate(&chain, 0.0, start.0, start.1, &samples()),
            ),
            (
                "Rk4",
                Rk4::new(0.01).integrate(&chain, 0.0, start.0, start.1, &samples()),
            ),
        ];
        for (name, run) in runs {
            let failure = run.expect_err(name);
            let IntegrationError::Unstable {
                t,
                h,
                steps,
                q,
                qdot,
            } = failure.error
            else {
                panic!("{name}: expected Unstable, got {}", failure.error);
            };
            let size = q.amax().max(qdot.amax());
            println!(
                "stiff {} | {name} h = 0.01 (hω = {:.0}) | Unstable at t = {t} after {} steps (growth seen over {steps}), |y| = {size:.1e}, {} samples kept",
                ratio_name(ratio),
                h * modes.omega[1],
                failure.trajectory.stats().steps_accepted,
                failure.trajectory.len()
            );
            assert!(
                failure.trajectory.stats().steps_accepted <= 30,
                "{name}: caught late, at t = {t}"
            );
            assert!(size.is_finite());
        }

        // Half the limit: stable, and as accurate as RK4 at that step
        // (slow mode hω ≈ 1e-4: far below 1e-10).
        let h = 0.5 * 8f64.sqrt() / modes.omega[1];
        let run = Rk4::new(h)
            .integrate(&chain, 0.0, start.0, start.1, &samples())
            .unwrap();
        let m = measure(&modes, start, &run);
        println!(
            "stiff {} | Rk4 h = {h:.2e} (half its limit) | ok, {} rhs, slow-mode error {:.1e}",
            ratio_name(ratio),
            run.stats().rhs_evals,
            m.slow_error
        );
        assert!(m.slow_error < 1e-10, "{m:?}");
    }
}

/// The adaptive explicit methods never see the fast mode (it stays at the
/// tolerance level), yet it sets their step. Where `|R(iωh)| > 1` it grows
/// until the error estimate rejects the step, so the accepted steps hover
/// near the edge of the stability region on the imaginary axis: Dopri5's
/// `|R(iy)|` exceeds 1 from y ≈ 0.9 (by 1e-6 at y = 1, 3 % at 2, 2× at
/// 3.5), DOP853's stays below 1 up to y = 5.95 (computed from the
/// tableaux). So the mean `h ω_fast` is of order one, at most 6, and the cost
/// is ∝ ω_fast: ten times more from 10⁶ to 10⁸, whatever the accuracy asks.
/// Accuracy is kept: steps that small resolve the slow mode far better than
/// the ≤ 100 tol the integrator suite allows at tolerance 1e-6, and the
/// spurious fast mode is made of accepted local errors: any growth beyond
/// what the estimate tolerates is rejected, so its displacement stays at
/// the tolerance level (≤ 10 tol). Its velocity, ω_fast times that, is where
/// the error shows.
///
/// At 10⁸ Dopri5 needs ~170 000 steps: its default budget of 100 000 ends
/// with `TooManySteps` at t ≈ 5.8, keeping the samples before; with a budget
/// of 300 000 it finishes.
#[test]
fn adaptive_explicit_methods_pay_for_the_fast_mode_with_steps() {
    let tol = 1e-6;
    let mut evals = Vec::new();
    for ratio in RATIOS {
        let chain = chain(ratio);
        let modes = Modes::of(&chain);
        let start = modes.slow_start();
        let times = samples();
        let dopri5 = Dopri5::new().rtol(tol).atol(tol);
        let dop853 = Dop853::new().rtol(tol).atol(tol);
        let budget = 300_000;
        let runs: [(&str, IntegrationResult<f64, 2>); 2] = [
            (
                "Dopri5",
                dopri5
                    .max_steps(budget)
                    .integrate(&chain, 0.0, start.0, start.1, &times),
            ),
            (
                "Dop853",
                dop853
                    .max_steps(budget)
                    .integrate(&chain, 0.0, start.0, start.1, &times),
            ),
        ];
        for (name, run) in runs {
            let run = run.unwrap_or_else(|f| panic!("{name}: {f}"));
            let stats = run.stats();
            let m = measure(&modes, start, &run);
            let mean_h_omega = T * modes.omega[1] / stats.steps_accepted as f64;
            println!(
                "stiff {} | {name} tol {tol:.0e} | ok, {} steps ({} rejected), {} rhs, mean hω_fast = {mean_h_omega:.2} | slow-mode error {:.1e}, q error {:.1e}, q̇ error {:.1e}, spurious fast amplitude {:.1e}",
                ratio_name(ratio),
                stats.steps_accepted,
                stats.steps_rejected,
                stats.rhs_evals,
                m.slow_error,
                m.q_error,
                m.qdot_error,
                m.fast_amplitude
            );
            assert!(
                (0.3..=4.6).contains(&mean_h_omega),
                "{name}: mean hω = {mean_h_omega}"
            );
            assert!(m.slow_error <= 100.0 * tol, "{name}: {m:?}");
            assert!(m.fast_amplitude <= 10.0 * tol, "{name}: {m:?}");
            evals.push((name, ratio, stats.rhs_evals));
        }

        if ratio == 1e8 {
            let failure = dopri5
                .integrate(&chain, 0.0, start.0, start.1, &times)
                .expect_err("Dopri5 at 1e8 within 100 000 steps");
            let IntegrationError::TooManySteps { t, max_steps, .. } = failure.error else {
                panic!("expected TooManySteps, got {}", failure.error);
            };
            let kept = failure.trajectory.times();
            println!(
                "stiff 1e8 | Dopri5 tol {tol:.0e}, default budget | TooManySteps after {max_steps} steps at t = {t:.3}, {} samples kept (to t = {})",
                kept.len(),
                kept.last().unwrap()
            );
            assert!(t > 1.0 && t < T);
            assert_eq!(kept, &times[..kept.len()]);
            assert!(times[kept.len()] > t);
            assert!(measure(&modes, start, &failure.trajectory).slow_error <= 100.0 * tol);
        }
    }
    for name in ["Dopri5", "Dop853"] {
        let cost = |ratio| {
            evals
                .iter()
                .find(|e| e.0 == name && e.1 == ratio)
                .unwrap()
                .2 as f64
        };
        let growth = cost(1e8) / cost(1e6);
        println!("stiff | {name}: cost 1e8 / cost 1e6 = {growth:.1} (ω_fast grows 10×)");
        assert!((5.0..=20.0).contains(&growth), "{name}: {growth}");
    }
}

/// Radau5 is L-stable: `R(z) → 0` as `|z| → ∞`, so its steps follow the slow
/// mode alone. From the slow start it crosses the 10 s in a few dozen steps
/// at either ratio (≤ 100 at tolerance 1e-6; the cost does not grow with
/// the stiffness). Its errors are the documented ones
/// (`lagrange-runtime/tests/integrators/radau5.rs`): at the end of a step ≤ 30 tol (the
/// global error ∝ tol^(5/6)), and at samples between steps, which come from
/// the order-3 collocation polynomial, ≤ 3.1 local tolerances
/// `0.1 tol^(2/3)` times `1 + |y|`. At 1e-10 too, to show that 10⁸ costs no
/// digits in this model.
///
/// With the fast mode ringing (velocity amplitude 1.4e-3 and 1.4e-2, far
/// above the tolerance) Radau5 has to follow the ringing until it has
/// damped it, within the tolerance on each step: hundreds to tens of
/// thousands of steps. The slow mode stays within 30 tol, and the ringing is
/// gone by T (below 1 % of its 1e-6; the exact solution keeps all of it):
/// L-stability damps what it does not resolve. It pays when the stiff mode
/// is negligible or meant to be damped, not when it carries energy.
#[test]
fn radau5_crosses_the_stiff_chain_in_few_steps() {
    for ratio in RATIOS {
        let chain = chain(ratio);
        let modes = Modes::of(&chain);
        let start = modes.slow_start();
        for tol in [1e-6, 1e-10] {
            let run = Radau5::new()
                .rtol(tol)
                .atol(tol)
                .integrate(&chain, 0.0, start.0, start.1, &samples())
                .unwrap();
            let stats = run.stats();
            let m = measure(&modes, start, &run);
            println!(
                "stiff {} | Radau5 tol {tol:.0e}, slow start | ok, {} steps ({} rejected), {} rhs, {} Jacobians, {} LU solves | state error at T {:.1e} (slow mode {:.1e}), worst sample (dense output) q {:.1e}, q̇ {:.1e} | fast amplitude {:.1e}",
                ratio_name(ratio),
                stats.steps_accepted,
                stats.steps_rejected,
                stats.rhs_evals,
                stats.jacobian_evals,
                stats.linear_solves,
                m.end_error,
                m.end_slow_error,
                m.q_error,
                m.qdot_error,
                m.fast_amplitude
            );
            let dense = 3.1 * 0.1 * tol.powf(2.0 / 3.0) * 1.15;
            assert!(m.end_error <= 30.0 * tol, "{m:?}");
            assert!(m.q_error.max(m.qdot_error) <= dense, "{m:?}");
            if tol == 1e-6 {
                assert!(
                    stats.steps_accepted + stats.steps_rejected <= 100,
                    "{stats:?}"
                );
            }
        }

        let tol = 1e-6;
        let start = modes.ringing_start();
        let run = Radau5::new()
            .rtol(tol)
            .atol(tol)
            .integrate(&chain, 0.0, start.0, start.1, &samples())
            .unwrap();
        let stats = run.stats();
        let m = measure(&modes, start, &run);
        println!(
            "stiff {} | Radau5 tol {tol:.0e}, fast mode ringing (1e-6) | ok, {} steps ({} rejected), {} rhs | slow-mode error at T {:.1e}, fast amplitude at T {:.1e} of 1.0e-6, worst q̇ error {:.1e}",
            ratio_name(ratio),
            stats.steps_accepted,
            stats.steps_rejected,
            stats.rhs_evals,
            m.end_slow_error,
            m.fast_amplitude,
            m.qdot_error
        );
        // |Δz| ≤ |Δη̇| + ω |Δη|: 30 tol on each state component.
        assert!(
            m.end_slow_error <= (1.0 + modes.omega[0]) * 30.0 * tol,
            "{m:?}"
        );
        assert!(m.fast_amplitude <= 1e-8, "{m:?}");
    }
}

/// `R(z)` of the symmetric methods: the diagonal Padé approximants of `e^z`.
fn stability_function(stages: usize, z: C) -> C {
    let one = C::new(1.0, 0.0);
    let (p, q) = match stages {
        1 => (one + z / 2.0, one - z / 2.0),
        2 => (one + z / 2.0 + z * z / 12.0, one - z / 2.0 + z * z / 12.0),
        _ => (
            one + z / 2.0 + z * z / 10.0 + z * z * z / 120.0,
            one - z / 2.0 + z * z / 10.0 - z * z * z / 120.0,
        ),
    };
    p / q
}

/// The symmetric implicit methods (midpoint, Gauss–Legendre 2 and 3, and the
/// variational midpoint rule, which on this linear model is the same map as
/// the implicit midpoint rule) at steps 50 and 500 times the RK4 limit
/// (h = 0.01 and 0.1; hω_fast up to 1414) stay bounded, and they neither
/// damp nor resolve the fast mode: `|R(iθ)| = 1` keeps its amplitude, and
/// its phase advances by `arg R(iθ)` per step instead of `θ`, which for
/// `θ ≫ 1` is close to π: the ringing is aliased to near the Nyquist
/// frequency. The test predicts each mode exactly, `z_n = R(iωh)^n z_0`, and
/// requires the run to match to rounding: the Newton iterations stop at
/// 10 ε of the state (|y| ≈ 0.14), which, on a fast amplitude of 1e-6, is
/// 2e-9 relative per step, so `n · 2e-9` allows for the worst case of all
/// steps erring alike. The slow mode's error is then the method's own phase
/// error, `n |R(iθ) − e^{iθ}| ≈ T ω C θ^{2s}` (C = 1/12, 1/720, 1/100800):
/// printed, and checked through the prediction.
#[test]
fn symmetric_implicit_methods_keep_the_fast_mode_but_alias_its_phase() {
    for ratio in RATIOS {
        let chain = chain(ratio);
        let modes = Modes::of(&chain);
        let start = modes.ringing_start();
        let z0 = modes.amplitudes(&start.0, &start.1);
        for h in [0.01, 0.1] {
            let n = (T / h).round() as i32;
            let runs: [(&str, usize, IntegrationResult<f64, 2>); 4] = [
                (
                    "ImplicitMidpoint",
                    1,
                    ImplicitMidpoint::new(h).integrate(&chain, 0.0, start.0, start.1, &samples()),
                ),
                (
                    "GaussLegendre2",
                    2,
                    GaussLegendre::two_stage(h).integrate(
                        &chain,
                        0.0,
                        start.0,
                        start.1,
                        &samples(),
                    ),
                ),
                (
                    "GaussLegendre3",
                    3,
                    GaussLegendre::three_stage(h).integrate(
                        &chain,
                        0.0,
                        start.0,
                        start.1,
                        &samples(),
                    ),
                ),
                (
                    "Variational",
                    1,
                    Variational::new(h).integrate(&chain, 0.0, start.0, start.1, &samples()),
                ),
            ];
            for (name, stages, run) in runs {
                let run = run.unwrap_or_else(|f| panic!("{name}: {f}"));
                let end = run.last().unwrap();
                assert_eq!(end.t, T);
                let z = modes.amplitudes(&end.q, &end.qdot);
                let exact = modes.exact_amplitudes(T, z0);
                let r = [0, 1].map(|i| stability_function(stages, C::new(0.0, modes.omega[i] * h)));
                let predicted = [0, 1].map(|i| z0[i] * r[i].powi(n));
                let off = [0, 1].map(|i| (z[i] - predicted[i]).norm() / z0[i].norm());
                let amplitude = z[1].norm() / z0[1].norm();
                let phase_step = r[1].arg();
                let exact_step = (modes.omega[1] * h + PI).rem_euclid(2.0 * PI) - PI;
                let fast_phase_error = (z[1] / exact[1]).arg();
                let slow_error = (z[0] - exact[0]).norm() / z0[0].norm();
                println!(
                    "stiff {} | {name} h = {h} (hω_fast = {:.0}) | ok, {} rhs, {} Newton iterations | fast amplitude ×{amplitude:.12}, phase/step {phase_step:.4} rad vs exact {exact_step:.4} (apparent ω {:.0} vs {:.0}), phase error at T {fast_phase_error:+.3} rad | slow-mode error {slow_error:.1e} | off the R(iωh)^n prediction: slow {:.0e}, fast {:.0e}",
                    ratio_name(ratio),
                    modes.omega[1] * h,
                    run.stats().rhs_evals,
                    run.stats().newton_iterations,
                    phase_step.abs() / h,
                    modes.omega[1],
                    off[0],
                    off[1]
                );
                // Rounding per step: Newton leaves ≤ 10 ε |y| (|y| ≤ 0.15)
                // in each component, |Δz| ≤ (1 + ω) of that; the stiff force
                // evaluated at a stage position rounded to ε |x| (|x| ≤ 0.1)
                // is off by kc ε |x|, a kick of h kc ε |x| to the fast
                // velocity (on the slow mode its projection is negligible).
                let newton = n as f64 * 10.0 * EPS * 0.15;
                let kicks = T * chain.kc * EPS * 0.1;
                let bound = [
                    newton * (1.0 + modes.omega[0]) / z0[0].norm(),
                    (newton * (1.0 + modes.omega[1]) + kicks) / z0[1].norm(),
                ];
                assert!(off[0] <= bound[0], "{name}: slow {off:?}, bound {bound:?}");
                assert!(off[1] <= bound[1], "{name}: fast {off:?}, bound {bound:?}");
                assert!((amplitude - 1.0).abs() <= bound[1], "{name}: ×{amplitude}");
            }
        }
    }
}
