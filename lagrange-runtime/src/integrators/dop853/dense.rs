//! DOP853's continuous extension of order seven, Hairer's `contd8`.

use nalgebra::{RealField, SVector};

use super::stages::{Stages, Step};
use super::tableau;

/// Hairer's `contd8` on one accepted step, with `s = θ`, `s₁ = 1 − θ`:
/// `y(t + θh) = r₁ + s(r₂ + s₁(r₃ + s(r₄ + s₁(r₅ + s(r₆ + s₁(r₇ + s r₈))))))`.
pub struct Dense<S, const N: usize> {
    q: [SVector<S, N>; 8],
    qdot: [SVector<S, N>; 8],
}

impl<S: RealField + Copy, const N: usize> Dense<S, N> {
    /// Hairer's coefficients `r₁…r₈` for `q` and `q̇`, from a step whose
    /// stages 13–16 are filled in.
    pub(super) fn new(
        h: S,
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        step: &Step<S, N>,
        k: &Stages<S, N>,
    ) -> Self {
        let high = tableau::D.each_ref().map(|d| k.sum(d));
        let coefficients = |y0: &SVector<S, N>,
                            y1: &SVector<S, N>,
                            k: &[SVector<S, N>; 16],
                            r: [&SVector<S, N>; 4]| {
            let diff = y1 - y0;
            let bspl = k[0] * h - diff;
            let r4 = diff - k[12] * h - bspl;
            [*y0, diff, bspl, r4, r[0] * h, r[1] * h, r[2] * h, r[3] * h]
        };
        Self {
            q: coefficients(q, &step.q, &k.q, high.each_ref().map(|r| &r.0)),
            qdot: coefficients(qdot, &step.qdot, &k.qdot, high.each_ref().map(|r| &r.1)),
        }
    }

    pub(super) fn at(&self, theta: S) -> (SVector<S, N>, SVector<S, N>) {
        let eval = |r: &[SVector<S, N>; 8]| {
            let s1 = S::one() - theta;
            let high = r[4] + (r[5] + (r[6] + r[7] * theta) * s1) * theta;
            r[0] + (r[1] + (r[2] + (r[3] + high * s1) * theta) * s1) * theta
        };
        (eval(&self.q), eval(&self.qdot))
    }
}
