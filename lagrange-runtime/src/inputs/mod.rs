//! Control inputs: models whose forces depend on values `u` that change
//! during a run, set by a controller.
//!
//! A model written with an `inputs:` section implements [`Actuated`]
//! besides [`Lagrangian`]: its `K` inputs are fields of the model that a
//! controller sets before each evaluation, and `∂f/∂u` is generated
//! symbolically beside `M` and `f`.

use nalgebra::{SMatrix, SVector};

use crate::Lagrangian;

/// A model with `K` control inputs `u`, held in the model and set by
/// [`set_inputs`](Actuated::set_inputs).
///
/// `lagrangian!` implements it for every model with an `inputs:` section.
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
}
