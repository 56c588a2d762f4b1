//! The symmetric implicit methods: bounded, the fast mode kept but its
//! phase aliased.

use super::modes::Modes;
use super::{C, EPS, RATIOS, T, chain, ratio_name, samples};
use lagrange::IntegrationResult;
use lagrange::prelude::*;
use std::f64::consts::PI;

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
