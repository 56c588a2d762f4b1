//! The exact solution of the stiff pair, mode by mode, and its check.

use super::{C, EPS, RATIOS, StiffPair, T, chain, ratio_name};
use lagrange::nalgebra::{Matrix2, Matrix4, Vector2, Vector4};
use lagrange::prelude::*;

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
pub(super) struct Modes {
    /// Orthonormal shapes: slow, fast.
    pub(super) shape: [Vector2<f64>; 2],
    pub(super) omega: [f64; 2],
}

impl Modes {
    const SLOW: usize = 0;
    const FAST: usize = 1;

    pub(super) fn of(chain: &StiffPair) -> Self {
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
    pub(super) fn amplitudes(&self, q: &Vector2<f64>, qdot: &Vector2<f64>) -> [C; 2] {
        [0, 1].map(|i| {
            C::new(
                self.shape[i].dot(qdot),
                self.omega[i] * self.shape[i].dot(q),
            )
        })
    }

    pub(super) fn state(&self, z: [C; 2]) -> (Vector2<f64>, Vector2<f64>) {
        let q =
            self.shape[0] * (z[0].im / self.omega[0]) + self.shape[1] * (z[1].im / self.omega[1]);
        let qdot = self.shape[0] * z[0].re + self.shape[1] * z[1].re;
        (q, qdot)
    }

    /// `z(t) = e^{iωt} z(0)`; the phase `ωt` is rounded to ε ωt
    /// (3e-11 rad for the fast mode at 10⁸, t = 10).
    pub(super) fn exact_amplitudes(&self, t: f64, z0: [C; 2]) -> [C; 2] {
        [0, 1].map(|i| z0[i] * C::from_polar(1.0, self.omega[i] * t))
    }

    /// The slow mode alone, `x ≈ (0.1, 0.1)`, at rest: the stiff spring is
    /// at its quasi-static stretch, and only rounding excites the fast mode.
    pub(super) fn slow_start(&self) -> (Vector2<f64>, Vector2<f64>) {
        (
            self.shape[Self::SLOW] * (0.1 * 2f64.sqrt()),
            Vector2::zeros(),
        )
    }

    /// The slow start plus the fast mode displaced by 1e-6: the stiff spring
    /// rings with velocity amplitude 1e-6 ω (1.4e-3 and 1.4e-2).
    pub(super) fn ringing_start(&self) -> (Vector2<f64>, Vector2<f64>) {
        let (q, qdot) = self.slow_start();
        (q + self.shape[Self::FAST] * 1e-6, qdot)
    }
}

/// What a run did to each mode, against the exact solution.
#[derive(Debug)]
pub(super) struct Measured {
    /// Worst `|z_slow − exact| / |z_slow(0)|` over the samples.
    pub(super) slow_error: f64,
    /// `|z_slow − exact|` at the last sample, where every method ends a step.
    pub(super) end_slow_error: f64,
    /// `max(|q − exact|, |q̇ − exact|)` at the last sample.
    pub(super) end_error: f64,
    /// Worst `|q − exact|` and `|q̇ − exact|` over the samples.
    pub(super) q_error: f64,
    pub(super) qdot_error: f64,
    /// The fast mode's displacement amplitude `|z_fast| / ω` at the end.
    pub(super) fast_amplitude: f64,
}

pub(super) fn measure(
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
