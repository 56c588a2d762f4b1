//! Which value of an evaluation was not finite.

use core::fmt;

/// Which value of an evaluation was NaN or infinite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum NonFiniteValue {
    /// The state `(q, q̇)` handed to the model, e.g. after an overflow.
    State,
    /// The mass matrix `M(t, q)` returned by the model.
    MassMatrix,
    /// The forcing `f(t, q, q̇)` returned by the model.
    Forcing,
    /// The momenta `p = ∂L/∂q̇` returned by the model, or carried by a
    /// variational integrator after an overflow.
    Momentum,
    /// `∂L/∂q` returned by the model.
    LagrangianGradient,
    /// The non-conservative forces `Q − ∂R/∂q̇` returned by the model.
    NonconservativeForces,
    /// The Jacobians `∂q̈/∂q`, `∂q̈/∂q̇` an implicit method needs (from the
    /// model's exact residual Jacobians, or overflowing finite differences).
    Jacobian,
    /// The constraints `φ`, their Jacobian `G`, velocities `φ̇` or bias `γ`
    /// returned by the model.
    Constraints,
    /// The control inputs `u` a controller returned
    /// ([`WithLayers::with_controller`](crate::model::WithLayers::with_controller)).
    Inputs,
    /// An [event](crate::events) function's value `g(t, q, q̇)`.
    EventFunction,
    /// The state an event's reset returned.
    EventReset,
    /// A sample interpolated by a method's dense output between two
    /// finite states: the interpolant overflowed (states near the largest
    /// finite number).
    DenseOutput,
}

impl fmt::Display for NonFiniteValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::State => "the state is NaN or infinite",
            Self::MassMatrix => "the mass matrix M(t, q) returned by the model is NaN or infinite",
            Self::Forcing => "the forcing f(t, q, q̇) returned by the model is NaN or infinite",
            Self::Momentum => "the momenta p = ∂L/∂q̇ are NaN or infinite",
            Self::LagrangianGradient => "∂L/∂q returned by the model is NaN or infinite",
            Self::NonconservativeForces => {
                "the non-conservative forces Q - ∂R/∂q̇ returned by the model are NaN or infinite"
            }
            Self::Jacobian => "the Jacobians ∂q̈/∂q, ∂q̈/∂q̇ are NaN or infinite",
            Self::Constraints => {
                "the constraints φ, G, φ̇ or γ returned by the model are NaN or infinite"
            }
            Self::Inputs => "the control inputs u returned by the controller are NaN or infinite",
            Self::EventFunction => "the event function g(t, q, q̇) is NaN or infinite",
            Self::EventReset => "the state returned by the event's reset is NaN or infinite",
            Self::DenseOutput => {
                "the dense output between two finite states is NaN or infinite (it overflowed)"
            }
        })
    }
}
