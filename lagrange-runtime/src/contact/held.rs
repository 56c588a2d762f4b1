//! The model's own constraints in a contact run (`constraints:` beside
//! `contacts:`: a body in unit quaternions, a closed loop, a rolling
//! wheel): always held, two-sided, their multipliers solved with the
//! contacts' forces.
//!
//! Every solve of a contact run goes through [`Terms`](super::phase::Terms):
//! with constraints `B q̈ = −γ_B` held, its responses to a force `d` are
//! the constrained ones, `P d` with `P = M⁻¹ − M⁻¹ Bᵀ (B M⁻¹ Bᵀ)⁻¹ B M⁻¹`
//! (the accelerations `d` gives while the constraints hold: `B P d = 0`),
//! and its free accelerations are the constrained model's, with the bias.
//! The complementarity problems, impacts and forces of the contacts are
//! then written once, for `M⁻¹` and `P` alike: an impulse changes the
//! velocities by `P Dᵀ p`, which keeps `B q̇` as it was. Where `M` is
//! regular only on the constraints (a quaternion's four rates, of which the
//! kinetic energy sees three), the metric is `M + k BᵀB` and the forcing
//! `f − k Bᵀγ_B`, as in every constrained run
//! ([`Holonomic::mass_regular_on_constraints_only`]).

use nalgebra::{Cholesky, DMatrix, DVector, Dyn, RealField, SMatrix, SVector};

use crate::linalg::mass::MassFactor;
use crate::model::constraints::{Holonomic, Visitor};
use crate::model::settings::ConstraintSettings;

/// The model's constraints at a state, their number the model's (`C`,
/// which the erased model does not know).
pub(crate) struct Held<S: RealField + Copy> {
    /// `φ(t, q)` (zero on the rows of velocity constraints); empty where
    /// the residuals were not asked for.
    pub(crate) values: DVector<S>,
    /// `B = ∂φ/∂q`, `C × N`.
    pub(crate) jacobian: DMatrix<S>,
    /// `φ̇ = B q̇ + ∂φ/∂t`; empty where the residuals were not asked for.
    pub(crate) velocities: DVector<S>,
    /// `γ_B` with `φ̈ = B q̈ + γ_B`.
    pub(crate) bias: DVector<S>,
    /// Which rows are constraints on the velocities (no position level).
    pub(crate) velocity_rows: Vec<bool>,
    /// Whether `M` is regular only on the constraints.
    pub(crate) regular_only: bool,
}

/// The visit that reads [`Held`] off a model at `(t, q, q̇)`: `φ` and `φ̇`
/// only where `residuals` asks (a projection), not in the solves of every
/// right-hand side.
pub(crate) struct Read<'a, S: RealField + Copy, const N: usize> {
    pub(crate) t: S,
    pub(crate) q: &'a SVector<S, N>,
    pub(crate) qdot: &'a SVector<S, N>,
    pub(crate) residuals: bool,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Read<'_, S, N> {
    type Output = Held<S>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Held<S>
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let Self {
            t,
            q,
            qdot,
            residuals,
        } = self;
        let dynamic = |v: SVector<S, C>| DVector::from_column_slice(v.as_slice());
        let jacobian = model.constraint_jacobian(t, q);
        let (values, velocities) = if residuals {
            (
                dynamic(model.constraints(t, q)),
                dynamic(model.constraint_velocities(t, q, qdot)),
            )
        } else {
            (DVector::zeros(0), DVector::zeros(0))
        };
        Held {
            values,
            jacobian: DMatrix::from_fn(C, N, |i, j| jacobian[(i, j)]),
            velocities,
            bias: dynamic(model.constraint_bias(t, q, qdot)),
            velocity_rows: model.velocity_constraint_rows().to_vec(),
            regular_only: model.mass_regular_on_constraints_only(),
        }
    }
}

impl<S: RealField + Copy> Held<S> {
    /// Row `i` of `B` as a vector of the coordinates.
    pub(crate) fn row<const N: usize>(&self, i: usize) -> SVector<S, N> {
        SVector::from_fn(|j, _| self.jacobian[(i, j)])
    }

