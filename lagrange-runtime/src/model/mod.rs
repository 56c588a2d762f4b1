//! The model contract: what a model is ([`Lagrangian`]: `M`, `f`, the
//! energies, the names) and what else it can do, each capability reached
//! one way, and the one wrapper through which a model is given another
//! setting without losing any of it ([`Layered`]).
//!
//! # What a model can do
//!
//! The core is required: `M(t, q)`, `f(t, q, q̇)`, `T`, `V` and the names of
//! the coordinates. Everything else is a capability, `None` where a model
//! lacks it, and this is the one list of them (as `lagrange-engine`'s
//! `emit/api.rs` is the one list of what is generated):
//!
//! | capability | reached through | who uses it |
//! |---|---|---|
//! | exact derivatives | [`Lagrangian::residual_jacobians`] | the implicit methods' Newton iterations, [`analysis`](crate::analysis) |
//! | its own solve of `M q̈ = f` | [`Lagrangian::accelerations`] | every method's right-hand side ([`dynamics::acceleration`](crate::dynamics::acceleration)), for a model whose `M` has a structure it exploits |
//! | the action | [`Lagrangian::momentum`], [`Lagrangian::lagrangian_gradient`], [`Lagrangian::nonconservative_forces`] | [`Variational`](crate::integrators::Variational) |
//! | holonomic constraints | [`Lagrangian::visit_constraints`] → [`Holonomic<N, C>`](crate::model::constraints::Holonomic) and the run's [`ConstraintSettings`](crate::constraints::ConstraintSettings) | every method (the saddle-point solve, drift control) |
//! | control inputs | [`Lagrangian::visit_inputs`] → [`Inputs<N, K>`](crate::inputs::Inputs) | the checks before a run (inputs never set) and the blame for a non-finite value |
//! | named `let`s | [`Lagrangian::visit_lets`] → [`Lets<N, K>`](lets::Lets) | drawing, export, fits of measured outputs |
//! | parameter derivatives | the model's type: [`ParameterDerivatives<N, P>`] | [`sensitivity`](crate::sensitivity), fits to measurements |
//!
//! The sized capabilities (a model's number of constraints `C`, of inputs
//! `K`, of `let`s) are reached by a visitor, which is handed the model with
//! its size known, statically dispatched: generic code over `Lagrangian<N>`
//! reaches them without naming the size, and a model without one pays
//! nothing.
//!
//! # Layers
//!
//! A model with another drift control ([`WithLayers::with_drift`]),
//! driven by a controller ([`WithLayers::with_controller`])
//! or seen without its exact Jacobians ([`WithLayers::without_jacobians`])
//! is a [`Layered`] model: the model and a [`Layer`] that changes one
//! capability. Every other capability is passed on by `Layered`'s one
//! implementation of this trait, so a layer cannot lose what it does not
//! touch; layers nest in any order.

use nalgebra::{RealField, SMatrix, SVector};

pub(crate) mod constraints;
pub(crate) mod controller;
pub(crate) mod handling;
pub(crate) mod inputs;
pub(crate) mod layer;
pub mod lets;
pub(crate) mod parameters;
mod passed_on;
mod reference;
pub(crate) mod settings;
mod with;

pub use layer::{At, FiniteDifferences, Layer, Layered, WithoutJacobians};
pub use parameters::{Domain, ParameterDerivatives, ParameterError};
pub use with::WithLayers;

