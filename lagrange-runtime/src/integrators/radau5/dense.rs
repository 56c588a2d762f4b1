//! An accepted Radau5 step: the new state, and its collocation polynomial
//! as the dense output between steps (RADAU5's `CONTR5`).

use nalgebra::{RealField, SVector};

use super::work::{Work, split};
use crate::driver::Recorder;
use crate::error::IntegrationError;
use crate::model::Lagrangian;

impl<S: RealField + Copy, const N: usize> Work<S, N> {
    /// Moves to the end of an accepted step and keeps its collocation
    /// polynomial, in Newton form on the nodes `0, c₂ − 1, c₁ − 1` (the
    /// stage times relative to the new `t`, in units of `h`) and `−1`.
    pub(super) fn accept(&mut self) {
        let k = &self.k;
        for i in 0..2 * N {
            let (z1, z2, z3) = (self.z[0][i], self.z[1][i], self.z[2][i]);
            self.y[i] += z3;
            let a1 = (z2 - z3) / k.c2m1;
            let ak = (z1 - z2) / k.c1mc2;
            let a3 = (ak - z1 / k.c[0]) / k.c[1];
            let a2 = (ak - a1) / k.c1m1;
            self.cont[0][i] = a1;
            self.cont[1][i] = a2;
            self.cont[2][i] = a2 - a3;
        }
        self.update_scale();
    }

    /// A constrained model's state at the end of the accepted step brought
    /// back onto its constraints ([`Recorder::control_drift`]). The
    /// collocation polynomial ends at `y`, so it moves with it; samples
    /// inside the step are projected on their own.
    pub(super) fn control_drift<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        rec: &mut Recorder<'_, S, N>,
        t_new: S,
    ) -> Result<(), IntegrationError<S, N>> {
        let (q, qdot) = split(&self.y);
        let (q, qdot) = rec.control_drift(model, t_new, q, qdot)?;
        self.y.rows_mut(0, N).copy_from(&q);
        self.y.rows_mut(N, N).copy_from(&qdot);
        Ok(())
    }

    /// Records the samples up to `t_new`, the end of the accepted step of
    /// size `h` whose state is now `y`.
    pub(super) fn record<L: Lagrangian<N, Scalar = S>>(
        &self,
        model: &L,
        rec: &mut Recorder<'_, S, N>,
        t_new: S,
        h: S,
    ) -> Result<(), IntegrationError<S, N>> {
        while let Some(ts) = rec.pending().filter(|&ts| ts <= t_new) {
            if ts == t_new {
                let (q, qdot) = split(&self.y);
                rec.record(ts, q, qdot);
            } else {
                let (q, qdot) = self.dense((ts - t_new) / h);
                rec.record_dense(model, ts, q, qdot)?;
            }
        }
        Ok(())
    }

    /// The collocation polynomial at `t_new + s h`, `s ∈ [−1, 0]`.
    pub(super) fn dense(&self, s: S) -> (SVector<S, N>, SVector<S, N>) {
        let k = &self.k;
        let at = |i: usize| {
            let (a1, a2, a3) = (self.cont[0][i], self.cont[1][i], self.cont[2][i]);
            self.y[i] + s * (a1 + (s - k.c2m1) * (a2 + (s - k.c1m1) * a3))
        };
        (
            SVector::from_fn(|i, _| at(i)),
            SVector::from_fn(|i, _| at(N + i)),
        )
    }
}
