//! The contract of a model with holonomic constraints: [`Holonomic`], and
//! the [`Visitor`] through which a run reaches it (see
//! [`constraints`](crate::constraints) for what the runtime does with it).

use nalgebra::{RealField, SMatrix, SVector};

use super::Lagrangian;
use super::settings::ConstraintSettings;

/// A model with `C` holonomic constraints `φ(t, q) = 0` on its `N`
/// coordinates (`C < N`).
///
/// `lagrangian!` implements it for every model with a `constraints:`
/// section; the four required methods are generated from the constraints
/// symbolically.
pub trait Holonomic<const N: usize, const C: usize>: Lagrangian<N> {
    /// Names of the constraints, in the order of `φ`.
    const CONSTRAINTS: [&'static str; C];

    /// The constraint values `φ(t, q)`: zero on the constraint manifold.
    fn constraints(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, C>;

    /// The constraint Jacobian `G(t, q) = ∂φ/∂q`, `C × N`.
    fn constraint_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, C, N>;

    /// The constraint velocities `φ̇ = G q̇ + ∂φ/∂t`: zero for a state on
    /// the manifold moving along it.
    fn constraint_velocities(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, C>;

    /// The bias `γ(t, q, q̇)` with `φ̈ = G q̈ + γ`: the part of the constraint
    /// accelerations that does not depend on `q̈`.
    fn constraint_bias(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, C>;

    /// `M`, `f`, `G` and `γ` together: generated models compute their
    /// shared subexpressions once. The constrained right-hand side calls
    /// this, once per evaluation.
    #[allow(clippy::type_complexity)]
    fn constrained_system(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> (
        SMatrix<Self::Scalar, N, N>,
        SVector<Self::Scalar, N>,
        SMatrix<Self::Scalar, C, N>,
        SVector<Self::Scalar, C>,
    ) {
        let (m, f) = self.mass_matrix_and_forcing(t, q, qdot);
        (
            m,
            f,
            self.constraint_jacobian(t, q),
            self.constraint_bias(t, q, qdot),
        )
    }

    /// Whether `M` is singular by itself and regular only on the velocities
    /// the constraints allow, the null space of `G`: a rigid body's four
    /// quaternion rates under `|q| = 1`, whose kinetic energy sees three.
    /// The saddle-point system is regular all the same, and the runtime
    /// solves it with `M + k GᵀG` in place of `M` and `f − k Gᵀγ` in place
    /// of `f`, which has the same `q̈` and `λ` wherever `G q̈ = −γ`
    /// (`k` scales `GᵀG` to `M`). The variational integrator steps the
    /// Lagrangian `L + (k/2)|φ̇|²` instead, equal to `L` on the constrained
    /// motion, whose mass matrix is `M + k GᵀG`.
    ///
    /// `lagrangian!` answers it from its compile-time rank check; a
    /// hand-written model whose `M` is regular keeps the default, `false`.
    #[inline]
    fn mass_regular_on_constraints_only(&self) -> bool {
        false
    }

    /// Which of the constraints are on the velocities,
    /// `A(t, q) q̇ + b(t, q) = 0` (rolling, a knife edge), not on the
    /// positions, in the order of `φ`. Such a row has no position-level
    /// value ([`constraints`](Holonomic::constraints) returns zero there,
    /// which no projection moves); its row of
    /// [`constraint_jacobian`](Holonomic::constraint_jacobian) is `A`, its
    /// [`constraint_velocities`](Holonomic::constraint_velocities) entry the
    /// residual `A q̇ + b`, and its bias `γ = Ȧ q̇ + ḃ`: the saddle-point
    /// system, the velocity projection and Baumgarte's velocity term treat
    /// it as they treat a holonomic row (Lagrange–d'Alembert dynamics).
    ///
    /// `lagrangian!` answers it from the constraints as written; a
    /// hand-written model of holonomic constraints keeps the default, all
    /// `false`.
    #[inline]
    fn velocity_constraint_rows(&self) -> [bool; C] {
        [false; C]
    }

    /// Whether any constraint is on the velocities
    /// ([`velocity_constraint_rows`](Holonomic::velocity_constraint_rows)).
    /// The methods and analyses that need a position-level constraint for
    /// every row (the variational integrator's RATTLE steps, the
    /// linearization on the constraint manifold) refuse such a model with a
    /// typed error; [`linearize_steady_motion`](crate::analysis::linearize_steady_motion)
    /// takes it.
    #[inline]
    fn has_velocity_constraints(&self) -> bool {
        self.velocity_constraint_rows().contains(&true)
    }
}

/// Whether `model` has constraints: a visit that does nothing.
pub(crate) fn is_constrained<L: Lagrangian<N>, const N: usize>(model: &L) -> bool {
    struct Probe;
    impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Probe {
        type Output = ();
        fn visit<H, const C: usize>(self, _: &H, _: ConstraintSettings<S>)
        where
            H: Holonomic<N, C, Scalar = S> + ?Sized,
        {
        }
    }
    model.visit_constraints(Probe).is_some()
}

/// What a constrained model says of itself that the methods needing more
/// than the saddle-point system ask before a run: whether its `M` is
/// regular only on the constraints, and whether any constraint is on the
/// velocities. `(false, false)` for a model without constraints.
fn constraint_kinds<L: Lagrangian<N>, const N: usize>(model: &L) -> (bool, bool) {
    struct Probe;
    impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Probe {
        type Output = (bool, bool);
        fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> (bool, bool)
        where
            H: Holonomic<N, C, Scalar = S> + ?Sized,
        {
            (
                model.mass_regular_on_constraints_only(),
                model.has_velocity_constraints(),
            )
        }
    }
    model.visit_constraints(Probe).unwrap_or((false, false))
}

/// Whether `model` has constraints and a mass matrix regular only on them
/// ([`Holonomic::mass_regular_on_constraints_only`]).
pub(crate) fn mass_regular_on_constraints_only<L: Lagrangian<N>, const N: usize>(
    model: &L,
) -> bool {
    constraint_kinds(model).0
}

/// Whether `model` has constraints on its velocities
/// ([`Holonomic::has_velocity_constraints`]).
pub(crate) fn has_velocity_constraints<L: Lagrangian<N>, const N: usize>(model: &L) -> bool {
    constraint_kinds(model).1
}

/// What the integrators do with a constrained model, written once for
/// every number of constraints: [`Lagrangian::visit_constraints`] calls
/// [`visit`](Visitor::visit) with the model, its `C` and the settings of
/// the run.
pub trait Visitor<S: RealField + Copy, const N: usize> {
    /// What the visit returns.
    type Output;

    /// Runs on a model with `C` constraints, kept as `settings` say.
    fn visit<H, const C: usize>(self, model: &H, settings: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized;
}
