//! The constructors that give a model a layer, apart from the contract:
//! [`WithLayers`], for every model (the prelude exports it). The contract's
//! traits name no layer; a layer's constructor is here.

use nalgebra::SVector;

use super::Lagrangian;
use super::constraints::Holonomic;
use super::controller::{Controlled, Controller};
use super::handling::{Constrained, ConstraintHandling};
use super::inputs::Actuated;
use super::layer::{FiniteDifferences, Layered, WithoutJacobians};
use super::settings::{Drift, InitialConditions};

/// A model given a [`Layer`](super::Layer): the same model with one
/// capability changed, integrated like the model itself. Every model has
/// these methods; each asks for the capability it changes. The model is
/// taken by value (a model from `lagrangian!` is `Copy`; borrow one that
/// is not: `(&model).with_drift(..)`), and layers nest in any order
/// (`model.with_controller(..).with_drift(..)`).
pub trait WithLayers<const N: usize>: Lagrangian<N> + Sized {
    /// This model without its exact
    /// [`residual_jacobians`](Lagrangian::residual_jacobians): the implicit
    /// methods and the linearizations take theirs by finite differences
    /// instead, the path of a model written without
    /// `#[lagrange(jacobians)]`. Everything else is the model's own.
    fn without_jacobians(self) -> WithoutJacobians<Self> {
        Layered::new(self, FiniteDifferences)
    }

    /// This constrained model with another drift control, for its runs:
    /// `method.integrate(&model.with_drift(Drift::None), ..)`.
    fn with_drift<const C: usize>(
        self,
        drift: Drift<Self::Scalar>,
    ) -> Constrained<Self, Self::Scalar>
    where
        Self: Holonomic<N, C>,
    {
        Layered::new(self, ConstraintHandling::default()).drift(drift)
    }

    /// This constrained model with another rule for inconsistent initial
    /// conditions.
    fn with_initial_conditions<const C: usize>(
        self,
        initial: InitialConditions,
    ) -> Constrained<Self, Self::Scalar>
    where
        Self: Holonomic<N, C>,
    {
        Layered::new(self, ConstraintHandling::default()).initial_conditions(initial)
    }

    /// This model with inputs driven by `controller`, which maps
    /// `(t, q, q̇)` to the inputs `u` at each evaluation of the right-hand
    /// side: integrate the [`Controlled`] model it returns like the model
    /// itself. The model is copied per evaluation with the controller's
    /// inputs set, so it must be `Copy` (generated models are).
    ///
    /// A prescribed input `u(t)` is a controller that ignores the state:
    /// `model.with_controller(|t, _, _| Vector1::new(t.sin()))`.
    fn with_controller<F, const K: usize>(self, controller: F) -> Controlled<Self, F, K>
    where
        Self: Actuated<N, K> + Copy,
        F: Fn(
            Self::Scalar,
            &SVector<Self::Scalar, N>,
            &SVector<Self::Scalar, N>,
        ) -> SVector<Self::Scalar, K>,
    {
        Layered::new(self, Controller::new(controller))
    }
}

impl<L: Lagrangian<N>, const N: usize> WithLayers<N> for L {}
