//! The contract of a model with control inputs: [`Actuated`] (inputs held
//! in the model and set by hand), [`Inputs`] (what the runtime reads of
//! them, also under a controller) and the [`Visitor`] through which a run
//! reaches them (see [`inputs`](crate::inputs) for how they are used).

use nalgebra::{RealField, SMatrix, SVector};

use super::Lagrangian;

/// What the runtime reads of a model's `K` control inputs: their names,
/// the values the model evaluates with at a state, and the values it
/// holds, if it holds them. Every [`Actuated`] model is one; so is a model
/// under a [`Controller`](crate::inputs::Controller), whose inputs are the controller's.
pub trait Inputs<const N: usize, const K: usize>: Lagrangian<N> {
    /// Names of the inputs, in the order of `u`.
    const NAMES: [&'static str; K];

    /// The inputs the model evaluates its forcing with at `(t, q, q̇)`.
    fn inputs_at(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, K>;

    /// The inputs the model holds, which a run needs set before its first
    /// step; `None` where none are held (a controller sets them at every
    /// evaluation).
    fn held_inputs(&self) -> Option<SVector<Self::Scalar, K>>;
}

impl<A: Actuated<N, K>, const N: usize, const K: usize> Inputs<N, K> for A {
    const NAMES: [&'static str; K] = A::INPUTS;

    #[inline]
    fn inputs_at(
        &self,
        _: A::Scalar,
        _: &SVector<A::Scalar, N>,
        _: &SVector<A::Scalar, N>,
    ) -> SVector<A::Scalar, K> {
        self.inputs()
    }

    #[inline]
    fn held_inputs(&self) -> Option<SVector<A::Scalar, K>> {
        Some(self.inputs())
    }
}

/// What the runtime does with a model's inputs, written once for every
/// number of inputs: [`Lagrangian::visit_inputs`] calls
/// [`visit`](Visitor::visit) with the model and its `K`.
pub trait Visitor<S: RealField + Copy, const N: usize> {
    /// What the visit returns.
    type Output;

    /// Runs on a model with `K` inputs.
    fn visit<A, const K: usize>(self, model: &A) -> Self::Output
    where
        A: Inputs<N, K, Scalar = S> + ?Sized;
}

/// A model with `K` control inputs `u`, held in the model and set by
/// [`set_inputs`](Actuated::set_inputs).
///
/// `lagrangian!` implements it for every model with an `inputs:` section.
/// A hand-written implementation must keep the inputs out of
/// [`mass_matrix`](Lagrangian::mass_matrix),
/// [`momentum`](Lagrangian::momentum) and the constraints, which a
/// [`Controlled`](crate::inputs::Controlled) model evaluates without its controller (they take no
/// `q̇`, or are checked free of inputs by the macro).
pub trait Actuated<const N: usize, const K: usize>: Lagrangian<N> {
    /// Names of the inputs, in the order of `u` (an indexed input `tau[3]`
    /// is `tau[0]`, `tau[1]`, `tau[2]`).
    const INPUTS: [&'static str; K];

    /// The inputs the model holds now.
    fn inputs(&self) -> SVector<Self::Scalar, K>;

    /// Sets the inputs for the following evaluations.
    fn set_inputs(&mut self, u: &SVector<Self::Scalar, K>);

    /// This model with constant inputs `u`: what a run with inputs that
    /// never change integrates (a controller is
    /// [`with_controller`](crate::model::WithLayers::with_controller)).
    #[must_use]
    fn with_inputs(mut self, u: &SVector<Self::Scalar, K>) -> Self
    where
        Self: Sized,
    {
        self.set_inputs(u);
        self
    }

    /// `∂f/∂u` at `(t, q, q̇)` and the inputs the model holds, `N × K`:
    /// how the forcing responds to each input (`M q̈ = f`, so the
    /// accelerations respond as `M⁻¹ ∂f/∂u`).
    fn input_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, K>;
}

/// A layer that leaves the inputs alone: a model under it is
/// [`Actuated`] as the model is, so that a controller can go on top of it
/// (`model.with_drift(..).with_controller(..)`). Not a
/// [`Controller`](crate::inputs::Controller): a controlled model's inputs
/// are the controller's, never set by hand. Each such layer says so beside
/// itself.
pub trait KeepsInputs {}

/// The names of `model`'s inputs, if it holds inputs that were never set
/// (not finite): refused before a run's first step. `None` for a model
/// without inputs, with every input set, or under a controller.
pub(crate) fn never_set<L: Lagrangian<N>, const N: usize>(
    model: &L,
) -> Option<&'static [&'static str]> {
    struct Unset;
    impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Unset {
        type Output = Option<&'static [&'static str]>;
        fn visit<A, const K: usize>(self, model: &A) -> Self::Output
        where
            A: Inputs<N, K, Scalar = S> + ?Sized,
        {
            let u = model.held_inputs()?;
            let names: &'static [&'static str] = const { &A::NAMES };
            (!crate::linalg::all_finite(u.as_slice())).then_some(names)
        }
    }
    model.visit_inputs(Unset).flatten()
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
