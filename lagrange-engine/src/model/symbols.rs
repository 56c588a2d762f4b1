//! The symbols of a model and what each id stands for.

use crate::expr::SymId;

/// What a symbol id stands for. Symbol ids are dense: `t`, then the
/// coordinates, then the velocities, then the parameters, so a numeric state
/// is one slice in that order. The accelerations and the control inputs
/// come last, the inputs after the accelerations, so that a model without
/// inputs numbers its symbols (and orders its nodes) as before they existed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SymKind {
    /// The time `t`.
    Time,
    /// The coordinate `q_i`.
    Coordinate(usize),
    /// The velocity `q̇_i`.
    Velocity(usize),
    /// The parameter scalar of that index, in the order of `Model::parameters`.
    Parameter(usize),
    /// Only in the residual `M q̈ − f` of the Jacobians.
    Acceleration(usize),
    /// A control input `u_k` (`inputs:`).
    Input(usize),
}

/// The symbols of a model.
#[derive(Clone, Debug)]
pub struct Symbols {
    /// `t`.
    pub time: SymId,
    /// `q`, in order.
    pub coordinates: Vec<SymId>,
    /// `q̇`, in order.
    pub velocities: Vec<SymId>,
    /// The parameters, one per scalar.
    pub parameters: Vec<SymId>,
    /// `q̈`, in order (only in the Jacobians' residual).
    pub accelerations: Vec<SymId>,
    /// The control inputs `u`, in order.
    pub inputs: Vec<SymId>,
}

impl Symbols {
    pub(super) fn new(n: usize, p: usize, inputs: usize) -> Self {
        let id = |k: usize| SymId(k as u32);
        Symbols {
            time: id(0),
            coordinates: (0..n).map(|i| id(1 + i)).collect(),
            velocities: (0..n).map(|i| id(1 + n + i)).collect(),
            parameters: (0..p).map(|k| id(1 + 2 * n + k)).collect(),
            accelerations: (0..n).map(|i| id(1 + 2 * n + p + i)).collect(),
            inputs: (0..inputs).map(|k| id(1 + 3 * n + p + k)).collect(),
        }
    }

    /// The number of symbols.
    pub fn count(&self) -> usize {
        1 + 3 * self.coordinates.len() + self.parameters.len() + self.inputs.len()
    }

    /// What a symbol stands for.
    pub fn kind(&self, s: SymId) -> SymKind {
        let n = self.coordinates.len();
        let k = s.0 as usize;
        if k == 0 {
            SymKind::Time
        } else if k <= n {
            SymKind::Coordinate(k - 1)
        } else if k <= 2 * n {
            SymKind::Velocity(k - 1 - n)
        } else if k <= 2 * n + self.parameters.len() {
            SymKind::Parameter(k - 1 - 2 * n)
        } else if k <= 3 * n + self.parameters.len() {
            SymKind::Acceleration(k - 1 - 2 * n - self.parameters.len())
        } else {
            SymKind::Input(k - 1 - 3 * n - self.parameters.len())
        }
    }
}
