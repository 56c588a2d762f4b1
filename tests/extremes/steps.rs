//! Numerical stability at the extremes: step sizes and step budgets.
//!
//! A step beyond the stability limit, a step too small to move time, a
//! tolerance too tight for the arithmetic, a budget that runs out: each must
//! end in its typed error, quickly, with the samples computed before it,
//! never in a hang, an infinity or a silently wrong trajectory.
//!
//! Every test prints its figures; `cargo test --release --test suite --
//! extremes::steps:: --nocapture --test-threads=1` shows them in order.

use lagrange::Method;
use lagrange::models::Oscillator;
use lagrange::nalgebra::{SVector, Vector1, Vector2};
use lagrange::prelude::*;
use lagrange::{IntegrationResult, InvalidInput};
use std::time::Instant;

/// A unit mass on a spring `k` with a dashpot `c`.
fn unit_spring(k: f64, c: f64) -> Oscillator {
    Oscillator::new(1.0, k, c)
}

lagrangian! {
    /// `M = [[2, 1], [1, 2]]`, `V = x² + x y + y²`: `q̈ = −q` exactly, but
    /// `y` released from 0 does not stay at 0: every acceleration comes out
    /// of solving with `M`, which leaves rounding (~1e-17) in `ÿ`.
    #[lagrange(jacobians)]
    pub struct Coupled {
        coordinates: x, y;
        kinetic: dot(x)^2 + dot(x)*dot(y) + dot(y)^2;
        potential: x^2 + x*y + y^2;
    }
}

type Start<const N: usize> = (f64, SVector<f64, N>, SVector<f64, N>);

/// Runs the fixed-step `method` with step `h` and a step budget.
fn fixed<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    method: Method,
    h: f64,
    max_steps: usize,
    model: &L,
    (t0, q0, v0): Start<N>,
    times: &[f64],
) -> IntegrationResult<f64, N> {
    assert!(!method.is_adaptive(), "{method:?}");
    method
        .with_step(h)
        .max_steps(max_steps)
        .integrate(model, t0, q0, v0, times)
}

/// Runs the adaptive `method` with `rtol`, `atol` and a step budget.
fn adaptive<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    method: Method,
    (rtol, atol): (f64, f64),
    max_steps: usize,
    model: &L,
    (t0, q0, v0): Start<N>,
    times: &[f64],
) -> IntegrationResult<f64, N> {
    assert!(method.is_adaptive(), "{method:?}");
    method
        .with_tolerance(rtol)
        .tolerances(rtol, atol)
        .max_steps(max_steps)
        .integrate(model, t0, q0, v0, times)
}

/// Released from x = 1 at rest, at t = 0.
fn released() -> Start<1> {
    (0.0, Vector1::new(1.0), Vector1::new(0.0))
}

/// The default budget of the fixed-step methods.
const FIXED_BUDGET: usize = 10_000_000;
/// The default budget of the adaptive ones.
const ADAPTIVE_BUDGET: usize = 100_000;

/// Every `1/10` up to 10.
fn samples() -> Vec<f64> {
    (1..=100).map(|k| 0.1 * k as f64).collect()
}

