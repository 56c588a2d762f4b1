//! The growth guard: how a fixed-step run, or an explicit adaptive one at a
//! tolerance too loose to hold its step, notices that the step is beyond
//! the method's stability limit before the state overflows.

use nalgebra::{RealField, SVector, SimdRealField};

use crate::trajectory::State;

/// Watches a run for step-size instability, by two signatures of
/// a mode that the step amplifies but cannot resolve. Both only count once
/// the state's size (largest component of `q`, `q̇`) is above 1000× its
/// starting scale, far beyond anything the start explains:
///
/// - **fast growth**: the size more than doubles on each step of a run,
///   `|R(hλ)| > 2`, until it exceeds the largest size seen before the run by
///   `2^STEPS`. A resolved motion
///   would need `λ h > 0.69` per step for that, where no method is
///   accurate. The total, not the run's length, decides: a mode that was
///   small beside the rest of the state (a kink between a light and a heavy
///   body) shows in the state's size only in its last steps before
///   overflow, growing 100× or more per step, and is stopped there.
/// - **unresolved growth**: the step is unresolved (a running mean over
///   about [`GrowthGuard::STEPS`] steps of the measure below is at least ½)
///   and the state grows [`GrowthGuard::FOLD`]-fold meanwhile. A step is
///   unresolved when the state changes by a sizable fraction of itself (it
///   turns by 30° or more, or flips sign: fewer than a dozen steps per
///   period), or when `Δq` disagrees with the trapezoidal rule on `q̇`,
///   `(h/2)(q̇ₙ + q̇ₙ₊₁)`, by as much as they measure themselves: a resolved
///   step agrees to `O(h²ω²)`, a mode that decays at rate `λ` in the model
///   but grows in the method (`R(hλ) > 1` for `hλ` past the limit on the
///   negative real axis, a stiff damper) does not agree at all. This is how
///   a mode just beyond the stability limit grows: RK4 at `hω = 1.01 · 2√2`
///   gains 7 % per step while turning by 106°, and at `hλ = −1.01 · 2.785`
///   2 % per step without turning. Too slow for the first signature, it
///   would otherwise run on into finite garbage or an overflow.
///
/// Growth that is smooth and slower than 2× per step (a physical
/// instability, or explicit Euler's slow energy gain at small `hω`) is not
/// an instability of the step and is left alone.
#[derive(Clone, Copy)]
pub(crate) struct GrowthGuard<S> {
    floor: S,
    last: S,
    run: usize,
    /// The largest size seen so far, and as it was when the current run of
    /// doubling steps began.
    peak: S,
    run_peak: S,
    /// Running mean of how unresolved the steps are.
    roughness: S,
    /// Size and steps since an unresolved, above-floor stretch began.
    stretch: Option<(S, usize)>,
}

impl<S: RealField + Copy> GrowthGuard<S> {
    const STEPS: usize = 8;
    const FOLD: f64 = 8.0;

    pub(crate) fn new<const N: usize>(q: &SVector<S, N>, qdot: &SVector<S, N>) -> Self {
        let size = Self::size(q, qdot);
        Self {
            floor: nalgebra::convert::<f64, S>(1000.0) * size.max(S::one()),
            last: size,
            run: 0,
            peak: size,
            run_peak: size,
            roughness: S::zero(),
            stretch: None,
        }
    }

    fn size<const N: usize>(q: &SVector<S, N>, qdot: &SVector<S, N>) -> S {
        q.iter()
            .chain(qdot.iter())
            .fold(S::zero(), |m, x| m.max(x.abs()))
    }

    /// After a step of length `h` from `before` to `after`: `Some(steps)`
    /// once either signature has lasted long enough to stop, `steps` being
    /// how long.
    #[inline]
    pub(crate) fn unstable<const N: usize>(
        &mut self,
        before: State<S, N>,
        after: (&SVector<S, N>, &SVector<S, N>),
        h: S,
    ) -> Option<usize> {
        let step = measure((&before.0, &before.1), after, h);
        self.judge_unresolved(step.size, step.unresolved(self.last))
    }

    /// The size of the state after the last step: what
    /// [`Measured::unresolved`] takes.
    pub(crate) fn last(&self) -> S {
        self.last
    }

    /// [`unstable`](Self::unstable) from the step's size and how unresolved
    /// it is ([`measure`], [`Measured::unresolved`], taken before: on the
    /// lanes for an ensemble, whose guards are one per lane).
    pub(crate) fn judge_unresolved(&mut self, size: S, unresolved: S) -> Option<usize> {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let steps = c(Self::STEPS as f64);
        self.roughness += (unresolved - self.roughness) / steps;
        if size > c(2.0) * self.last {
            if self.run == 0 {
                self.run_peak = self.peak;
            }
            self.run += 1;
        } else {
            self.run = 0;
        }
        self.last = size;
        self.peak = self.peak.max(size);
        if size <= self.floor {
            self.stretch = None;
            return None;
        }
        // The run must carry the size 2^STEPS past the largest size seen
        // before it (the envelope), not merely past where it started: the
        // size max(|q|, |q̇|) dips when the larger component crosses zero,
        // and a resolved oscillation climbing back out of such a dip must not
        // look like a blow-up. At least two steps: a single jump is the first
        // step from rest of a stiff spring (q̇ goes from 0 to ω q).
        if self.run >= 2 && size > c(2f64.powi(Self::STEPS as i32)) * self.run_peak {
            return Some(self.run);
        }
        if self.roughness < c(0.5) {
            self.stretch = None;
            return None;
        }
        let (start, steps) = self.stretch.get_or_insert((size, 0));
        *steps += 1;
        (size >= c(Self::FOLD) * *start).then_some(*steps)
    }
}