/// A mechanical system written as `M(t, q) q̈ = f(t, q, q̇)`: the contract
/// between a model and everything that runs it.
///
/// `lagrangian!` implements this trait for every model it derives; the
/// integrators consume nothing else. `N` is the number of coordinates.
///
/// Only [`mass_matrix`](Lagrangian::mass_matrix), [`forcing`](Lagrangian::forcing)
/// and the two energies are required: a model written by hand is those four
/// functions and its coordinates' names. Generated code also overrides
/// [`mass_matrix_and_forcing`](Lagrangian::mass_matrix_and_forcing) so that the
/// subexpressions `M` and `f` share are computed once per right-hand side,
/// and provides the capabilities it has ([the list](self#what-a-model-can-do)).
///
/// ```
/// use lagrange_runtime::Lagrangian;
/// use nalgebra::{SMatrix, SVector};
///
/// /// A unit mass on a spring of stiffness `k`, written by hand.
/// struct Oscillator { k: f64 }
///
/// impl Lagrangian<1> for Oscillator {
///     type Scalar = f64;
///     const COORDINATES: [&'static str; 1] = ["x"];
///     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
///         SMatrix::<f64, 1, 1>::new(1.0)
///     }
///     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
///         SVector::<f64, 1>::new(-self.k * q[0])
///     }
///     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
///         0.5 * qd[0] * qd[0]
///     }
///     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
///         0.5 * self.k * q[0] * q[0]
///     }
/// }
///
/// let osc = Oscillator { k: 4.0 };
/// let q = SVector::<f64, 1>::new(1.0);
/// let qd = SVector::<f64, 1>::new(0.0);
/// assert_eq!(osc.energy(0.0, &q, &qd), 2.0);
/// ```
pub trait Lagrangian<const N: usize> {
    /// The scalar type: `f64` by default in generated models, `f32` works too.
    type Scalar: RealField + Copy;

