//! `lagrange_runtime::analysis`: linearization against differences of the
//! accelerations, equilibria found and refused, normal modes against
//! closed forms, and `B` of an actuated model.

mod actuated;
mod equilibria;
mod linearization;
mod manifold;
mod models;
mod modes;

use lagrange_runtime::Lagrangian;
use lagrange_runtime::dynamics::acceleration;
use lagrange_runtime::nalgebra::{SMatrix, SVector};

/// `(∂q̈/∂q, ∂q̈/∂q̇)` by central differences of [`acceleration`], written
/// here independently of the library's own: step `h = ε^(1/3) max(1, |x|)`,
/// whose error is truncation `h² |∂³q̈| / 6` plus rounding `ε |q̈| / h`,
/// both `≈ ε^(2/3) ≈ 4e-11` times the size of `q̈` and its derivatives.
pub fn differences<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    model: &L,
    q: &SVector<f64, N>,
    qdot: &SVector<f64, N>,
) -> (SMatrix<f64, N, N>, SMatrix<f64, N, N>) {
    let step = |x: f64| f64::EPSILON.cbrt() * x.abs().max(1.0);
    let acc = |q: &SVector<f64, N>, v: &SVector<f64, N>| acceleration(model, 0.0, q, v).unwrap();
    let mut dq = SMatrix::<f64, N, N>::zeros();
    let mut dv = dq;
    for k in 0..N {
        let (mut qp, mut qm) = (*q, *q);
        qp[k] += step(q[k]);
        qm[k] -= step(q[k]);
        dq.set_column(k, &((acc(&qp, qdot) - acc(&qm, qdot)) / (qp[k] - qm[k])));
        let (mut vp, mut vm) = (*qdot, *qdot);
        vp[k] += step(qdot[k]);
        vm[k] -= step(qdot[k]);
        dv.set_column(k, &((acc(q, &vp) - acc(q, &vm)) / (vp[k] - vm[k])));
    }
    (dq, dv)
}

/// SplitMix64: reproducible states without a dependency.
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        lo + (hi - lo) * (z >> 11) as f64 / (1u64 << 53) as f64
    }
}
