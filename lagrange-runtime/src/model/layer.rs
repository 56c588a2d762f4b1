//! [`Layered`]: a model with one capability changed by a [`Layer`], every
//! other capability passed on by the one implementation below.
//!
//! `Layered`'s implementation of [`Lagrangian`] writes out every method of
//! the trait (`clippy::missing_trait_methods` holds it to that), each
//! either passed to the model or to the layer's hook for it: a method added
//! to the trait is a compile error here until it is passed on, never a
//! capability silently lost by a wrapper.

use nalgebra::{RealField, SMatrix, SVector};

use super::Lagrangian;
use crate::model::constraints::{Holonomic, Visitor as ConstraintVisitor};
use crate::model::inputs::{KeepsInputs, Visitor as InputVisitor};
use crate::model::lets::Visitor as LetVisitor;
use crate::model::settings::ConstraintSettings;

/// A model `M` with a [`Layer`] `A` that changes one of its capabilities:
/// another drift control ([`WithLayers::with_drift`](crate::model::WithLayers::with_drift)), a controller
/// ([`WithLayers::with_controller`](crate::model::WithLayers::with_controller)), no
/// exact Jacobians ([`WithLayers::without_jacobians`](crate::model::WithLayers::without_jacobians)). Integrate it like
/// the model itself; layers nest in any order
/// (`model.with_controller(..).with_drift(..)`), the outer one applied
/// last.
///
/// A layered model owns its model: a model from `lagrangian!` is `Copy`,
/// and a borrowed one is a model too (`(&model).with_drift(..)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layered<M, A> {
    model: M,
    layer: A,
}

impl<M, A> Layered<M, A> {
    /// `model` with `layer`.
    pub fn new(model: M, layer: A) -> Self {
        Self { model, layer }
    }

    /// The model under the layer.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// The layer.
    pub fn layer(&self) -> &A {
        &self.layer
    }

    /// The model under the layer, to change it between runs.
    pub fn model_mut(&mut self) -> &mut M {
        &mut self.model
    }

    /// The layer, to change it between runs.
    pub fn layer_mut(&mut self) -> &mut A {
        &mut self.layer
    }

    /// The model and the layer apart.
    pub fn into_parts(self) -> (M, A) {
        (self.model, self.layer)
    }
}

/// The model that answers at a state, as a [`Layer`] decides.
pub enum At<'m, M> {
    /// The model itself: the layer leaves the dynamics alone.
    Model(&'m M),
    /// A copy of the model changed for this state (a controller's inputs
    /// set in it).
    Changed(M),
    /// No model can answer: what it would be given is not finite (a
    /// controller's NaN). The evaluations return NaN, which the runtime
    /// reports, blaming the inputs.
    NotFinite,
}

/// What a [`Layered`] model's layer changes. Every hook has a default that
/// leaves the model's capability as it is: a layer overrides the one it is
/// for.
pub trait Layer<M: Lagrangian<N>, const N: usize>: Sized {
    /// The model that evaluates everything that depends on `q̇` at
    /// `(t, q, q̇)` (the forcing, the energies, `∂L/∂q`, the forces): the
    /// model itself by default. `M(t, q)`, `p` and the constraints take no
    /// part in it (a controller's inputs are kept out of them).
    #[inline]
    fn at<'m>(
        &self,
        model: &'m M,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> At<'m, M> {
        let _ = (t, q, qdot);
        At::Model(model)
    }

    /// The exact residual Jacobians, or `None` for finite differences.
    #[inline]
    #[allow(clippy::type_complexity)]
    fn residual_jacobians(
        &self,
        model: &M,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
        qddot: &SVector<M::Scalar, N>,
    ) -> Option<(SMatrix<M::Scalar, N, N>, SMatrix<M::Scalar, N, N>)> {
        model.residual_jacobians(t, q, qdot, qddot)
    }

    /// The constraint settings of a run, from those of the model below.
    #[inline]
    fn constraint_settings(
        &self,
        settings: ConstraintSettings<M::Scalar>,
    ) -> ConstraintSettings<M::Scalar> {
        settings
    }