/// Beyond the stability limit each explicit fixed-step method amplifies a
/// mode by `|R(hλ)| > 1` per step; the run must stop with `Unstable` and a
/// finite state, keeping the samples before. Two stiff modes, `|λ| = 1000`:
///
/// - a stiff spring (`k = 10⁶`, undamped, `λ = ±1000 i`): RK4 is stable up
///   to `hω = 2√2`, symplectic Euler up to 2; explicit Euler never is on the
///   imaginary axis (it gains `√(1 + h²ω²)` per step), so its rows are `hω`
///   itself, from 0.4 up (see the next test for below);
/// - a stiff damper (`k = 1`, `c = 1000`, `λ ≈ −1000`): explicit and
///   symplectic Euler are stable for `h|λ| ≤ 2`, RK4 for `h|λ| ≤ 2.785`.
///
/// Samples every 50 steps, 2000 steps in all, so that the driver's steps are
/// `h` itself (it cuts each interval into equal steps no longer than `h`:
/// with other sample times the step taken may be below the limit although
/// `h` is not). At `f = 0.9` of the limit every run reaches the end; at 1.01
/// to 100 it stops. Just beyond the limit the growth is slow (RK4 on the
/// damper: 2 % per step), and the guard waits until the state is 8000× its
/// starting scale to be sure it is not physics: the detection time is
/// printed.
#[test]
fn explicit_steps_beyond_the_stability_limit_stop_with_unstable() {
    let spring = unit_spring(1e6, 0.0);
    let damper = unit_spring(1.0, 1000.0);
    let lambda = (1000.0 + (1000.0f64.powi(2) - 4.0).sqrt()) / 2.0;
    let cases: [(&str, &Oscillator, Method, f64, f64); 5] = [
        ("stiff spring", &spring, Method::Rk4, 8f64.sqrt(), 1000.0),
        (
            "stiff spring",
            &spring,
            Method::SymplecticEuler,
            2.0,
            1000.0,
        ),
        ("stiff damper", &damper, Method::ExplicitEuler, 2.0, lambda),
        (
            "stiff damper",
            &damper,
            Method::SymplecticEuler,
            2.0,
            lambda,
        ),
        ("stiff damper", &damper, Method::Rk4, 2.785, lambda),
    ];
    let every_50_steps = |h: f64| (1..=40).map(|i| (50 * i) as f64 * h).collect::<Vec<_>>();
    let unstable = |model_name: &str, model: &Oscillator, method: Method, h: f64, row: String| {
        let times = every_50_steps(h);
        let failure = fixed(method, h, FIXED_BUDGET, model, released(), &times)
            .expect_err(&format!("{method:?}"));
        let IntegrationError::Unstable { t, q, qdot, .. } = failure.error else {
            panic!(
                "{model_name}, {method:?}, {row}: expected Unstable, got {}",
                failure.error
            );
        };
        let kept = failure.trajectory.len();
        let steps = failure.trajectory.stats().steps_accepted;
        let size = q[0].abs().max(qdot[0].abs());
        println!(
            "steps | {model_name} | {method:?} {row} | Unstable at t = {t:.4} after {steps} steps, |y| = {size:.1e}, {kept} samples kept"
        );
        assert!(
            size.is_finite() && size < 1e300,
            "{method:?}: |y| = {size:e}"
        );
        assert_eq!(failure.trajectory.times(), &times[..kept]);
    };
    for (model_name, model, method, limit, rate) in cases {
        let h = 0.9 * limit / rate;
        let stable = fixed(
            method,
            h,
            FIXED_BUDGET,
            model,
            released(),
            &every_50_steps(h),
        );
        assert!(
            stable.is_ok(),
            "{method:?} at 0.9 of its limit: {}",
            stable.unwrap_err()
        );
        for f in [1.01, 1.1, 2.0, 10.0, 100.0] {
            let h = f * limit / rate;
            let row = format!("h = {f} × limit (h|λ| = {:.3})", h * rate);
            unstable(model_name, model, method, h, row);
        }
    }
    for h_omega in [0.4, 1.0, 10.0, 100.0] {
        let row = format!("hω = {h_omega}");
        unstable(
            "stiff spring",
            &spring,
            Method::ExplicitEuler,
            h_omega / 1000.0,
            row,
        );
    }
}

/// The limit of the guard: explicit Euler on an undamped spring at
/// `hω = 0.3` gains 4.4 % per step while turning by 17°, smoothly, as a
/// physical instability could; the guard lets it run (no false alarm is
/// worth more than an early stop here). It overflows at t ≈ 4.9 (16 000
/// steps): the forcing of a state of 1e302 is infinite, reported as
/// `NonFiniteState`, with the samples before. Stopping it earlier would take
/// knowing the model's eigenvalues; a shorter run returns its growing, but
/// finite, samples.
#[test]
fn explicit_euler_slow_gain_below_the_guard_overflows_into_non_finite_state() {
    let spring = unit_spring(1e6, 0.0);
    let times = samples();
    let failure = fixed(
        Method::ExplicitEuler,
        0.3 / 1000.0,
        FIXED_BUDGET,
        &spring,
        released(),
        &times,
    )
    .expect_err("overflow");
    let IntegrationError::NonFiniteState { t, q, .. } = failure.error else {
        panic!("expected NonFiniteState, got {}", failure.error);
    };
    let kept = failure.trajectory.len();
    println!(
        "steps | stiff spring | ExplicitEuler hω = 0.3 | NonFiniteState (overflow) at t = {t:.3}, q = {:.1e}, {kept} samples kept",
        q[0]
    );
    // (1 + h²ω²)^(n/2) = 1.09^(n/2) carries q̇ from 10³ (ω x) to overflow
    // in n ≈ 16 000 steps of 3e-4: t ≈ 4.9.
    assert!((4.0..6.0).contains(&t), "t = {t}");
    assert_eq!(failure.trajectory.times(), &times[..kept]);
    assert!(
        failure
            .trajectory
            .iter()
            .all(|s| s.q[0].is_finite() && s.qdot[0].is_finite())
    );
}

