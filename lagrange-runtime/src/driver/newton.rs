//! What the implicit methods' Newton iterations share: the noise floor below
//! which a correction that no longer shrinks is rounding, not error.

use nalgebra::{RealField, SVector};

use crate::linalg::mass::pivot_ratio;
use crate::model::Lagrangian;

/// Below this size relative to the state, a Newton correction that no
/// longer shrinks is the noise of evaluating the equations, and the iterate
/// is as converged as the arithmetic allows: `ε (1000 + 10 N κ)` at
/// `(t, q)`. The 1000 ε is the evaluation of the model itself (sums with
/// cancellation); `10 N κ ε` is what the solve `M q̈ = f` adds, whose
/// relative error grows with `κ`, the pivot ratio of `M` (its condition
/// number, see [`pivot_ratio`]): a light body beside a heavy one
/// (`κ = 10⁶`) makes the accelerations, and so the corrections, noisy at
/// ~10⁻¹¹, where a floor of 1000 ε would call a converged step divergent.
pub(crate) fn newton_noise_floor<S, L, const N: usize>(model: &L, t: S, q: &SVector<S, N>) -> S
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
{
    let c = |x: f64| -> S { nalgebra::convert(x) };
    let kappa = pivot_ratio(&model.mass_matrix(t, q))
        .filter(|kappa| kappa.is_finite())
        .unwrap_or(S::one());
    S::default_epsilon() * (c(1000.0) + c(10.0 * N as f64) * kappa)
}