    /// The metric the run solves with: `M`, or `M + k BᵀB` where `M` is
    /// regular only on the constraints (`k` the ratio of the largest
    /// entries of `M` and `BᵀB`), and `k` (zero for `M`).
    pub(crate) fn metric<const N: usize>(&self, m: &SMatrix<S, N, N>) -> (SMatrix<S, N, N>, S) {
        if !self.regular_only {
            return (*m, S::zero());
        }
        let mut btb = SMatrix::<S, N, N>::zeros();
        for i in 0..self.jacobian.nrows() {
            let r = self.row::<N>(i);
            btb += r * r.transpose();
        }
        let k = crate::linalg::schur::regularization_weight(m, &btb);
        (m + btb * k, k)
    }
}

/// The constrained solves of one state: `M⁻¹ Bᵀ` (in the metric) and the
/// Cholesky factor of `B M⁻¹ Bᵀ`.
pub(crate) struct HeldSolve<S: RealField + Copy, const N: usize> {
    rows: Vec<SVector<S, N>>,
    bias: DVector<S>,
    responses: Vec<SVector<S, N>>,
    schur: Cholesky<S, Dyn>,
    k: S,
}

impl<S: RealField + Copy, const N: usize> HeldSolve<S, N> {
    /// `None` where `B M⁻¹ Bᵀ` is not positive definite: constraints that
    /// are dependent, or a zero row.
    pub(crate) fn new(factor: &MassFactor<S, N>, held: &Held<S>, k: S) -> Option<Self> {
        let c = held.jacobian.nrows();
        let rows: Vec<SVector<S, N>> = (0..c).map(|i| held.row(i)).collect();
        let responses = rows
            .iter()
            .map(|r| factor.solve(r).ok())
            .collect::<Option<Vec<_>>>()?;
        let schur = DMatrix::from_fn(c, c, |i, j| rows[i].dot(&responses[j]));
        let schur = Cholesky::new(schur)?;
        // Constraints that have become parallel: a pivot below `C ε`
        // times the largest.
        let l = schur.l_dirty();
        let eps = nalgebra::convert::<f64, S>(c as f64) * S::default_epsilon();
        let diagonal: Vec<S> = (0..c).map(|i| l[(i, i)]).collect();
        let scale = diagonal.iter().fold(S::zero(), |m, &d| m.max(d));
        let floor = eps * scale * scale;
        if !diagonal.iter().all(|&d| d.is_finite() && d * d > floor) {
            return None;
        }
        Some(Self {
            rows,
            bias: held.bias.clone(),
            responses,
            schur,
            k,
        })
    }

    /// `x − M⁻¹ Bᵀ μ` with `B (x − M⁻¹ Bᵀ μ) = −bias`, `x = M⁻¹ b`
    /// given: the constraints' part removed from a solve.
    fn hold(&self, mut x: SVector<S, N>, bias: Option<&DVector<S>>) -> SVector<S, N> {
        let mut rhs = DVector::from_iterator(self.rows.len(), self.rows.iter().map(|r| r.dot(&x)));
        if let Some(bias) = bias {
            rhs += bias;
        }
        let mu = self.schur.solve(&rhs);
        for (response, m) in self.responses.iter().zip(mu.iter()) {
            x -= response * *m;
        }
        x
    }

    /// `P d`: the accelerations a force `d` gives with the constraints
    /// held (`B P d = 0`).
    pub(crate) fn respond(
        &self,
        factor: &MassFactor<S, N>,
        d: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        Some(self.hold(factor.solve(d).ok()?, None))
    }

    /// The accelerations under the forcing `f` with the constraints held,
    /// `B q̈ = −γ_B`.
    pub(crate) fn accelerate(
        &self,
        factor: &MassFactor<S, N>,
        f: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        let mut f = *f;
        if self.k != S::zero() {
            for (r, b) in self.rows.iter().zip(self.bias.iter()) {
                f -= r * (self.k * *b);
            }
        }
        Some(self.hold(factor.solve(&f).ok()?, Some(&self.bias)))
    }
}