/// A step so small that `t + h == t` cannot move the integration: every
/// fixed-step method must report `StepSizeUnderflow` at the start, before
/// any step, and return at once. Two ways to get there: `t0 = 1e20` with
/// `h = 1` (an ulp of 1e20 is 16 384), and `t0 = 1` with `h = 1e-300` (the
/// step reported is `h` itself, below an ulp of 1). The adaptive methods
/// land in the same error from `t0 = 1e20`: their step may not go below
/// `10 ε |t| = 2.2e5` there, more than the whole span.
///
/// From `t0 = 0` the same `h = 1e-300` does advance `t` (floats are dense
/// near 0), but the span needs 1e300 steps of it: `TooManySteps` at `t0`
/// before any step (timed), whatever the budget, and the step is never
/// lengthened to fit the budget.
#[test]
fn a_step_that_does_not_advance_time_is_step_size_underflow() {
    let spring = unit_spring(1.0, 0.0);
    let (x0, v0) = (Vector1::new(1.0), Vector1::new(0.0));
    for (t0, h, end) in [(1e20, 1.0, 1e20 + 1e5), (1.0, 1e-300, 2.0)] {
        let start = (t0, x0, v0);
        let mut runs: Vec<(Method, IntegrationResult<f64, 1>)> = Method::FIXED_STEP
            .iter()
            .map(|&method| {
                let run = fixed(method, h, FIXED_BUDGET, &spring, start, &[end]);
                (method, run)
            })
            .collect();
        if t0 == 1e20 {
            runs.extend(Method::ADAPTIVE.iter().map(|&method| {
                let tolerances = (1e-8, 1e-8);
                (
                    method,
                    adaptive(method, tolerances, ADAPTIVE_BUDGET, &spring, start, &[end]),
                )
            }));
        }
        for (method, run) in runs {
            let name = &format!("{method:?}");
            let failure = run.expect_err(name);
            let IntegrationError::StepSizeUnderflow {
                t,
                h: h_tried,
                q,
                qdot,
            } = failure.error
            else {
                panic!(
                    "{name} from t0 = {t0:e}, h = {h:e}: expected StepSizeUnderflow, got {}",
                    failure.error
                );
            };
            let stats = failure.trajectory.stats();
            println!(
                "steps | t0 = {t0:e}, h = {h:e} | {name} | StepSizeUnderflow at t = {t:e} with h = {h_tried:.2e}, {} steps, {} rhs",
                stats.steps_accepted, stats.rhs_evals
            );
            assert_eq!((t, q, qdot), (t0, x0, v0), "{name}");
            assert!(
                t + h_tried == t || h_tried <= 10.0 * f64::EPSILON * t,
                "{name}"
            );
            assert_eq!(stats.steps_accepted, 0, "{name}");
            assert!(failure.trajectory.is_empty(), "{name}");
        }
    }

    let clock = Instant::now();
    let failure = fixed(
        Method::ExplicitEuler,
        1e-300,
        FIXED_BUDGET,
        &spring,
        released(),
        &[1.0],
    )
    .expect_err("the default budget");
    let elapsed = clock.elapsed();
    let IntegrationError::TooManySteps { t, max_steps, .. } = failure.error else {
        panic!("expected TooManySteps, got {}", failure.error);
    };
    println!(
        "steps | t0 = 0, h = 1e-300 | ExplicitEuler, default budget | TooManySteps (budget {max_steps}) at t = {t:.2e}, before any step, {:.2} s",
        elapsed.as_secs_f64()
    );
    assert_eq!(max_steps, 10_000_000);
    // 1e300 steps needed: refused before any step.
    assert_eq!((t, failure.trajectory.stats().steps_accepted), (0.0, 0));
    for method in Method::FIXED_STEP {
        let name = &format!("{method:?}");
        let failure = fixed(method, 1e-300, 1000, &spring, released(), &[1.0]).expect_err(name);
        assert!(
            matches!(
                failure.error,
                IntegrationError::TooManySteps {
                    max_steps: 1000,
                    ..
                }
            ),
            "{name}: {}",
            failure.error
        );
    }
}

