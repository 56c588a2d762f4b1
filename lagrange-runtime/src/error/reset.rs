//! Why an event's reset could not give a state.

/// Why an event's reset refused the state at its event: the reason of
/// [`IntegrationError::ResetFailed`](super::IntegrationError::ResetFailed).
///
/// A reset written by a user returns [`Refused`](Self::Refused) from
/// [`Event::try_reset`](crate::events::Event::try_reset); the contacts'
/// switches return the others (see [`contact`](crate::contact)).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum ResetFailure {
    /// The reset's own reason, in its words.
    #[error("{reason}")]
    Refused {
        /// What the reset said.
        reason: String,
    },

    /// No assignment of contact modes satisfies the contact conditions:
    /// the complementarity problem has no solution (with friction,
    /// Painlevé's paradox).
    #[error(
        "no consistent contact mode {}: the contact conditions have no solution (with \
         friction, Painlevé's paradox)",
        if *.at_impact { "at the impact" } else { "after the switch" }
    )]
    NoConsistentMode {
        /// Whether at an impact (velocity level) or between impacts.
        at_impact: bool,
    },

    /// The touching contacts' forces after the switch are not determined:
    /// their rows of `G` (and of `T` for stuck ones) are dependent in the
    /// metric of `M`, or `M` is singular.
    #[error("the touching contacts' forces are not determined after the switch")]
    DependentContacts,

    /// The contacts' modes undo each other: more switches in a row at one
    /// time than a scene can need, without time passing.
    #[error("{switches} contact switches in a row at the same time: the modes undo each other")]
    Chattering {
        /// How many switches fell on that time.
        switches: usize,
    },
}

impl ResetFailure {
    /// A reset's refusal with `reason`.
    pub fn refused(reason: impl Into<String>) -> Self {
        Self::Refused {
            reason: reason.into(),
        }
    }
}