    /// Hands `visitor` the constraints `constraints` met in the model, with
    /// the run's `settings`, as the layered model's: as they are by
    /// default; joined to the layered dynamics by a layer that changes them
    /// (the controller's).
    #[inline]
    fn visit_constrained<V, H, const C: usize>(
        layered: &Layered<M, Self>,
        constraints: &H,
        settings: ConstraintSettings<M::Scalar>,
        visitor: V,
    ) -> V::Output
    where
        V: ConstraintVisitor<M::Scalar, N>,
        H: Holonomic<N, C, Scalar = M::Scalar> + ?Sized,
    {
        let _ = layered;
        visitor.visit::<H, C>(constraints, settings)
    }

    /// Hands `visitor` the layered model's inputs: the model's by default.
    #[inline]
    fn visit_inputs<V>(layered: &Layered<M, Self>, visitor: V) -> Option<V::Output>
    where
        V: InputVisitor<M::Scalar, N>,
    {
        layered.model.visit_inputs(visitor)
    }
}

/// The layer of [`WithLayers::without_jacobians`](crate::model::WithLayers::without_jacobians): the residual Jacobians
/// are taken by finite differences of the acceleration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FiniteDifferences;

/// Differences of the Jacobians change no input: a controller can go on
/// top.
impl KeepsInputs for FiniteDifferences {}

impl<M: Lagrangian<N>, const N: usize> Layer<M, N> for FiniteDifferences {
    #[inline]
    fn residual_jacobians(
        &self,
        _: &M,
        _: M::Scalar,
        _: &SVector<M::Scalar, N>,
        _: &SVector<M::Scalar, N>,
        _: &SVector<M::Scalar, N>,
    ) -> Option<(SMatrix<M::Scalar, N, N>, SMatrix<M::Scalar, N, N>)> {
        None
    }
}

/// A model seen without its exact residual Jacobians:
/// [`WithLayers::without_jacobians`](crate::model::WithLayers::without_jacobians).
pub type WithoutJacobians<M> = Layered<M, FiniteDifferences>;

/// NaN in every entry: what an evaluation returns where no model answers.
fn nan<S: RealField + Copy, const R: usize>() -> SVector<S, R> {
    SVector::from_element(nalgebra::convert::<f64, S>(f64::NAN))
}

macro_rules! at {
    ($self:ident, $t:ident, $q:ident, $qdot:ident, |$m:ident| $value:expr, $nan:expr) => {
        match $self.layer.at(&$self.model, $t, $q, $qdot) {
            At::Model($m) => $value,
            At::Changed(ref $m) => $value,
            At::NotFinite => $nan,
        }
    };
}