/// Tolerances the arithmetic cannot honour, for each adaptive method:
///
/// - `rtol = 1e-20` (below `10 ε`) or `atol = 0` is refused up front,
///   `InvalidInput`, before any evaluation;
/// - the tightest legal one, `rtol = 10 ε`, `atol = 1e-20`, is honoured:
///   the run ends, at a cost (printed), within ~100 ε·steps of `cos t`;
/// - `rtol = 1e-14`, `atol = 1e-300` on a coordinate that stays near
///   rounding level asks it to be right to ~1e-42. Dopri5 and DOP853 manage
///   that with steps of ~1e-11 and crawl until their budget of 100 000
///   steps ends the run (`TooManySteps` at t ≈ 2e-6); Radau5 passes a
///   handful of steps, then cuts `h` (by ≥ 2× per rejection) until it
///   underflows (`StepSizeUnderflow` near t = 1e-295). Either way a clear
///   error within the budget, never a hang.
#[test]
fn impossible_tolerances_end_in_a_clear_error() {
    let spring = unit_spring(1.0, 0.0);
    let min_rtol = 10.0 * f64::EPSILON;
    for method in Method::ADAPTIVE {
        let name = &format!("{method:?}");
        // A third-order pair at 10 ε takes steps of the order of
        // (10 ε)^(1/3) (340 000 over these 10 s, measured), beyond the
        // budget the others meet.
        let budget = if method.order() < 5 {
            100 * ADAPTIVE_BUDGET
        } else {
            ADAPTIVE_BUDGET
        };
        let run = |rtol, atol| adaptive(method, (rtol, atol), budget, &spring, released(), &[10.0]);
        let failure = run(1e-20, 1e-20).expect_err(name);
        assert!(
            matches!(
                failure.error,
                IntegrationError::InvalidInput(InvalidInput::InvalidRelativeTolerance { .. })
            ),
            "{name}: {}",
            failure.error
        );
        assert_eq!(failure.trajectory.stats().rhs_evals, 0);
        let failure = run(1e-8, 0.0).expect_err(name);
        assert!(
            matches!(
                failure.error,
                IntegrationError::InvalidInput(InvalidInput::InvalidAbsoluteTolerance { .. })
            ),
            "{name}: {}",
            failure.error
        );
        assert_eq!(failure.trajectory.stats().rhs_evals, 0);
        println!(
            "steps | {name} rtol = 1e-20 | InvalidInput (relative tolerance below 10 ε), 0 rhs"
        );

        let clock = Instant::now();
        let tight = run(min_rtol, 1e-20).unwrap_or_else(|f| panic!("{name}: {f}"));
        let elapsed = clock.elapsed();
        let end = tight.last().unwrap();
        let error = (end.q[0] - 10f64.cos())
            .abs()
            .max((end.qdot[0] + 10f64.sin()).abs());
        let stats = tight.stats();
        println!(
            "steps | {name} rtol = 10 ε, atol = 1e-20 | ok, {} steps ({} rejected), {} rhs, {:.2} ms, error at t = 10: {error:.1e}",
            stats.steps_accepted,
            stats.steps_rejected,
            stats.rhs_evals,
            elapsed.as_secs_f64() * 1e3
        );
        // Rounding alone adds ~ε per step; 100 ε per step is generous for
        // the method's own error at 10 ε, and 1e-9 a loose cap.
        assert!(
            error <= (100.0 * f64::EPSILON * stats.steps_accepted as f64).min(1e-9),
            "{name}: {error:e}"
        );
    }

    // atol = 1e-300 on a coordinate y = 1e-10, asked to be right to ~1e-24,
    // below the rounding x's terms leave in its acceleration. From exactly 0
    // it would stay exactly 0 (the solve of M q̈ = f is exact there) and any
    // atol would be met.
    let coupled = Coupled::new();
    let (q0, qdot0) = (Vector2::new(1.0, 1e-10), Vector2::zeros());
    let start = (0.0, q0, qdot0);
    let runs = Method::ADAPTIVE.map(|method| {
        (
            format!("{method:?}"),
            adaptive(
                method,
                (1e-14, 1e-300),
                ADAPTIVE_BUDGET,
                &coupled,
                start,
                &[1.0],
            ),
        )
    });
    for (name, run) in runs {
        let failure = run.expect_err(&name);
        let stats = failure.trajectory.stats();
        let attempts = stats.steps_accepted + stats.steps_rejected;
        let outcome = match failure.error {
            IntegrationError::StepSizeUnderflow { t, h, .. } => {
                format!("StepSizeUnderflow at t = {t:.1e}, h = {h:.1e}")
            }
            IntegrationError::TooManySteps { t, .. } => format!("TooManySteps at t = {t:.1e}"),
            other => panic!("{name}: expected StepSizeUnderflow or TooManySteps, got {other}"),
        };
        println!(
            "steps | {name} rtol = 1e-14, atol = 1e-300, a coordinate near rounding level | {outcome} after {attempts} attempts ({} accepted), {} rhs",
            stats.steps_accepted, stats.rhs_evals
        );
        assert!(attempts <= ADAPTIVE_BUDGET, "{stats:?}");
        assert!(failure.trajectory.is_empty());
    }
}

