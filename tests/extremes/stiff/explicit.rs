//! The explicit methods: fixed steps beyond their stability limit stop,
//! adaptive ones pay for the fast mode with steps.

use super::modes::{Modes, measure};
use super::{RATIOS, T, chain, ratio_name, samples};
use lagrange::IntegrationResult;
use lagrange::prelude::*;

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
        // About ×10, as ω_fast; where the step settles at the stability
        // edge depends on rounding in the fast mode (STABILITY.md §3): a
        // rounding-level change of Dop853's stage sums once gave 39 670 and
        // 1 162 742 evaluations, ×29, and the representable step of the
        // clock ×21.8 (45 649 and 995 980). So ×10 within a factor 3.
        assert!((3.3..=30.0).contains(&growth), "{name}: {growth}");
    }
}
