//! Radau5, L-stable: steps that follow the slow mode alone.

use super::modes::{Modes, measure};
use super::{RATIOS, chain, ratio_name, samples};
use lagrange::prelude::*;

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
