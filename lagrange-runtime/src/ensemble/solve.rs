//! `q̈` of every lane at once: the model's `M` and `f` on SIMD lanes, the
//! mass matrix factored lane by lane by the same row form as a scalar
//! right-hand side, each lane judged after as the scalar solve judges it.
//! A lane the fast path cannot answer for as its scalar would (a pivot not
//! positive, `M` ill-conditioned, a value not finite) is solved again
//! alone, by the scalar solve, which answers with its result (LU where
//! Cholesky refused `M`) or its error. A model that solves for `q̈` itself
//! (the recursion over a tree of links, `LaneModel::accelerations`) does so
//! on the lanes, and a lane it declines goes to the scalar solve, as its
//! scalar right-hand side does.

use nalgebra::{RealField, SVector, SimdBool, SimdPartialOrd, SimdRealField, SimdValue};

use super::LaneModel;
use crate::dynamics::mass_error;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::finite_lanes;
use crate::linalg::ldlt::{backward, factor_rows, forward};
use crate::linalg::mass::solve_mass_matrix;

/// The element type of a lane model's lanes (`f64` for `AutoF64x4`).
pub(super) type Element<L, const N: usize> = <<L as LaneModel<N>>::Lanes as SimdValue>::Element;

/// A lane's failure: which lane, and its error as its scalar run reports
/// it (at `t`, in that lane's state).
pub(super) type LaneFailure<L, const N: usize> = (usize, IntegrationError<Element<L, N>, N>);

/// `q̈` on every lane at `(t, q, q̇)`, or the first lane (lowest index)
/// whose scalar right-hand side fails, with its error.
#[inline]
pub(super) fn accelerations<L: LaneModel<N>, const N: usize>(
    model: &L,
    t: Element<L, N>,
    q: &SVector<L::Lanes, N>,
    qdot: &SVector<L::Lanes, N>,
) -> Result<SVector<L::Lanes, N>, LaneFailure<L, N>> {
    accelerations_inline(model, t, q, qdot)
}

/// [`accelerations`], written once for it and for its AVX2 copy, into
/// each of which it is inlined.
#[inline(always)]
fn accelerations_inline<L: LaneModel<N>, const N: usize>(
    model: &L,
    t: Element<L, N>,
    q: &SVector<L::Lanes, N>,
    qdot: &SVector<L::Lanes, N>,
) -> Result<SVector<L::Lanes, N>, LaneFailure<L, N>> {
    if L::SOLVES_ACCELERATIONS {
        if let Some((x, solved)) = model.accelerations(L::Lanes::splat(t), q, qdot) {
            // The scalar checks the state first, then asks the model.
            let answered = solved & finite_lanes(&[q.as_slice(), qdot.as_slice()]);
            if answered.all() {
                return Ok(x);
            }
            let (m, f) = model.mass_matrix_and_forcing(L::Lanes::splat(t), q, qdot);
            return alone(t, q, qdot, &m, &f, x, answered);
        }
    }
    let (m, f) = model.mass_matrix_and_forcing(L::Lanes::splat(t), q, qdot);
    let (l, d, inverse_d) = factor_rows(&m, |_| false).expect("lanes refuse no pivot");
    let mut x = f;
    forward(&l, &mut x);
    backward(&l, &inverse_d, &mut x);

    // Where the scalar solve takes this path: every pivot positive, the
    // smallest above `N ε` of the largest (`well_conditioned`), and the
    // state, `M`, `f` and `q̈` finite (`x · 0` is zero just where `x` is).
    let zero = nalgebra::zero::<L::Lanes>();
    let mut positive = d[0].simd_gt(zero);
    let (mut smallest, mut largest) = (d[0], d[0]);
    for &p in d.iter().skip(1) {
        positive = positive & p.simd_gt(zero);
        smallest = smallest.simd_min(p);
        largest = largest.simd_max(p);
    }
    let n: Element<L, N> = nalgebra::convert(N as f64);
    let floor = L::Lanes::splat(n * epsilon::<Element<L, N>>()) * largest;
    let finite = finite_lanes(&[
        q.as_slice(),
        qdot.as_slice(),
        m.as_slice(),
        f.as_slice(),
        x.as_slice(),
    ]);
    let answered = positive & smallest.simd_gt(floor) & finite;
    if answered.all() {
        return Ok(x);
    }
    alone(t, q, qdot, &m, &f, x, answered)
}

/// `x` with every lane not `answered` solved again alone by the scalar
/// solve from its `M` and `f`, or the first such lane's error.
#[inline(always)]
#[allow(clippy::type_complexity)]
fn alone<V, const N: usize>(
    t: V::Element,
    q: &SVector<V, N>,
    qdot: &SVector<V, N>,
    m: &nalgebra::SMatrix<V, N, N>,
    f: &SVector<V, N>,
    mut x: SVector<V, N>,
    answered: V::SimdBool,
) -> Result<SVector<V, N>, (usize, IntegrationError<V::Element, N>)>
where
    V: SimdRealField + Copy,
    V::Element: RealField + Copy,
{
    for lane in (0..V::LANES).filter(|&lane| answered.bitmask() & (1 << lane) == 0) {
        let (q, qdot) = (lane_of(q, lane), lane_of(qdot, lane));
        if !crate::driver::finite_state(&q, &qdot) {
            let value = NonFiniteValue::State;
            return Err((lane, IntegrationError::NonFiniteState { t, q, qdot, value }));
        }
        let (m, f) = (m.map(|v| v.extract(lane)), lane_of(f, lane));
        match solve_mass_matrix(&m, &f) {
            Ok(solved) => {
                for (entry, value) in x.iter_mut().zip(solved.iter()) {
                    entry.replace(lane, *value);
                }
            }
            Err(error) => return Err((lane, mass_error(error, t, &q, &qdot))),
        }
    }
    Ok(x)
}

/// [`accelerations`] compiled for AVX2, with the model's `M` and `f` it
/// inlines: the slope an [`Ensemble`](super::Ensemble) takes on a CPU with
/// AVX2 when the build has none (the same bits; see
/// [`advance_to`](super::Ensemble::advance_to)).
///
/// # Safety
///
/// The CPU must have AVX2.
#[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
#[target_feature(enable = "avx2")]
pub(super) unsafe fn accelerations_avx2<L: LaneModel<N>, const N: usize>(
    model: &L,
    t: Element<L, N>,
    q: &SVector<L::Lanes, N>,
    qdot: &SVector<L::Lanes, N>,
) -> Result<SVector<L::Lanes, N>, LaneFailure<L, N>> {
    accelerations_inline(model, t, q, qdot)
}

/// The scalar solve's `ε`.
fn epsilon<S: RealField>() -> S {
    S::default_epsilon()
}

/// Lane `lane` of a vector of lanes.
#[inline]
pub(super) fn lane_of<V: SimdRealField + Copy, const N: usize>(
    x: &SVector<V, N>,
    lane: usize,
) -> SVector<V::Element, N>
where
    V::Element: RealField + Copy,
{
    x.map(|v| v.extract(lane))
}

/// Vectors of lanes from one vector per lane.
pub(super) fn gather<V: SimdRealField + Copy, const N: usize>(
    lanes: &[SVector<V::Element, N>],
) -> SVector<V, N>
where
    V::Element: RealField + Copy,
{
    SVector::<V, N>::from_fn(|i, _| {
        let mut v = V::splat(lanes[0][i]);
        for (lane, x) in lanes.iter().enumerate().skip(1) {
            v.replace(lane, x[i]);
        }
        v
    })
}
