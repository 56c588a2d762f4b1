//! Families of equilibria: where `∂f/∂q` (or its tangent part `K_z`) is
//! singular, Newton's step is not determined, and a cyclic coordinate, a
//! free body or a symmetry leaves a whole family at rest (a cart-pole's
//! upright pole at every cart position). The step taken is then the
//! minimum-norm one, which moves to the member of the family nearest the
//! guess, and the family's neutral directions are the null space of the
//! stiffness, found from its singular values.

use nalgebra::{DMatrix, DVector, RealField};

/// The singular value decomposition of a stiffness matrix, with the rank
/// judged against `noise` (the derivatives' relative accuracy,
/// [`relative_noise`](super::derivatives::relative_noise)): a singular
/// value below `noise` times the largest is zero.
pub(super) struct Neutral<S: RealField + Copy> {
    svd: nalgebra::SVD<S, nalgebra::Dyn, nalgebra::Dyn>,
    cutoff: S,
}

impl<S: RealField + Copy> Neutral<S> {
    pub(super) fn new(k: &DMatrix<S>, noise: S) -> Self {
        let svd = k.clone().svd(true, true);
        let largest = svd.singular_values.max();
        Self {
            svd,
            cutoff: noise * largest,
        }
    }

    /// The minimum-norm solution of `K x = r` over the directions `K`
    /// moves (the neutral ones left as they are); `None` where `K` moves
    /// none, or the result is not finite.
    pub(super) fn solve(&self, r: &DVector<S>) -> Option<DVector<S>> {
        let (u, v_t) = (self.svd.u.as_ref()?, self.svd.v_t.as_ref()?);
        let mut x = DVector::zeros(v_t.ncols());
        let mut moved = false;
        for (i, &sigma) in self.svd.singular_values.iter().enumerate() {
            if sigma > self.cutoff && sigma > S::zero() {
                let coefficient = u.column(i).dot(r) / sigma;
                x += v_t.row(i).transpose() * coefficient;
                moved = true;
            }
        }
        (moved && crate::linalg::all_finite(x.as_slice())).then_some(x)
    }

    /// An orthonormal basis of the neutral directions: the right singular
    /// vectors of the singular values at zero.
    pub(super) fn directions(&self) -> Vec<DVector<S>> {
        let Some(v_t) = self.svd.v_t.as_ref() else {
            return Vec::new();
        };
        self.svd
            .singular_values
            .iter()
            .enumerate()
            .filter(|&(_, &sigma)| sigma <= self.cutoff)
            .map(|(i, _)| v_t.row(i).transpose())
            .collect()
    }
}
