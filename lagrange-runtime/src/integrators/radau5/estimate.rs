//! Radau5's embedded error estimate, RADAU5's `ESTRAD`.

use nalgebra::RealField;

use super::ERR_FLOOR;
use super::work::{Work, evaluate};
use crate::driver::Recorder;
use crate::linalg::second_order::solve_block;
use crate::model::Lagrangian;

impl<S: RealField + Copy, const N: usize> Work<S, N> {
    /// RADAU5's `ESTRAD`: the scaled RMS norm of the embedded error
    /// estimate `(γ̂/h − J)⁻¹ (f(y) + Σ dᵢ Zᵢ / h)`, re-estimated from
    /// `f(y + err)` when it fails on a first or rejected step (where the
    /// plain estimate is unreliable for stiff components). `None` if not
    /// finite.
    pub(super) fn estimate_error<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        model: &L,
        rec: &mut Recorder<'_, S, N>,
        t: S,
        h: S,
        refine: bool,
    ) -> Option<S> {
        let gamma = self.k.gamma / h;
        let dd = self.k.dd.map(|d| d / h);
        for i in 0..2 * N {
            let r = dd[0] * self.z[0][i] + dd[1] * self.z[1][i] + dd[2] * self.z[2][i];
            self.err_rhs[i] = r;
            self.err[i] = r + self.f0[i];
        }
        solve_block(
            &self.real,
            &self.jq,
            gamma,
            &mut self.err,
            &mut self.real_work,
        );
        rec.stats.linear_solves += 1;
        let err = self.error_norm()?;
        if err < S::one() || !refine {
            return Some(err);
        }
        self.stage.copy_from(&self.y);
        self.stage += &self.err;
        if evaluate(rec, model, t, &self.stage, &mut self.err).is_err() {
            // The plain estimate already rejects the step.
            return Some(err);
        }
        self.err += &self.err_rhs;
        solve_block(
            &self.real,
            &self.jq,
            gamma,
            &mut self.err,
            &mut self.real_work,
        );
        rec.stats.linear_solves += 1;
        self.error_norm()
    }

    fn error_norm(&self) -> Option<S> {
        let mut sum = S::zero();
        for (e, s) in self.err.iter().zip(self.scal.iter()) {
            sum += (*e / *s).powi(2);
        }
        let norm = (sum / nalgebra::convert((2 * N).max(1) as f64)).sqrt();
        // Checked before the floor: max(NaN, floor) would hide it.
        norm.is_finite()
            .then(|| norm.max(nalgebra::convert(ERR_FLOOR)))
    }
}
