//! How a run keeps the constraints: the drift control, and what to do with
//! an inconsistent start. Chosen per model by the layer
//! [`ConstraintHandling`] ([`Constrained`]).

use nalgebra::RealField;

use crate::model::Lagrangian;
use crate::model::{Layer, Layered};

/// How the drift of `φ` and `φ̇` away from zero is controlled (see
/// [the module](super#drift-and-how-to-control-it) for what each costs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Drift<S> {
    /// Project `q` onto `φ = 0` and `q̇` onto `φ̇ = 0`, in the metric of
    /// `M`, after every accepted step and at every sample from dense
    /// output: residuals at rounding level. The default.
    #[default]
    Projection,
    /// Replace `φ̈ = 0` by `φ̈ + 2α φ̇ + β² φ = 0`: drift damped at rate `β`,
    /// with damping `α` (`α = β` is critical damping). Both must be finite
    /// and non-negative; they are rates, in the model's units of inverse
    /// time.
    Baumgarte {
        /// The damping rate `α`.
        alpha: S,
        /// The stiffness rate `β`.
        beta: S,
    },
    /// No control: the drift as the method leaves it, for measuring it.
    None,
}

/// What to do with an initial state off the constraints beyond rounding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum InitialConditions {
    /// Project it as after a step, report the corrections in
    /// [`Stats`](crate::trajectory::Stats) and integrate from the corrected state (the
    /// sample at `t0` is that state). The default.
    #[default]
    Project,
    /// Refuse it with
    /// [`InconsistentInitialConditions`](crate::error::InvalidInput::InconsistentInitialConditions).
    Reject,
}

/// The constraint handling of one run, as a constrained model hands it to
/// a [`Visitor`](super::constraints::Visitor) with its constraints.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ConstraintSettings<S> {
    /// The drift control.
    pub drift: Drift<S>,
    /// The rule for an inconsistent start.
    pub initial: InitialConditions,
}

impl<S> Default for ConstraintSettings<S> {
    /// Projection after every step, inconsistent starts projected.
    fn default() -> Self {
        Self {
            drift: Drift::Projection,
            initial: InitialConditions::Project,
        }
    }
}

impl<S: RealField + Copy> ConstraintSettings<S> {
    /// The Baumgarte terms `(2α, β²)` added to `γ` as `2α φ̇ + β² φ`, if
    /// that is the drift control.
    pub(crate) fn baumgarte(&self) -> Option<(S, S)> {
        match self.drift {
            Drift::Baumgarte { alpha, beta } => Some((alpha + alpha, beta * beta)),
            _ => None,
        }
    }

    /// Whether states are projected after steps and at samples.
    pub(crate) fn projects(&self) -> bool {
        matches!(self.drift, Drift::Projection)
    }
}

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
/// initial conditions: [`Holonomic::with_drift`](super::constraints::Holonomic::with_drift),
/// [`Holonomic::with_initial_conditions`](super::constraints::Holonomic::with_initial_conditions).
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
