//! The slopes of an explicit Runge–Kutta step, kept from step to step, and
//! the sums over them that a tableau's rows weigh: shared by [`Dopri5`]
//! (7 stages) and [`Dop853`] (16). And what the first-same-as-last pairs
//! with one error estimate share: their stage loop over a tableau's
//! constant rows ([`fsal_step`]), the step it makes ([`Step`]) and the
//! test of its error ([`Step::judge`]), and their settings' builders
//! (`pair_settings!`). The stages, the step and its error are written once
//! for scalars and SIMD lanes of them (`V`, `V = S` for a scalar run): the
//! [`AdaptiveEnsemble`](crate::ensemble::AdaptiveEnsemble) steps its lanes
//! with Dopri5's tableau through the same [`fsal_step`].
//!
//! [`Dopri5`]: crate::integrators::Dopri5
//! [`Dop853`]: crate::integrators::Dop853

use nalgebra::{RealField, SVector, SimdRealField};

use crate::driver::Recorder;
use crate::driver::pair::Outcome;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::model::Lagrangian;

/// The slopes of the `K` stages of a step, split as the state is: stage
/// `j`'s slope is `(k_q[j], k_q̇[j]) = (q̇_j, q̈_j)`.
pub(crate) struct Stages<V, const N: usize, const K: usize> {
    /// The `q` part of each slope, which is the stage's own `q̇`.
    pub(crate) q: [SVector<V, N>; K],
    /// The `q̇` part of each slope, `q̈`.
    pub(crate) qdot: [SVector<V, N>; K],
}

impl<V, const N: usize, const K: usize> Stages<V, N, K>
where
    V: SimdRealField + Copy,
    V::Element: RealField + Copy,
{
    /// Stage 1 is `f` at the start, `(q̇, q̈)`; the others are filled by each
    /// step before anything reads them.
    pub(crate) fn new(qdot: &SVector<V, N>, qddot: &SVector<V, N>) -> Self {
        Self {
            q: [*qdot; K],
            qdot: [*qddot; K],
        }
    }

    /// `(Σ w_j k_q[j], Σ w_j k_q̇[j])` in stage order, over one of a
    /// tableau's constant rows. Inlined where it is called, the loop is
    /// unrolled over a row known at compile time, its zeros dropped there
    /// and its weights immediates; over a row chosen at run time it stays a
    /// loop. A zero weight is skipped: the same bits as adding its product,
    /// because the slopes are finite (each comes from a state the solve
    /// accepted) and a sum begun at `+0` is never `−0`, so adding `±0`
    /// leaves it unchanged.
    #[inline(always)]
    pub(crate) fn sum(&self, weights: &'static [f64]) -> (SVector<V, N>, SVector<V, N>) {
        let (mut sq, mut sqdot) = (SVector::<V, N>::zeros(), SVector::<V, N>::zeros());
        for (j, &x) in weights.iter().enumerate() {
            if x != 0.0 {
                let w = V::splat(nalgebra::convert::<f64, V::Element>(x));
                sq += self.q[j] * w;
                sqdot += self.qdot[j] * w;
            }
        }
        (sq, sqdot)
    }

    /// After an accepted step, its slope at the new state (stage `last`,
    /// 0-based) is the next step's first: first same as last.
    pub(crate) fn first_same_as_last(&mut self, last: usize) {
        self.q[0] = self.q[last];
        self.qdot[0] = self.qdot[last];
    }
}

/// One attempted step of a pair with one error estimate: the higher-order
/// solution and the estimate. Its stages stay in the [`Stages`] it was
/// computed in, so that an attempt moves a few vectors, not all the slopes
/// (a copy through `memcpy` on every step: with it, and with the weights
/// read from a table built per run, Dopri5 took 45.6 ns per evaluation on
/// the double pendulum instead of 41.0, the two builds alternating in one
/// run of `cargo bench -p lagrange-studies --bench rhs_overhead` when this
/// changed; BENCHMARKS.md, "Constant weights, no copies", says why).
pub struct Step<V, const N: usize> {
    pub(crate) q: SVector<V, N>,
    pub(crate) qdot: SVector<V, N>,
    pub(crate) err_q: SVector<V, N>,
    pub(crate) err_qdot: SVector<V, N>,
}

impl<V, const N: usize> Step<V, N>
where
    V: SimdRealField + Copy,
    V::Element: RealField + Copy,
{
    /// Hairer's error norm, lane by lane: the RMS over `q` and `q̇` of the
    /// embedded error relative to `atol + rtol max(|y_old|, |y_new|)`.
    pub(crate) fn error(
        &self,
        (rtol, atol): (V::Element, V::Element),
        q: &SVector<V, N>,
        qdot: &SVector<V, N>,
    ) -> V {
        let (rtol, atol) = (V::splat(rtol), V::splat(atol));
        let mut sum = V::zero();
        let parts = [
            (q, &self.q, &self.err_q),
            (qdot, &self.qdot, &self.err_qdot),
        ];
        for (y0, y1, e) in parts {
            for i in 0..N {
                let sk = atol + rtol * y0[i].simd_abs().simd_max(y1[i].simd_abs());
                let x = e[i] / sk;
                sum += x * x;
            }
        }
        let n = V::splat(nalgebra::convert::<f64, V::Element>((2 * N).max(1) as f64));
        (sum / n).simd_sqrt()
    }
}