/// A step budget that runs out ends every method with `TooManySteps`,
/// stating the budget, the time reached and the state there, and keeping
/// every sample up to that time: 25 steps from t = 0, samples every 0.1.
/// The fixed-step methods (h = 0.01) stop at exactly t = 0.25; the adaptive
/// ones (tolerance 1e-10) wherever 25 attempts got them. The state at the
/// stop is the method's own: within its error of `cos t` (first order:
/// ≈ h t / 2 ≈ 1.3e-3, so 5e-3; second order: the phase error h² t / 12 ≈
/// 2e-6, so 1e-5; the others, and the adaptive ones at 1e-10, 1e-6). The
/// third-order pair runs at 1e-6 instead, where 25 of its steps pass a
/// sample (at 1e-10 its steps of about 1e-3 reach none), its state within
/// 1e-4 (25 steps, each within the tolerance, with room for the error's
/// growth over a quarter period).
#[test]
fn an_exhausted_step_budget_is_too_many_steps_with_the_samples_so_far() {
    let spring = unit_spring(1.0, 0.0);
    let times = samples();
    let (h, budget) = (0.01, 25);
    for method in Method::ALL {
        let name = &format!("{method:?}");
        let third_order = method.is_adaptive() && method.order() < 5;
        let tol = if third_order { 1e-6 } else { 1e-10 };
        let run = if method.is_adaptive() {
            adaptive(method, (tol, tol), budget, &spring, released(), &times)
        } else {
            fixed(method, h, budget, &spring, released(), &times)
        };
        let failure = run.expect_err(name);
        let IntegrationError::TooManySteps {
            t,
            max_steps,
            q,
            qdot,
        } = failure.error
        else {
            panic!("{name}: expected TooManySteps, got {}", failure.error);
        };
        let stats = failure.trajectory.stats();
        let kept = failure.trajectory.times();
        let error = (q[0] - t.cos()).abs().max((qdot[0] + t.sin()).abs());
        println!(
            "steps | budget 25 | {name} | TooManySteps at t = {t:.4}, {} samples kept, {} accepted + {} rejected steps, state error {error:.1e}",
            kept.len(),
            stats.steps_accepted,
            stats.steps_rejected
        );
        assert_eq!(max_steps, budget, "{name}");
        assert_eq!(
            stats.steps_accepted + stats.steps_rejected,
            budget,
            "{name}"
        );
        if !method.is_adaptive() {
            assert!((t - 0.25).abs() < 1e-15, "{name}: t = {t}");
        }
        assert_eq!(kept, &times[..kept.len()], "{name}");
        assert!(
            kept.iter().all(|&s| s <= t) && times[kept.len()] > t,
            "{name}: kept {kept:?}, t = {t}"
        );
        assert!(!kept.is_empty(), "{name}");
        let allowed = match method.order() {
            1 => 5e-3,
            2 => 1e-5,
            _ if third_order => 1e-4,
            _ => 1e-6,
        };
        assert!(error <= allowed, "{name}: error {error:e}");
    }
}
