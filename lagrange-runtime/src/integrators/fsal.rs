//! An explicit first-same-as-last embedded pair from its coefficients
//! alone: a method of this kind is a [`Coefficients`] implementation (its
//! nodes, its rows, its error weights, the polynomial weights of its
//! continuous extension, its step-size controller) and a type alias,
//! `Fsal<Its, S, K, P>`. Everything else — the settings and their
//! builders, the [`StepMethod`], the pair the driver's loop steps
//! (`driver/pair.rs`), the stages over `integrators/stages.rs`, the error
//! test and the continuous extension — is here, once. [`Tsit5`](super::Tsit5) and
//! [`Bs3`](super::Bs3) are such pairs. [`Dopri5`](super::Dopri5) keeps its
//! own continuous extension (Hairer's `d` coefficients, whose order of
//! operations its recorded results hold) and [`Dop853`](super::Dop853)
//! its two error estimates and three extra stages.

use core::marker::PhantomData;

use nalgebra::{RealField, SVector};

use super::StepMethod;
use super::stages::{Stages, Step, fsal_step, model_slope, pair_settings};
use crate::driver::pair::{Controller, Embedded, EmbeddedPair, Outcome, PairWalk, Tolerances};
use crate::driver::{Recorder, check_tolerances};
use crate::error::{IntegrationError, InvalidInput};
use crate::model::Lagrangian;
use crate::trajectory::State;

/// The coefficients of an explicit first-same-as-last pair of `K` stages
/// with a continuous extension of degree `P` in `θ`.
pub trait Coefficients<const K: usize, const P: usize>:
    core::fmt::Debug + Clone + Copy + PartialEq + 'static
{
    /// The nodes `c_i`; `c_K = 1`.
    const C: [f64; K];
    /// The rows of `A` below the diagonal, each as long as its index
    /// (`A[0]` empty); the last row is the weights `b` of the solution
    /// propagated, so that the last stage is at the new state and is the
    /// next step's first.
    const A: [&'static [f64]; K];
    /// `b − b̂`: the weights of the error estimate.
    const E: [f64; K];
    /// The continuous extension `y(t + θh) = y + h Σ_p θ^(p+1) Σ_j
    /// DENSE[p][j] k_j`, row `p` the weights of `θ^(p+1)`; its rows sum to
    /// `b`, so that it ends on the step.
    const DENSE: [&'static [f64]; P];
    /// The step-size controller's constants.
    const CONTROL: Controller;
}

/// An explicit first-same-as-last pair with the coefficients `T`: its
/// settings, the tolerances and the step budget.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fsal<T, S, const K: usize, const P: usize> {
    settings: Tolerances<S>,
    coefficients: PhantomData<T>,
}

pair_settings!(
    [T: Coefficients<K, P>, const K: usize, const P: usize] Fsal<T, S, K, P>,
    { coefficients: PhantomData },
    "Defaults: `rtol = atol = 1e-8`, raised to `100 ε` for scalar types with fewer digits, and a budget of 100 000 steps."
);

impl<T, S, const K: usize, const P: usize> StepMethod<S> for Fsal<T, S, K, P>
where
    T: Coefficients<K, P>,
    S: RealField + Copy,
{
    type Walker<const N: usize> = PairWalk<S, Self, N>;

    fn walker<const N: usize>(&self) -> Result<Self::Walker<N>, InvalidInput<S>> {
        check_tolerances(self.settings.rtol, self.settings.atol)?;
        Ok(PairWalk::new(*self))
    }
}

impl<T, S, const N: usize, const K: usize, const P: usize> Embedded<S, N> for Fsal<T, S, K, P>
where
    T: Coefficients<K, P>,
    S: RealField + Copy,
{
    type Pair = Pair<T, S, N, K, P>;
    const CONTROL: Controller = T::CONTROL;

    fn tolerances(&self) -> Tolerances<S> {
        self.settings
    }

    fn pair(&self, qdot: &SVector<S, N>, qddot: &SVector<S, N>) -> Self::Pair {
        Pair {
            c: T::C.map(nalgebra::convert),
            rtol: self.settings.rtol,
            atol: self.settings.atol,
            k: Stages::new(qdot, qddot),
            coefficients: PhantomData,
        }
    }
}

/// The pair of one run: the nodes in `S`, the tolerances, the stages.
pub struct Pair<T, S, const N: usize, const K: usize, const P: usize> {
    c: [S; K],
    rtol: S,
    atol: S,
    k: Stages<S, N, K>,
    coefficients: PhantomData<T>,
}

/// The continuous extension of one step: for `q` and for `q̇`, the start
/// and the weights of `θ, θ², …, θ^P`, each times `h`.
pub struct Dense<S, const N: usize, const P: usize> {
    q: (SVector<S, N>, [SVector<S, N>; P]),
    qdot: (SVector<S, N>, [SVector<S, N>; P]),
}

impl<T, S, const N: usize, const K: usize, const P: usize> EmbeddedPair<S, N>
    for Pair<T, S, N, K, P>
where
    T: Coefficients<K, P>,
    S: RealField + Copy,
{
    type Step = Step<S, N>;
    type Dense = Dense<S, N, P>;

    fn attempt<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        rec: &mut Recorder<'_, S, N>,
        model: &L,
        times: (S, S, S),
        state: (&SVector<S, N>, &SVector<S, N>),
    ) -> Result<Outcome<S, Step<S, N>>, IntegrationError<S, N>> {
        let slope = &mut model_slope(rec, model);
        let step = fsal_step(slope, times, state, &mut self.k, &T::A, &self.c, &T::E)?;
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
    ) -> Dense<S, N, P> {
        let mut dense = Dense {
            q: (*q, [SVector::zeros(); P]),
            qdot: (*qdot, [SVector::zeros(); P]),
        };
        for (p, row) in T::DENSE.iter().enumerate() {
            let (wq, wqdot) = self.k.sum(row);
            (dense.q.1[p], dense.qdot.1[p]) = (wq * h, wqdot * h);
        }
        dense
    }

    /// `y + (w₁ + (w₂ + … + w_P θ) θ) θ`, by Horner's rule.
    fn dense_at(dense: &Dense<S, N, P>, theta: S) -> State<S, N> {
        let eval = |(y, w): &(SVector<S, N>, [SVector<S, N>; P])| {
            let mut sum = w[P - 1];
            for w in w[..P - 1].iter().rev() {
                sum = w + sum * theta;
            }
            y + sum * theta
        };
        (eval(&dense.q), eval(&dense.qdot))
    }

    fn advance(&mut self, _: &Step<S, N>) {
        self.k.first_same_as_last(K - 1);
    }
}