    /// Names of the generalized coordinates, in the order of `q`.
    const COORDINATES: [&'static str; N];

    /// The mass matrix `M(t, q) = ∂²T/∂q̇²` (symmetric).
    fn mass_matrix(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, N>;

    /// The forcing `f(t, q, q̇)` such that `M q̈ = f`.
    fn forcing(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, N>;

    /// `M` and `f` together; generated models compute their shared
    /// subexpressions once. Integrators call this, once per right-hand side.
    fn mass_matrix_and_forcing(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> (SMatrix<Self::Scalar, N, N>, SVector<Self::Scalar, N>) {
        (self.mass_matrix(t, q), self.forcing(t, q, qdot))
    }

    /// Kinetic energy `T(t, q, q̇)`.
    fn kinetic_energy(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> Self::Scalar;

    /// Potential energy `V(t, q)`.
    fn potential_energy(&self, t: Self::Scalar, q: &SVector<Self::Scalar, N>) -> Self::Scalar;

    /// Total energy `T + V`. Conserved when the model has no forces, no
    /// dissipation and no explicit time dependence.
    fn energy(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> Self::Scalar {
        self.kinetic_energy(t, q, qdot) + self.potential_energy(t, q)
    }

    /// The exact Jacobians `(∂r/∂q, ∂r/∂q̇)` of the residual
    /// `r(t, q, q̇, q̈) = M(t, q) q̈ − f(t, q, q̇)`, for the Newton iterations
    /// of implicit methods. `None` (the default) makes them fall back to
    /// finite differences of the acceleration. Models written with
    /// `#[lagrange(jacobians)]` generate them symbolically.
    #[allow(clippy::type_complexity)]
    fn residual_jacobians(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
        qddot: &SVector<Self::Scalar, N>,
    ) -> Option<(SMatrix<Self::Scalar, N, N>, SMatrix<Self::Scalar, N, N>)> {
        let _ = (t, q, qdot, qddot);
        None
    }

    /// `q̈` at `(t, q, q̇)` solved by the model itself, for a model that
    /// knows the structure of its `M` and need not have it formed and
    /// factored whole: a [`Sensitivity`](crate::sensitivity::Sensitivity)
    /// model, whose `M` is the model's repeated down the diagonal, solves
    /// with the model's `M` once. `None` (the default, and every model from
    /// `lagrangian!`) solves `M q̈ = f` from
    /// [`mass_matrix_and_forcing`](Self::mass_matrix_and_forcing). A model
    /// with constraints is not asked: its `q̈` is the saddle-point solve.
    /// A model that overrides it sets [`SOLVES_ACCELERATIONS`](Self::SOLVES_ACCELERATIONS);
    /// a run refuses one whose method answers without the flag
    /// ([`InvalidInput::AccelerationsNotFlagged`](crate::error::InvalidInput::AccelerationsNotFlagged)),
    /// rather than ignore the method.
    #[allow(clippy::type_complexity)]
    fn accelerations(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> Option<Result<SVector<Self::Scalar, N>, crate::error::IntegrationError<Self::Scalar, N>>>
    {
        let _ = (t, q, qdot);
        None
    }

    /// Whether [`accelerations`](Self::accelerations) answers: only then is
    /// it asked (a layer over a model that does not would otherwise set a
    /// controller's inputs once more per evaluation, for nothing).
    const SOLVES_ACCELERATIONS: bool = false;

    /// The generalized momenta `p = ∂L/∂q̇`, if the model provides them
    /// (generated models do). Variational integrators need them.
    fn momentum(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> Option<SVector<Self::Scalar, N>> {
        let _ = (t, q, qdot);
        None
    }

    /// `∂L/∂q`, if the model provides it (generated models do). Variational
    /// integrators need it.
    fn lagrangian_gradient(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> Option<SVector<Self::Scalar, N>> {
        let _ = (t, q, qdot);
        None
    }

    /// The non-conservative generalized forces `Q − ∂R/∂q̇`, if the model
    /// provides them: every model from `lagrangian!` does (zero, without
    /// any code to evaluate, for one with neither `forces:` nor
    /// `dissipation:`); a hand-written conservative model returns
    /// `Some(SVector::zeros())`. Variational integrators need them, and
    /// refuse a model that leaves the default `None` rather than assume it
    /// conservative.
    fn nonconservative_forces(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> Option<SVector<Self::Scalar, N>> {
        let _ = (t, q, qdot);
        None
    }

    /// Whether the model has unilateral contacts (`contacts:`, see
    /// [`contact`](crate::contact)), which only
    /// [`contact::integrate`](crate::contact::integrate) runs: the other
    /// runs refuse such a model
    /// ([`InvalidInput::ContactsNotRun`](crate::error::InvalidInput::ContactsNotRun))
    /// rather than let it pass through its floor. The analyses (which look
    /// at the smooth dynamics only) take it.
    const HAS_CONTACTS: bool = false;

    /// Hands `visitor` this model as a [`Holonomic`](crate::model::constraints::Holonomic)
    /// model with its number of constraints `C`, and the constraint
    /// settings of the run, if it has constraints: how the integrators
    /// reach them (see [`constraints`](crate::constraints)). `None`, the
    /// default, is a model in minimal coordinates. A model with a
    /// `constraints:` section overrides it with one line,
    /// `Some(visitor.visit::<Self, C>(self, Default::default()))`.
    fn visit_constraints<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: constraints::Visitor<Self::Scalar, N>,
    {
        let _ = visitor;
        None
    }

    /// Hands `visitor` this model's control inputs with their number `K`,
    /// if it has any (see [`inputs`](crate::inputs)): how the runtime
    /// refuses inputs never set and blames a controller's NaN. `None`, the
    /// default, is a model without inputs; a model with an `inputs:`
    /// section overrides it with `Some(visitor.visit::<Self, K>(self))`.
    fn visit_inputs<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: inputs::Visitor<Self::Scalar, N>,
    {
        let _ = visitor;
        None
    }

    /// Hands `visitor` this model's named `let`s with their number `K`, if
    /// it names any (see [`lets`]). `None`, the default, names
    /// none; a model from `lagrangian!` with `let`s overrides it with
    /// `Some(visitor.visit::<Self, K>(self))`.
    fn visit_lets<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: lets::Visitor<Self::Scalar, N>,
    {
        let _ = visitor;
        None
    }

    /// Whether every runtime parameter of the model is finite. Integrators
    /// reject a model with a NaN or infinite parameter before the first step.
    fn parameters_are_finite(&self) -> bool {
        true
    }
}

/// Whether `model` can be evaluated at all: every parameter finite, and
/// every input it holds set. What a run checks before its first step, and
/// an analysis before its first evaluation.
pub(crate) fn ready<L: Lagrangian<N>, const N: usize>(
    model: &L,
) -> Result<(), crate::error::InvalidInput<L::Scalar>> {
    if !model.parameters_are_finite() {
        return Err(crate::error::InvalidInput::NonFiniteParameters);
    }
    if let Some(inputs) = inputs::never_set(model) {
        return Err(crate::error::InvalidInput::InputsNotSet { inputs });
    }
    Ok(())
}
