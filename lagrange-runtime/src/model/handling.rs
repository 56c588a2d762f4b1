//! The layer that changes a constrained model's drift control or its rule
//! for an inconsistent start: [`ConstraintHandling`], [`Constrained`].

use super::Lagrangian;
use super::inputs::KeepsInputs;
use super::layer::{Layer, Layered};
use super::settings::{ConstraintSettings, Drift, InitialConditions};

/// The layer that sets a constrained model's [`ConstraintSettings`]: the
/// drift control, the rule for an inconsistent start, or both; what it
/// leaves unset is the model's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstraintHandling<S> {
    drift: Option<Drift<S>>,
    initial: Option<InitialConditions>,
}

impl<S> Default for ConstraintHandling<S> {
    /// Nothing set: the model's own settings.
    fn default() -> Self {
        Self {
            drift: None,
            initial: None,
        }
    }
}

/// A constrained model with its own drift control or rule for inconsistent
/// initial conditions: [`WithLayers::with_drift`](super::WithLayers::with_drift),
/// [`WithLayers::with_initial_conditions`](super::WithLayers::with_initial_conditions).
/// Integrate it like the model itself:
///
/// ```text
/// let measured = Rk4::new(1e-3).integrate(&pendulum.with_drift(Drift::None), t0, q0, v0, &times)?;
/// let strict = pendulum.with_drift(Drift::Projection).initial_conditions(InitialConditions::Reject);
/// ```
///
/// (A model needs `lagrangian!` or a page of hand-written code; the
/// compiled example is on `lagrange::models::CartesianPendulum`.)
pub type Constrained<M, S> = Layered<M, ConstraintHandling<S>>;

impl<M, S: Copy> Layered<M, ConstraintHandling<S>> {
    /// The drift control for this model's runs.
    pub fn drift(mut self, drift: Drift<S>) -> Self {
        self.layer_mut().drift = Some(drift);
        self
    }

    /// The rule for an inconsistent initial state.
    pub fn initial_conditions(mut self, initial: InitialConditions) -> Self {
        self.layer_mut().initial = Some(initial);
        self
    }
}

impl<M: Lagrangian<N>, const N: usize> Layer<M, N> for ConstraintHandling<M::Scalar> {
    #[inline]
    fn constraint_settings(
        &self,
        settings: ConstraintSettings<M::Scalar>,
    ) -> ConstraintSettings<M::Scalar> {
        ConstraintSettings {
            drift: self.drift.unwrap_or(settings.drift),
            initial: self.initial.unwrap_or(settings.initial),
        }
    }
}

/// A drift control or a rule for the start changes no input: a controller
/// can go on top (`model.with_drift(..).with_controller(..)`).
impl<S> KeepsInputs for ConstraintHandling<S> {}
