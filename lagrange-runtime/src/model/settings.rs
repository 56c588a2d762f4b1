//! How a run keeps the constraints: the drift control, and what to do with
//! an inconsistent start, as data of the contract. A model's own are its
//! [`Holonomic`](super::constraints::Holonomic) visit's; the layer that
//! changes them is `handling.rs`'s
//! [`ConstraintHandling`](super::handling::ConstraintHandling).

use nalgebra::RealField;

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
