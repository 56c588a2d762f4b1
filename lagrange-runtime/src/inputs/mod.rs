//! Control inputs: models whose forces depend on values `u` that change
//! during a run, set by a controller.
//!
//! A model written with an `inputs:` section implements [`Actuated`]
//! besides [`Lagrangian`]: its `K` inputs are fields of the model that a
//! controller sets before each evaluation, and `∂f/∂u` is generated
//! symbolically beside `M` and `f`.
//!
//! Inputs start unset (NaN), and the integrators refuse a model whose
//! inputs were never set ([`InvalidInput::InputsNotSet`](crate::InvalidInput::InputsNotSet)):
//! no run silently integrates NaN or a zero nobody chose. Two ways to set
//! them:
//!
//! - **constant inputs**: `model.with_inputs(&u)` (generated), integrated
//!   like any model;
//! - **a controller**: [`model.with_controller(|t, q, qdot| u)`](Actuated::with_controller),
//!   a [`Controlled`] model that calls the controller once per evaluation of
//!   the right-hand side and integrates like any model. A prescribed input
//!   `u(t)` is a controller that ignores `q` and `q̇`; a feedback law reads
//!   them. A controller that returns a NaN or an infinity stops the run
//!   with [`NonFiniteValue::Inputs`](crate::NonFiniteValue::Inputs) at that
//!   `t` and state.
//!
//! Inputs never appear in the mass matrix, the momenta or the constraints
//! (`lagrangian!` refuses them there: their time derivatives would be
//! needed), so `M(t, q)`, `p` and `φ` are evaluated without the controller.
//!
//! The compiled example is on `lagrange::models::CartPole`.

mod controlled;

pub use controlled::Controlled;

use nalgebra::{SMatrix, SVector};

use crate::Lagrangian;

/// A model with `K` control inputs `u`, held in the model and set by
/// [`set_inputs`](Actuated::set_inputs).
///
/// `lagrangian!` implements it for every model with an `inputs:` section.
/// A hand-written implementation must keep the inputs out of
/// [`mass_matrix`](Lagrangian::mass_matrix),
/// [`momentum`](Lagrangian::momentum) and the constraints, which a
/// [`Controlled`] model evaluates without its controller (they take no
/// `q̇`, or are checked free of inputs by the macro).
pub trait Actuated<const N: usize, const K: usize>: Lagrangian<N> {
    /// Names of the inputs, in the order of `u` (an indexed input `tau[3]`
    /// is `tau[0]`, `tau[1]`, `tau[2]`).
    const INPUTS: [&'static str; K];

    /// The inputs the model holds now.
    fn inputs(&self) -> SVector<Self::Scalar, K>;

    /// Sets the inputs for the following evaluations.
    fn set_inputs(&mut self, u: &SVector<Self::Scalar, K>);

    /// `∂f/∂u` at `(t, q, q̇)` and the inputs the model holds, `N × K`:
    /// how the forcing responds to each input (`M q̈ = f`, so the
    /// accelerations respond as `M⁻¹ ∂f/∂u`).
    fn input_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, K>;

    /// This model driven by `controller`, which maps `(t, q, q̇)` to the
    /// inputs `u` at each evaluation of the right-hand side: integrate the
    /// [`Controlled`] model it returns like the model itself. The model is
    /// copied per evaluation with the controller's inputs set, so it must
    /// be `Copy` (generated models are).
    ///
    /// A prescribed input `u(t)` is a controller that ignores the state:
    /// `model.with_controller(|t, _, _| Vector1::new(t.sin()))`.
    fn with_controller<F>(&self, controller: F) -> Controlled<'_, Self, F, K>
    where
        Self: Copy + Sized,
        F: Fn(
            Self::Scalar,
            &SVector<Self::Scalar, N>,
            &SVector<Self::Scalar, N>,
        ) -> SVector<Self::Scalar, K>,
    {
        Controlled::new(self, controller)
    }
}

/// The input that explains a non-finite evaluation at `(t, q, q̇)`:
/// [`NonFiniteValue::Inputs`](crate::NonFiniteValue::Inputs) when the
/// model's controller returned a non-finite `u` there, else `value`.
pub(crate) fn blame<L: Lagrangian<N>, const N: usize>(
    model: &L,
    value: crate::NonFiniteValue,
    t: L::Scalar,
    q: &SVector<L::Scalar, N>,
    qdot: &SVector<L::Scalar, N>,
) -> crate::NonFiniteValue {
    use crate::NonFiniteValue as V;
    match value {
        V::Forcing | V::LagrangianGradient | V::NonconservativeForces | V::Jacobian
            if !model.inputs_are_finite_at(t, q, qdot) =>
        {
            V::Inputs
        }
        _ => value,
    }
}

/// An input not set: NaN, what a generated model's inputs hold until
/// `with_inputs` or a controller sets them (used by the serde derive of
/// `#[lagrange(serde)]` models, which do not store inputs).
#[doc(hidden)]
pub fn unset<S: nalgebra::RealField + Copy>() -> S {
    nalgebra::convert(f64::NAN)
}

/// An indexed input not set: `K` NaNs.
#[doc(hidden)]
pub fn unset_array<S: nalgebra::RealField + Copy, const K: usize>() -> [S; K] {
    [unset(); K]
}
