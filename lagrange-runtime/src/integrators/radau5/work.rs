//! The workspace of one Radau5 integration (or stepper): everything its
//! steps compute, allocated once.

use nalgebra::{Complex, DMatrix, DVector, RealField, SVector};

use super::Radau5;
use super::coefficients::Coefficients;
use crate::driver::Recorder;
use crate::error::IntegrationError;
use crate::linalg::lu::Lu;
use crate::model::Lagrangian;

/// Everything one integration needs, allocated once in [`Work::new`]: the
/// vectors have `2N` entries (`q` then `q̇`), the matrices `N × N`.
pub(super) struct Work<S: RealField + Copy, const N: usize> {
    pub(super) k: Coefficients<S>,
    /// RADAU5's transformed tolerances (see [`Radau5`]).
    pub(super) rtol: S,
    pub(super) atol: S,
    /// Newton stops when its predicted remaining error is below this (in
    /// units of the tolerance).
    pub(super) fnewt: S,
    /// The state at `t` and its derivative `(q̇, q̈)` there.
    pub(super) y: DVector<S>,
    pub(super) f0: DVector<S>,
    /// `atol' + rtol' |y|` at the start of the step.
    pub(super) scal: DVector<S>,
    /// Stage increments `Zᵢ = Yᵢ − y`; during an iteration, the stage
    /// derivatives and then the Newton corrections.
    pub(super) z: [DVector<S>; 3],
    /// The increments in eigen-coordinates, `W = (T⁻¹ ⊗ I) Z`.
    pub(super) w: [DVector<S>; 3],
    /// The collocation polynomial of the last accepted step (its value at
    /// the end is `y`).
    pub(super) cont: [DVector<S>; 3],
    /// Scratch: a stage state, the error estimate and its right-hand side.
    pub(super) stage: DVector<S>,
    pub(super) err: DVector<S>,
    pub(super) err_rhs: DVector<S>,
    /// `∂q̈/∂q` and `∂q̈/∂q̇` at the state of the last Jacobian evaluation.
    pub(super) jq: DMatrix<S>,
    pub(super) jv: DMatrix<S>,
    /// Factors of `γ̂/h I − ∂q̈/∂q̇ − h/γ̂ ∂q̈/∂q` (the real block) and of the
    /// same with `(α̂ + iβ̂)/h` (the complex block).
    pub(super) real: Lu<S>,
    pub(super) complex: Lu<Complex<S>>,
    pub(super) real_work: DVector<S>,
    pub(super) complex_rhs: DVector<Complex<S>>,
    pub(super) complex_work: DVector<Complex<S>>,
}

impl<S: RealField + Copy, const N: usize> Work<S, N> {
    pub(super) fn new(settings: &Radau5<S>) -> Self {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let rtol = c(0.1) * settings.rtol.powf(c(2.0 / 3.0));
        let atol = rtol * (settings.atol / settings.rtol);
        let eps = S::default_epsilon();
        let fnewt = (c(10.0) * eps / rtol).max(c(0.03).min(rtol.sqrt()));
        let vector = || DVector::<S>::zeros(2 * N);
        Self {
            k: Coefficients::new(),
            rtol,
            atol,
            fnewt,
            y: vector(),
            f0: vector(),
            scal: vector(),
            z: [vector(), vector(), vector()],
            w: [vector(), vector(), vector()],
            cont: [vector(), vector(), vector()],
            stage: vector(),
            err: vector(),
            err_rhs: vector(),
            jq: DMatrix::zeros(N, N),
            jv: DMatrix::zeros(N, N),
            real: Lu::new(N),
            complex: Lu::new(N),
            real_work: DVector::zeros(N),
            complex_rhs: DVector::zeros(2 * N),
            complex_work: DVector::zeros(N),
        }
    }

    /// The scale-free first guess of Hairer's `hinit`: 1 % of the time in
    /// which `y` would change by its own size. (RADAU5 leaves the first step
    /// to the caller; a guess too large is cut tenfold by the first-step
    /// rule, one too small grows up to 8× per step.)
    pub(super) fn initial_step(&self, h_max: S) -> S {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let (mut dny, mut dnf) = (S::zero(), S::zero());
        for i in 0..2 * N {
            dny += (self.y[i] / self.scal[i]).powi(2);
            dnf += (self.f0[i] / self.scal[i]).powi(2);
        }
        let h0 = (dny / dnf).sqrt() * c(0.01);
        // y or ẏ negligible, or a norm overflowing (a tiny atol): RADAU5's
        // default first step.
        let degenerate = dnf <= c(1e-10) || dny <= c(1e-10) || !(h0.is_finite() && h0 > S::zero());
        if degenerate { c(1e-6) } else { h0 }.min(h_max)
    }

    /// The state `(q, q̇)` as the current `y`.
    pub(super) fn load(&mut self, q: &SVector<S, N>, qdot: &SVector<S, N>) {
        self.y.rows_mut(0, N).copy_from(q);
        self.y.rows_mut(N, N).copy_from(qdot);
    }

    pub(super) fn update_scale(&mut self) {
        for (s, y) in self.scal.iter_mut().zip(self.y.iter()) {
            *s = self.atol + self.rtol * y.abs();
        }
    }
}

/// `ẏ = (q̇, q̈)` at `(t, y)` into `out`: one counted right-hand side.
pub(super) fn evaluate<L: Lagrangian<N>, const N: usize>(
    rec: &mut Recorder<'_, L::Scalar, N>,
    model: &L,
    t: L::Scalar,
    y: &DVector<L::Scalar>,
    out: &mut DVector<L::Scalar>,
) -> Result<(), IntegrationError<L::Scalar, N>> {
    let (q, qdot) = split(y);
    let qddot = rec.rhs(model, t, &q, &qdot)?;
    out.rows_mut(0, N).copy_from(&qdot);
    out.rows_mut(N, N).copy_from(&qddot);
    Ok(())
}

/// `(q, q̇)` from a `2N` state vector.
pub(super) fn split<S: RealField + Copy, const N: usize>(
    y: &DVector<S>,
) -> (SVector<S, N>, SVector<S, N>) {
    (
        SVector::from_fn(|i, _| y[i]),
        SVector::from_fn(|i, _| y[N + i]),
    )
}