/// What the guard reads of a step: the state's size after it (the largest
/// component of `q`, `q̇`), the size of its change, and how far `Δq`
/// disagrees with the trapezoidal rule on `q̇`, `(h/2)(q̇ₙ + q̇ₙ₊₁)`,
/// relative to both (zero where both are).
#[derive(Clone, Copy)]
pub(crate) struct Measured<S> {
    pub(crate) size: S,
    pub(crate) change: S,
    pub(crate) disagreement: S,
}

impl<V: SimdRealField + Copy> Measured<V> {
    /// How unresolved the step is: how much the state changed against its
    /// size (after the step, or `last` before it, whichever is larger), or
    /// the disagreement if that is more; zero where the sizes are.
    #[inline]
    pub(crate) fn unresolved(&self, last: V) -> V {
        let (zero, whole) = (V::zero(), larger(self.size, last));
        let ratio = (self.change / whole).select(whole.simd_gt(zero), zero);
        larger(ratio, self.disagreement)
    }
}

/// A step [`Measured`], for a scalar state or lane by lane for SIMD lanes
/// of states (each lane's values its scalar's: the same operations on
/// finite values, maxima taken in any order). Every value must be finite.
#[inline]
pub(crate) fn measure<V: SimdRealField + Copy, const N: usize>(
    before: (&SVector<V, N>, &SVector<V, N>),
    after: (&SVector<V, N>, &SVector<V, N>),
    h: V,
) -> Measured<V> {
    let zero = V::zero();
    let half_h = h / (V::one() + V::one());
    let (mut size, mut change, mut dq_max, mut trapezoid_max, mut apart) =
        (zero, zero, zero, zero, zero);
    for i in 0..N {
        size = larger(larger(size, after.0[i].simd_abs()), after.1[i].simd_abs());
        let dq = after.0[i] - before.0[i];
        let trapezoid = (before.1[i] + after.1[i]) * half_h;
        change = larger(
            larger(change, dq.simd_abs()),
            (after.1[i] - before.1[i]).simd_abs(),
        );
        dq_max = larger(dq_max, dq.simd_abs());
        trapezoid_max = larger(trapezoid_max, trapezoid.simd_abs());
        apart = larger(apart, (dq - trapezoid).simd_abs());
    }
    let whole = dq_max + trapezoid_max;
    let disagreement = (apart / whole).select(whole.simd_gt(zero), zero);
    Measured {
        size,
        change,
        disagreement,
    }
}

/// The larger of `a` and `b`, both finite and not `−0` (sizes, absolute
/// values): `a > b ? a : b`, one `maxsd` for a scalar, where
/// `simd_max`'s `a >= b ? a : b` is a compare and three logical
/// operations (issue 49). The same value for such arguments.
#[inline]
fn larger<V: SimdRealField + Copy>(a: V, b: V) -> V {
    a.select(a.simd_gt(b), b)
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector1;

    use super::GrowthGuard;

    /// Feeds the guard a state of each size in turn (as `q`, unit steps;
    /// `q̇` consistent with smooth exponential growth between samples when
    /// `smooth`, else zero) and returns the step (1-based) at which it stops
    /// the run, if any.
    fn stops(start: f64, sizes: &[f64], smooth: bool) -> Option<(usize, usize)> {
        let velocity = |prev: f64, next: f64| {
            if smooth && prev > 0.0 && next.is_finite() && next > 0.0 {
                next * (next / prev).ln()
            } else {
                0.0
            }
        };
        let mut guard = GrowthGuard::new(&Vector1::new(start), &Vector1::new(0.0));
        let mut before = (Vector1::new(start), Vector1::new(0.0));
        sizes.iter().enumerate().find_map(|(k, &size)| {
            let after = (
                Vector1::new(size),
                Vector1::new(velocity(before.0[0], size)),
            );
            let stop = guard.unstable(before, (&after.0, &after.1), 1.0);
            before = after;
            stop.map(|run| (k + 1, run))
        })
    }

    fn stops_at(start: f64, sizes: &[f64]) -> Option<(usize, usize)> {
        stops(start, sizes, true)
    }

    #[test]
    fn eight_doublings_past_the_floor_stop_the_run() {
        // Already near the floor (1000× the start), then 2.1× per step:
        // 2.1^8 = 378 is the first power past 2^8.
        let mut sizes = vec![500.0, 500.0];
        sizes.extend((1..=12).map(|k| 500.0 * 2.1f64.powi(k)));
        let stop = stops(1.0, &sizes, false);
        assert!(matches!(stop, Some((k, _)) if k <= 10), "{stop:?}");
    }

    /// A fast mode hidden under a larger slow motion shows in the state's
    /// size only when it overtakes it, then grows by orders of magnitude per
    /// step: stopped as soon as the total passes 256×, not after eight steps
    /// (by which time it would have overflowed).
    #[test]
    fn a_blow_up_faster_than_geometric_is_stopped_within_steps() {
        let sizes = [0.5, 0.5, 0.5, 5.0, 1e4, 1e86, f64::INFINITY];
        assert_eq!(stops_at(0.5, &sizes), Some((5, 2)));
    }

    #[test]
    fn a_single_jump_below_the_floor_is_no_alarm() {
        // 300× in one step, but still below 1000× the starting scale: a
        // fast transient, not yet a blow-up.
        assert_eq!(stops(1.0, &[1.0, 300.0, 300.0, 280.0], false), None);
    }

    #[test]
    fn slow_smooth_growth_is_never_stopped() {
        // 10 % per step, resolved (the velocity matches the growth): a
        // physical instability, not the step's.
        let sizes: Vec<f64> = (1..=200).map(|k| 1.1f64.powi(k)).collect();
        assert_eq!(stops_at(1.0, &sizes), None);
    }
}