#[warn(clippy::missing_trait_methods)]
impl<M, A, const N: usize> Lagrangian<N> for Layered<M, A>
where
    M: Lagrangian<N>,
    A: Layer<M, N>,
{
    type Scalar = M::Scalar;
    const COORDINATES: [&'static str; N] = M::COORDINATES;
    const HAS_CONTACTS: bool = M::HAS_CONTACTS;
    const SOLVES_ACCELERATIONS: bool = M::SOLVES_ACCELERATIONS;

    #[inline]
    fn mass_matrix(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> SMatrix<M::Scalar, N, N> {
        self.model.mass_matrix(t, q)
    }

    #[inline]
    fn forcing(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, N> {
        at!(self, t, q, qdot, |m| m.forcing(t, q, qdot), nan())
    }

    #[inline]
    fn mass_matrix_and_forcing(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> (SMatrix<M::Scalar, N, N>, SVector<M::Scalar, N>) {
        at!(
            self,
            t,
            q,
            qdot,
            |m| m.mass_matrix_and_forcing(t, q, qdot),
            (self.model.mass_matrix(t, q), nan())
        )
    }

    #[inline]
    fn kinetic_energy(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> M::Scalar {
        at!(
            self,
            t,
            q,
            qdot,
            |m| m.kinetic_energy(t, q, qdot),
            nan::<_, 1>()[0]
        )
    }

    #[inline]
    fn potential_energy(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> M::Scalar {
        self.model.potential_energy(t, q)
    }

    #[inline]
    fn energy(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> M::Scalar {
        at!(self, t, q, qdot, |m| m.energy(t, q, qdot), nan::<_, 1>()[0])
    }

    #[inline]
    fn residual_jacobians(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
        qddot: &SVector<M::Scalar, N>,
    ) -> Option<(SMatrix<M::Scalar, N, N>, SMatrix<M::Scalar, N, N>)> {
        self.layer
            .residual_jacobians(&self.model, t, q, qdot, qddot)
    }

    #[allow(clippy::type_complexity)]
    #[inline]
    fn accelerations(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<Result<SVector<M::Scalar, N>, crate::error::IntegrationError<M::Scalar, N>>> {
        if !M::SOLVES_ACCELERATIONS {
            return None;
        }
        // Where no model answers, the forcing's NaN is reported (and blamed)
        // by the solve with `M`.
        at!(self, t, q, qdot, |m| m.accelerations(t, q, qdot), None)
    }

    #[inline]
    fn momentum(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        self.model.momentum(t, q, qdot)
    }

    #[inline]
    fn lagrangian_gradient(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        at!(
            self,
            t,
            q,
            qdot,
            |m| m.lagrangian_gradient(t, q, qdot),
            Some(nan())
        )
    }

    #[inline]
    fn nonconservative_forces(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> Option<SVector<M::Scalar, N>> {
        at!(
            self,
            t,
            q,
            qdot,
            |m| m.nonconservative_forces(t, q, qdot),
            Some(nan())
        )
    }

    #[inline]
    fn visit_constraints<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: ConstraintVisitor<M::Scalar, N>,
    {
        self.model.visit_constraints(Rejoin {
            layered: self,
            visitor,
        })
    }

    #[inline]
    fn visit_inputs<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: InputVisitor<M::Scalar, N>,
    {
        A::visit_inputs(self, visitor)
    }

    #[inline]
    fn visit_lets<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: LetVisitor<M::Scalar, N>,
    {
        self.model.visit_lets(visitor)
    }

    #[inline]
    fn parameters_are_finite(&self) -> bool {
        self.model.parameters_are_finite()
    }
}

/// A layered constrained model is constrained: its `φ`, `G`, `φ̇` and `γ`
/// are the model's, its `M` and `f` the layered ones, so that
/// `layered.multipliers(..)` is what the layered model's run sees.
impl<M, A, const N: usize, const C: usize> Holonomic<N, C> for Layered<M, A>
where
    M: Holonomic<N, C>,
    A: Layer<M, N>,
{
    const CONSTRAINTS: [&'static str; C] = M::CONSTRAINTS;

    #[inline]
    fn constraints(&self, t: M::Scalar, q: &SVector<M::Scalar, N>) -> SVector<M::Scalar, C> {
        self.model.constraints(t, q)
    }

    #[inline]
    fn constraint_jacobian(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
    ) -> SMatrix<M::Scalar, C, N> {
        self.model.constraint_jacobian(t, q)
    }

    #[inline]
    fn constraint_velocities(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, C> {
        self.model.constraint_velocities(t, q, qdot)
    }

    #[inline]
    fn constraint_bias(
        &self,
        t: M::Scalar,
        q: &SVector<M::Scalar, N>,
        qdot: &SVector<M::Scalar, N>,
    ) -> SVector<M::Scalar, C> {
        self.model.constraint_bias(t, q, qdot)
    }

    #[inline]
    fn mass_regular_on_constraints_only(&self) -> bool {
        self.model.mass_regular_on_constraints_only()
    }

    #[inline]
    fn velocity_constraint_rows(&self) -> [bool; C] {
        self.model.velocity_constraint_rows()
    }
}

/// The visitor that meets the constraints inside a layered model and hands
/// them on as the layered model's: the layer's settings applied, and, by a
/// layer that changes the dynamics, joined to them.
struct Rejoin<'a, M, A, V> {
    layered: &'a Layered<M, A>,
    visitor: V,
}

impl<M, A, V, const N: usize> ConstraintVisitor<M::Scalar, N> for Rejoin<'_, M, A, V>
where
    M: Lagrangian<N>,
    A: Layer<M, N>,
    V: ConstraintVisitor<M::Scalar, N>,
{
    type Output = V::Output;

    #[inline]
    fn visit<H, const C: usize>(
        self,
        constraints: &H,
        settings: ConstraintSettings<M::Scalar>,
    ) -> V::Output
    where
        H: Holonomic<N, C, Scalar = M::Scalar> + ?Sized,
    {
        let settings = self.layered.layer.constraint_settings(settings);
        A::visit_constrained::<V, H, C>(self.layered, constraints, settings, self.visitor)
    }
}

/// Dynamics from `L` (a layered model that changes them), constraints from
/// `H` (met inside it): what a constrained method sees of a constrained
/// model under a controller. `constrained_system` is the trait's default:
/// `M` and `f` from `L`, `G` and `γ` from `H`.
pub(crate) struct Joined<'a, L, H: ?Sized, S, const C: usize> {
    pub(crate) dynamics: &'a L,
    pub(crate) constraints: &'a H,
    pub(crate) settings: ConstraintSettings<S>,
}

#[warn(clippy::missing_trait_methods)]
impl<L, H, S, const N: usize, const C: usize> Lagrangian<N> for Joined<'_, L, H, S, C>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    H: Holonomic<N, C, Scalar = S> + ?Sized,
{
    type Scalar = L::Scalar;
    const COORDINATES: [&'static str; N] = L::COORDINATES;

    #[inline]
    fn mass_matrix(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> SMatrix<L::Scalar, N, N> {
        self.dynamics.mass_matrix(t, q)
    }
    #[inline]
    fn forcing(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, N> {
        self.dynamics.forcing(t, q, qdot)
    }
    #[inline]
    fn mass_matrix_and_forcing(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> (SMatrix<L::Scalar, N, N>, SVector<L::Scalar, N>) {
        self.dynamics.mass_matrix_and_forcing(t, q, qdot)
    }
    #[inline]
    fn kinetic_energy(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> L::Scalar {
        self.dynamics.kinetic_energy(t, q, qdot)
    }
    #[inline]
    fn potential_energy(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> L::Scalar {
        self.dynamics.potential_energy(t, q)
    }
    #[inline]
    fn energy(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> L::Scalar {
        self.dynamics.energy(t, q, qdot)
    }
    #[inline]
    fn residual_jacobians(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
        qddot: &SVector<L::Scalar, N>,
    ) -> Option<(SMatrix<L::Scalar, N, N>, SMatrix<L::Scalar, N, N>)> {
        self.dynamics.residual_jacobians(t, q, qdot, qddot)
    }
    #[allow(clippy::type_complexity)]
    #[inline]
    fn accelerations(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<Result<SVector<S, N>, crate::error::IntegrationError<S, N>>> {
        // Never asked: a constrained model's `q̈` is the saddle-point solve.
        self.dynamics.accelerations(t, q, qdot)
    }

    #[inline]
    fn momentum(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> Option<SVector<L::Scalar, N>> {
        self.dynamics.momentum(t, q, qdot)
    }
    #[inline]
    fn lagrangian_gradient(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> Option<SVector<L::Scalar, N>> {
        self.dynamics.lagrangian_gradient(t, q, qdot)
    }
    #[inline]
    fn nonconservative_forces(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> Option<SVector<L::Scalar, N>> {
        self.dynamics.nonconservative_forces(t, q, qdot)
    }
    #[inline]
    fn visit_constraints<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: ConstraintVisitor<L::Scalar, N>,
    {
        Some(visitor.visit::<Self, C>(self, self.settings))
    }
    #[inline]
    fn visit_inputs<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: InputVisitor<L::Scalar, N>,
    {
        self.dynamics.visit_inputs(visitor)
    }
    #[inline]
    fn visit_lets<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: LetVisitor<L::Scalar, N>,
    {
        self.dynamics.visit_lets(visitor)
    }
    #[inline]
    fn parameters_are_finite(&self) -> bool {
        self.dynamics.parameters_are_finite()
    }
}

impl<L, H, S, const N: usize, const C: usize> Holonomic<N, C> for Joined<'_, L, H, S, C>
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
    H: Holonomic<N, C, Scalar = S> + ?Sized,
{
    const CONSTRAINTS: [&'static str; C] = H::CONSTRAINTS;

    #[inline]
    fn constraints(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> SVector<L::Scalar, C> {
        self.constraints.constraints(t, q)
    }
    #[inline]
    fn constraint_jacobian(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
    ) -> SMatrix<L::Scalar, C, N> {
        self.constraints.constraint_jacobian(t, q)
    }
    #[inline]
    fn constraint_velocities(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, C> {
        self.constraints.constraint_velocities(t, q, qdot)
    }
    #[inline]
    fn constraint_bias(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        qdot: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, C> {
        self.constraints.constraint_bias(t, q, qdot)
    }
    #[inline]
    fn mass_regular_on_constraints_only(&self) -> bool {
        self.constraints.mass_regular_on_constraints_only()
    }
    #[inline]
    fn velocity_constraint_rows(&self) -> [bool; C] {
        self.constraints.velocity_constraint_rows()
    }
}