/// What the tests of each pair check of its coefficients, to the rounding
/// of their printed digits (`1e-13`): a transcription check, not a
/// derivation. The rows sum to their nodes; the quadrature conditions
/// `Σ b_i c_i^(k−1) = 1/k` hold to `order` for `b` and to `embedded` for
/// `b̂`; the tree conditions `Σ b_i a_ij c_j = 1/6` and (for an order of 4
/// or more) `Σ b_i a_ij c_j² = 1/12`; the continuous extension ends on `b`.
/// The orders themselves are measured by the integration tests that run
/// every method.
#[cfg(test)]
pub(crate) fn check_coefficients<T, const K: usize, const P: usize>(order: i32, embedded: i32)
where
    T: Coefficients<K, P>,
{
    let a = |i: usize, j: usize| T::A[i].get(j).copied().unwrap_or(0.0);
    let b = |i: usize| T::A[K - 1].get(i).copied().unwrap_or(0.0);
    let bhat = |i: usize| b(i) - T::E[i];
    let close = |x: f64, y: f64| (x - y).abs() < 1e-13;
    for (i, &c) in T::C.iter().enumerate().skip(1) {
        let row: f64 = (0..i).map(|j| a(i, j)).sum();
        assert!(close(row, c), "row {i}: {row}");
    }
    assert!(
        close(T::C[K - 1], 1.0),
        "the last stage is not at the new state"
    );
    for (weights, order, name) in [
        (&b as &dyn Fn(usize) -> f64, order, "b"),
        (&bhat, embedded, "b̂"),
    ] {
        for k in 1..=order {
            let q: f64 = (0..K).map(|i| weights(i) * T::C[i].powi(k - 1)).sum();
            assert!(close(q, 1.0 / k as f64), "{name}, order {k}: {q}");
        }
    }
    let tree = |p: i32| -> f64 {
        (0..K)
            .map(|i| b(i) * (0..i).map(|j| a(i, j) * T::C[j].powi(p)).sum::<f64>())
            .sum()
    };
    assert!(close(tree(1), 1.0 / 6.0), "{}", tree(1));
    if order >= 4 {
        assert!(close(tree(2), 1.0 / 12.0), "{}", tree(2));
    }
    for i in 0..K {
        let at_one: f64 = T::DENSE
            .iter()
            .map(|r| r.get(i).copied().unwrap_or(0.0))
            .sum();
        assert!(close(at_one, b(i)), "b_{i}(1) = {at_one}");
    }
}