impl<S: RealField + Copy, const N: usize> Step<S, N> {
    /// The step from `(q, q̇)` judged: accepted when its error is within
    /// the tolerances, rejected with the error otherwise. Finite stages
    /// with a non-finite error are an overflow in the sums: an error at
    /// `t_new`, which rejects the step as a failing stage does.
    pub(crate) fn judge(
        self,
        tolerances: (S, S),
        (q, qdot): (&SVector<S, N>, &SVector<S, N>),
        t_new: S,
    ) -> Result<Outcome<S, Self>, IntegrationError<S, N>> {
        let err = self.error(tolerances, q, qdot);
        if !err.is_finite() {
            let (q, qdot, value) = (self.q, self.qdot, NonFiniteValue::State);
            return Err(IntegrationError::NonFiniteState {
                t: t_new,
                q,
                qdot,
                value,
            });
        }
        Ok(if err <= S::one() {
            Outcome::Accepted { step: self, err }
        } else {
            Outcome::Rejected { err }
        })
    }
}

/// One step of size `h` of a first-same-as-last explicit tableau of `K`
/// stages from `(t, q, q̇)`, `q̈` there in the first stage of `k`: stage
/// `i` at `t + c_i h` from row `i` of `a`, whose last row is the weights
/// `b`, so the last stage is the new state (and the next step's first);
/// `e = b − b̂` the error estimate's weights. The stages are left in `k`.
/// Inlined, the rows are constants at each call: unrolled sums with the
/// zeros dropped and the weights immediates ([`Stages::sum`]). `slope` is
/// `q̈ = a(t, q, q̇)`: a run's right-hand side through its recorder
/// ([`model_slope`]), or every lane's at once for an ensemble.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fsal_step<V, E, const N: usize, const K: usize>(
    slope: &mut impl FnMut(V::Element, &SVector<V, N>, &SVector<V, N>) -> Result<SVector<V, N>, E>,
    (t, t_new, h): (V::Element, V::Element, V::Element),
    (q, qdot): (&SVector<V, N>, &SVector<V, N>),
    k: &mut Stages<V, N, K>,
    a: &[&'static [f64]; K],
    c: &[V::Element; K],
    e: &'static [f64],
) -> Result<Step<V, N>, E>
where
    V: SimdRealField + Copy,
    V::Element: RealField + Copy,
{
    let hv = V::splat(h);
    k.q[0] = *qdot;
    let mut q_new = *q;
    for (i, (&row, &c)) in a.iter().zip(c).enumerate().skip(1) {
        let (dq, dqdot) = k.sum(row);
        let (qi, qdoti) = (q + dq * hv, qdot + dqdot * hv);
        // The last row holds the weights b, so the last stage is the new
        // state, at exactly the time the clock moves to.
        let ti = if i == K - 1 { t_new } else { t + c * h };
        k.qdot[i] = slope(ti, &qi, &qdoti)?;
        k.q[i] = qdoti;
        q_new = qi;
    }
    let (err_q, err_qdot) = k.sum(e);
    Ok(Step {
        q: q_new,
        qdot: k.q[K - 1],
        err_q: err_q * hv,
        err_qdot: err_qdot * hv,
    })
}

/// A run's right-hand side as [`fsal_step`]'s `slope`: the model's `q̈`
/// through the recorder, which counts it.
#[inline(always)]
pub(crate) fn model_slope<'r, L, S, const N: usize>(
    rec: &'r mut Recorder<'_, S, N>,
    model: &'r L,
) -> impl FnMut(S, &SVector<S, N>, &SVector<S, N>) -> Result<SVector<S, N>, IntegrationError<S, N>> + 'r
where
    S: RealField + Copy,
    L: Lagrangian<N, Scalar = S>,
{
    move |t, q, qdot| rec.rhs(model, t, q, qdot)
}

/// The settings of an explicit embedded pair `$ty<S>` (a struct whose
/// field `settings: Tolerances<S>` holds them): `new` with the shared
/// defaults (`rtol = atol = 1e-8`, raised to `100 ε` for scalar types with
/// fewer digits; a budget of 100 000 steps), the three builders and
/// `Default`. `$new` is the pair's own line on its defaults. A generic
/// settings type names its parameters in brackets and the initializers of
/// its other fields in braces: `pair_settings!([T: Tr] Ty<T, S>, { f: v }, "…")`.
macro_rules! pair_settings {
    ($ty:ident, $new:literal) => {
        $crate::integrators::stages::pair_settings!([] $ty<S>, {}, $new);
    };
    ([$($generics:tt)*] $ty:ty, { $($field:ident: $value:expr),* }, $new:literal) => {
        impl<S: RealField + Copy, $($generics)*> $ty {
            #[doc = $new]
            pub fn new() -> Self {
                let tol = $crate::driver::default_tolerance::<S>();
                Self {
                    settings: $crate::driver::pair::Tolerances {
                        rtol: tol,
                        atol: tol,
                        max_steps: 100_000,
                    },
                    $($field: $value),*
                }
            }

            /// Relative tolerance; must be at least `10 ε`, and has no
            /// upper bound. A loose one is honoured as asked; from about
            /// `0.1` up the error control no longer holds an explicit step
            /// within its stability region, and a run that then blows up
            /// stops with [`Unstable`]($crate::error::IntegrationError::Unstable),
            /// as a fixed step beyond its limit does (use
            /// [`Radau5`]($crate::integrators::Radau5) for such tolerances).
            pub fn rtol(mut self, rtol: S) -> Self {
                self.settings.rtol = rtol;
                self
            }

            /// Absolute tolerance, the error scale for components near
            /// zero; must be positive.
            pub fn atol(mut self, atol: S) -> Self {
                self.settings.atol = atol;
                self
            }

            /// The step budget, counting rejected steps too, so that every
            /// call ends.
            pub fn max_steps(mut self, max_steps: usize) -> Self {
                self.settings.max_steps = max_steps;
                self
            }
        }

        impl<S: RealField + Copy, $($generics)*> Default for $ty {
            fn default() -> Self {
                Self::new()
            }
        }
    };
}
pub(crate) use pair_settings;
