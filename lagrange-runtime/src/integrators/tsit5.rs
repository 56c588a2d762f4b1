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

use nalgebra::{RealField, SVector};

use super::StepMethod;
use super::stages::{Stages as Slopes, Step, fsal_step, pair_settings};
use crate::driver::pair::{Controller, Embedded, EmbeddedPair, Outcome, PairWalk, Tolerances};
use crate::driver::{Recorder, check_tolerances};
use crate::error::{IntegrationError, InvalidInput};
use crate::model::Lagrangian;
use crate::trajectory::State;

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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tsit5<S> {
    settings: Tolerances<S>,
}

pair_settings!(
    Tsit5,
    "Defaults: `rtol = atol = 1e-8`, raised to `100 ε` for scalar types with fewer digits, and a budget of 100 000 steps."
);

impl<S: RealField + Copy> StepMethod<S> for Tsit5<S> {
    type Walker<const N: usize> = PairWalk<S, Self, N>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        check_tolerances(self.settings.rtol, self.settings.atol)?;
        Ok(PairWalk::new(*self))
    }
}

impl<S: RealField + Copy, const N: usize> Embedded<S, N> for Tsit5<S> {
    type Pair = Pair<S, N>;
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

    fn tolerances(&self) -> Tolerances<S> {
        self.settings
    }

    fn pair(&self, qdot: &SVector<S, N>, qddot: &SVector<S, N>) -> Pair<S, N> {
        Pair {
            c: C.map(nalgebra::convert),
            rtol: self.settings.rtol,
            atol: self.settings.atol,
            k: Slopes::new(qdot, qddot),
        }
    }
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

/// One integration's nodes, tolerances, and the stages of the last step
/// attempted (the first holds `q̈` at the current state).
pub struct Pair<S, const N: usize> {
    c: [S; 7],
    rtol: S,
    atol: S,
    k: Slopes<S, N, 7>,
}

/// The continuous extension on one accepted step: its start and the slopes
/// weighted by `h R[p][i]`, `y(t + θh) = y + Σ_p θ^(p+1) w_p`.
pub struct Dense<S, const N: usize> {
    q: (SVector<S, N>, [SVector<S, N>; 4]),
    qdot: (SVector<S, N>, [SVector<S, N>; 4]),
}

impl<S: RealField + Copy, const N: usize> EmbeddedPair<S, N> for Pair<S, N> {
    type Step = Step<S, N>;
    type Dense = Dense<S, N>;

    /// Six right-hand sides; the step is rejected when the error exceeds
    /// the tolerance.
    fn attempt<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        times: (S, S, S),
        state: (&SVector<S, N>, &SVector<S, N>),
    ) -> Result<Outcome<S, Step<S, N>>, IntegrationError<S, N>> {
        let step = fsal_step(rec, model, times, state, &mut self.k, &A, &self.c, &E)?;
        step.judge((self.rtol, self.atol), state, times.1)
    }

    fn end(step: &Step<S, N>) -> State<S, N> {
        (step.q, step.qdot)
    }

    fn dense(
        &self,
        h: S,
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        _: &Step<S, N>,
    ) -> Dense<S, N> {
        let w = |p: usize| {
            let (wq, wqdot) = self.k.sum(&R[p]);
            (wq * h, wqdot * h)
        };
        let (w0, w1, w2, w3) = (w(0), w(1), w(2), w(3));
        Dense {
            q: (*q, [w0.0, w1.0, w2.0, w3.0]),
            qdot: (*qdot, [w0.1, w1.1, w2.1, w3.1]),
        }
    }

    fn dense_at(dense: &Dense<S, N>, theta: S) -> State<S, N> {
        let eval = |(y, w): &(SVector<S, N>, [SVector<S, N>; 4])| {
            y + (w[0] + (w[1] + (w[2] + w[3] * theta) * theta) * theta) * theta
        };
        (eval(&dense.q), eval(&dense.qdot))
    }

    fn advance(&mut self, _: &Step<S, N>) {
        self.k.first_same_as_last(6);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A transcription check, not a derivation: the rows sum to their
    /// nodes, the quadrature conditions `Σ b_i c_i^(k−1) = 1/k` hold to
    /// order 5 for `b` and 4 for `b̂`, two tree conditions of orders 3 and
    /// 4 hold, and the continuous extension ends on `b`, each to the
    /// rounding of the 16 printed digits (1e-13). The orders themselves
    /// are measured by the integration tests that run every method.
    #[test]
    fn the_tableau_meets_the_order_conditions() {
        let b = A[6];
        let bhat: Vec<f64> = (0..7)
            .map(|i| b.get(i).copied().unwrap_or(0.0) - E[i])
            .collect();
        let a = |i: usize, j: usize| A[i].get(j).copied().unwrap_or(0.0);
        let close = |x: f64, y: f64| (x - y).abs() < 1e-13;
        for (i, &c) in C.iter().enumerate().skip(1) {
            let row: f64 = (0..i).map(|j| a(i, j)).sum();
            assert!(close(row, c), "row {i}: {row}");
        }
        let b7 = |i: usize| b.get(i).copied().unwrap_or(0.0);
        for k in 1..=5 {
            let q: f64 = (0..7).map(|i| b7(i) * C[i].powi(k - 1)).sum();
            assert!(close(q, 1.0 / k as f64), "b, order {k}: {q}");
        }
        for k in 1..=4 {
            let q: f64 = (0..7).map(|i| bhat[i] * C[i].powi(k - 1)).sum();
            assert!(close(q, 1.0 / k as f64), "b̂, order {k}: {q}");
        }
        // Σ b_i a_ij c_j = 1/6 (order 3) and Σ b_i a_ij c_j² = 1/12 (4).
        let tree = |p: i32| -> f64 {
            (0..7)
                .map(|i| b7(i) * (0..i).map(|j| a(i, j) * C[j].powi(p)).sum::<f64>())
                .sum()
        };
        assert!(close(tree(1), 1.0 / 6.0), "{}", tree(1));
        assert!(close(tree(2), 1.0 / 12.0), "{}", tree(2));
        // The continuous extension ends on the step: b_i(1) = b_i.
        for i in 0..7 {
            let at_one: f64 = R.iter().map(|r| r[i]).sum();
            assert!(close(at_one, b7(i)), "b_{i}(1) = {at_one}");
        }
    }
}
