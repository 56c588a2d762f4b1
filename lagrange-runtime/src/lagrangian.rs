//! The contract between a derived model and the integrators.

use nalgebra::{RealField, SMatrix, SVector};

/// A mechanical system in minimal generalized coordinates, written as
/// `M(t, q) q̈ = f(t, q, q̇)`.
///
/// `lagrangian!` implements this trait for every model it derives; the
/// integrators consume nothing else. `N` is the number of degrees of freedom.
///
/// Only [`mass_matrix`](Lagrangian::mass_matrix), [`forcing`](Lagrangian::forcing)
/// and the two energies are required. Generated code also overrides
/// [`mass_matrix_and_forcing`](Lagrangian::mass_matrix_and_forcing) so that the
/// subexpressions `M` and `f` share are computed once per right-hand side.
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

    /// Whether the model has no non-conservative forces at all (no
    /// `forces:` and no `dissipation:`): then
    /// [`nonconservative_forces`](Self::nonconservative_forces) is zero
    /// without any code for it. Generated models set it; hand-written ones
    /// that leave it `false` and provide no `nonconservative_forces` are
    /// refused by the variational integrator rather than assumed conservative.
    const CONSERVATIVE: bool = false;

    /// The non-conservative generalized forces `Q − ∂R/∂q̇`, if the model
    /// provides them (generated models with `forces:` or `dissipation:` do;
    /// a [`CONSERVATIVE`](Self::CONSERVATIVE) model gets zero from this
    /// default). Variational integrators need them.
    fn nonconservative_forces(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> Option<SVector<Self::Scalar, N>> {
        let _ = (t, q, qdot);
        Self::CONSERVATIVE.then(SVector::zeros)
    }

    /// Hands `visitor` this model as a [`Holonomic`](crate::Holonomic)
    /// model with its number of constraints `C`, if it has constraints:
    /// how the integrators reach them (see [`constraints`](crate::constraints)).
    /// `None`, the default, is a model in minimal coordinates. A model with
    /// a `constraints:` section overrides it with one line,
    /// `Some(visitor.visit::<Self, C>(self))`.
    fn visit_constraints<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: crate::constraints::Visitor<Self::Scalar, N>,
    {
        let _ = visitor;
        None
    }

    /// Whether every runtime parameter of the model is finite. Integrators
    /// reject a model with a NaN or infinite parameter before the first step.
    fn parameters_are_finite(&self) -> bool {
        true
    }

    /// Whether every control input of the model holds a value (see
    /// [`Actuated`](crate::Actuated)). A model from `lagrangian!` with
    /// `inputs:` starts with its inputs NaN, meaning "not set", and
    /// integrators refuse it before the first step
    /// ([`InvalidInput::InputsNotSet`](crate::InvalidInput::InputsNotSet))
    /// rather than run on NaN or on a default nobody chose. A model without
    /// inputs, and a model under a controller, are always set.
    fn inputs_are_set(&self) -> bool {
        true
    }

    /// The names of the model's control inputs, for the error that says
    /// which were never set (empty for a model without inputs).
    fn input_names(&self) -> &'static [&'static str] {
        &[]
    }

    /// Whether the control inputs that drive the model at `(t, q, q̇)` are
    /// finite. Only a model under a controller
    /// ([`Controlled`](crate::inputs::Controlled)) can answer `false`; the
    /// integrators ask when an evaluation came back non-finite, to report
    /// [`NonFiniteValue::Inputs`](crate::NonFiniteValue::Inputs) instead of
    /// blaming the forcing.
    fn inputs_are_finite_at(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> bool {
        let _ = (t, q, qdot);
        true
    }
}
