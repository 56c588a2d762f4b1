//! Bogacki–Shampine 3(2): the third-order adaptive explicit pair.
//!
//! P. Bogacki and L. F. Shampine, "A 3(2) pair of Runge–Kutta formulas",
//! *Applied Mathematics Letters* 2 (1989) 321–325 (MATLAB's `ode23`):
//! four stages, the last at the new state (first same as last, three
//! right-hand sides a step), the third-order solution propagated, the
//! second-order one for the error estimate. Its continuous extension is
//! the cubic Hermite interpolant of the step's ends, `y`, `y'` at both
//! (third order, from the same stages).

use super::fsal::{Coefficients, Fsal};
use crate::driver::pair::Controller;

/// Bogacki–Shampine 3(2) with adaptive steps: three right-hand sides a
/// step, half of [`Dopri5`](crate::integrators::Dopri5)'s. Measured on the
/// methods guide's problems (BENCHMARKS.md, "The explicit pairs beside
/// each other"), it needs more evaluations than Dopri5 to reach every
/// error, down to 1e-2 on the double pendulum, and fewer only where
/// stability rather than accuracy sets the step (a stiff chain at 1e-4:
/// 0.63 of Dopri5's): a choice for `ode23`'s behaviour, not for speed on a
/// smooth model.
///
/// The local error of the second-order embedded solution is kept below
/// `atol + rtol |y|` (RMS over `q` and `q̇`, Hairer's norm and step-size
/// control), and the third-order solution is propagated. Samples come from
/// the cubic Hermite interpolant of each step. A stage where the model
/// cannot be evaluated rejects the step and retries with a fifth of it.
///
/// ```
/// use lagrange_runtime::Bs3;
///
/// let loose = Bs3::new().rtol(1e-4).atol(1e-6);
/// # let _: Bs3<f64> = loose;
/// ```
pub type Bs3<S> = Fsal<BogackiShampine, S, 4, 3>;

/// The coefficients of [`Bs3`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BogackiShampine;

impl Coefficients<4, 3> for BogackiShampine {
    const C: [f64; 4] = [0.0, 1.0 / 2.0, 3.0 / 4.0, 1.0];
    const A: [&'static [f64]; 4] = [
        &[],
        &[1.0 / 2.0],
        &[0.0, 3.0 / 4.0],
        // The third-order weights b: stage 4 is the new state (FSAL).
        &[2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0],
    ];
    /// `b − b̂`, `b̂ = (7/24, 1/4, 1/3, 1/8)`.
    const E: [f64; 4] = [-5.0 / 72.0, 1.0 / 12.0, 1.0 / 9.0, -1.0 / 8.0];
    /// The cubic Hermite interpolant, `y(θ) = y + (3θ² − 2θ³)(y₁ − y) +
    /// h(θ − 2θ² + θ³) k₁ + h(θ³ − θ²) k₄` with `y₁ − y = h Σ b_j k_j`,
    /// by powers of `θ`.
    const DENSE: [&'static [f64]; 3] = [
        &[1.0],
        &[-4.0 / 3.0, 1.0, 4.0 / 3.0, -1.0],
        &[5.0 / 9.0, -2.0 / 3.0, -8.0 / 9.0, 1.0],
    ];
    /// Hairer's control for an error estimate of order two (exponent
    /// `1/3`), without stabilization, and the initial step of a
    /// third-order method.
    const CONTROL: Controller = Controller {
        safety: 0.9,
        fac_min: 0.2,
        fac_max: 10.0,
        beta: 0.0,
        exponent: 1.0 / 3.0,
        beta_weight: 0.0,
        order: 3,
        stretch: 1.01,
    };
}

#[cfg(test)]
mod tests {
    use super::BogackiShampine;
    use crate::integrators::fsal::check_coefficients;

    #[test]
    fn the_tableau_meets_the_order_conditions() {
        check_coefficients::<BogackiShampine, 4, 3>(3, 2);
    }
}
