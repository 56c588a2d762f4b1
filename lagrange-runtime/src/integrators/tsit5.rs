//! Tsitouras 5(4): adaptive explicit Runge–Kutta with a free dense output,
//! the non-stiff default of DifferentialEquations.jl.
//!
//! Ch. Tsitouras, "Runge–Kutta pairs of order 5(4) satisfying only the
//! first column simplifying assumption", *Computers & Mathematics with
//! Applications* 62 (2011) 770–775: seven stages, the last at the new
//! state (first same as last, six right-hand sides a step), the
//! fifth-order solution propagated, the fourth-order one for the error
//! estimate, and a continuous extension of order four from the same stages
//! (no extra evaluation). Coefficients as in DifferentialEquations.jl's
//! `tsit_tableaus.jl` (and diffsol's `Tableau::tsit45`); the first column
//! of `A` is `c_i − Σ_{j>1} a_ij`, so each row sums to its node exactly.

use super::fsal::{Coefficients, Fsal};
use crate::driver::pair::Controller;

/// Tsitouras 5(4) with adaptive steps: six right-hand sides a step, as
/// [`Dopri5`](crate::integrators::Dopri5), with coefficients chosen for a
/// smaller error per step and a dense output of order four from the same
/// stages.
///
/// The local error of the fourth-order embedded solution is kept below
/// `atol + rtol |y|` (RMS over `q` and `q̇`, Hairer's norm and step-size
/// control, as for Dopri5), and the fifth-order solution is propagated.
/// Sample times never shorten a step: samples come from the continuous
/// extension. A stage where the model cannot be evaluated rejects the step
/// and retries with a fifth of it.
///
/// ```
/// use lagrange_runtime::Tsit5;
///
/// let tight = Tsit5::new().rtol(1e-10).atol(1e-12).max_steps(1_000_000);
/// # let _: Tsit5<f64> = tight;
/// ```
pub type Tsit5<S> = Fsal<Tsitouras, S, 7, 4>;

/// The coefficients of [`Tsit5`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tsitouras;

impl Coefficients<7, 4> for Tsitouras {
    const C: [f64; 7] = C;
    const A: [&'static [f64]; 7] = A;
    const E: [f64; 7] = E;
    const DENSE: [&'static [f64]; 4] = [&R[0], &R[1], &R[2], &R[3]];
    /// Hairer's stabilized control for an error estimate of order four, as
    /// Dopri5's.
    const CONTROL: Controller = Controller {
        safety: 0.9,
        fac_min: 0.2,
        fac_max: 10.0,
        beta: 0.04,
        exponent: 0.2,
        beta_weight: 0.75,
        order: 5,
        stretch: 1.01,
    };
}

/// The nodes `c_i`.
const C: [f64; 7] = [0.0, 0.161, 0.327, 0.9, 0.980_025_540_904_509_7, 1.0, 1.0];

/// Row `i` of `A`: `a_ij` for `j < i`; the last row is the weights `b`.
const A: [&[f64]; 7] = [
    &[],
    &[C[1]],
    &[C[2] - 0.335_480_655_492_357, 0.335_480_655_492_357],
    &[
        C[3] - (-6.359_448_489_975_075 + 4.362_295_432_869_581),
        -6.359_448_489_975_075,
        4.362_295_432_869_581,
    ],
    &[
        C[4] - (-11.748_883_564_062_83 + 7.495_539_342_889_836 + -0.092_495_066_361_755_25),
        -11.748_883_564_062_83,
        7.495_539_342_889_836,
        -0.092_495_066_361_755_25,
    ],
    &[
        C[5] - (-12.920_969_317_847_11
            + 8.159_367_898_576_159
            + -0.071_584_973_281_401
            + -0.028_269_050_394_068_38),
        -12.920_969_317_847_11,
        8.159_367_898_576_159,
        -0.071_584_973_281_401,
        -0.028_269_050_394_068_38,
    ],
    &[
        0.096_460_766_818_065_23,
        0.01,
        0.479_889_650_414_499_6,
        1.379_008_574_103_742,
        -3.290_069_515_436_081,
        2.324_710_524_099_774,
    ],
];

/// `b − b̂`: fifth- minus fourth-order weights.
const E: [f64; 7] = [
    -0.001_780_011_052_225_777,
    -0.000_816_434_459_656_746_9,
    0.007_880_878_010_261_995,
    -0.144_711_007_173_262_9,
    0.582_357_165_452_555_2,
    -0.458_082_105_929_186_97,
    1.0 / 66.0,
];

/// The continuous extension: stage `i`'s weight at `θ` is
/// `b_i(θ) = Σ_p R[p][i] θ^(p+1)`, with `b_i(1) = b_i` (and `R[0]` the
/// linear term, only stage 1's).
const R: [[f64; 7]; 4] = [
    [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [
        -2.763_706_197_274_826,
        0.131_699_999_999_999_98,
        3.930_296_236_894_751_6,
        -12.411_077_166_933_676,
        37.509_313_416_511_04,
        -27.896_526_289_197_286,
        1.5,
    ],
    [
        2.913_255_461_821_912_6,
        -0.2234,
        -5.941_033_872_131_505,
        30.338_188_630_282_32,
        -88.178_904_894_766_4,
        65.091_894_674_793_66,
        -4.0,
    ],
    [
        -1.053_088_497_729_021_6,
        0.1017,
        2.490_627_285_651_253,
        -16.548_102_889_244_902,
        47.379_521_962_819_28,
        -34.870_657_861_496_61,
        2.5,
    ],
];

#[cfg(test)]
mod tests {
    use super::Tsitouras;
    use crate::integrators::fsal::check_coefficients;

    #[test]
    fn the_tableau_meets_the_order_conditions() {
        check_coefficients::<Tsitouras, 7, 4>(5, 4);
    }
}
