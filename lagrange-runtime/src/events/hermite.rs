//! The cubic Hermite interpolant of a step, for methods without dense
//! output: `(q, q̇)` and their slopes `(q̇, q̈)` at both ends.
//!
//! Its error is `O(h⁴)` (the fourth derivative of the solution, times
//! `h⁴/384` at mid-step), whatever the order of the method that made the
//! step, so an event located on it is that accurate: exact for a solution
//! cubic in `t`, such as free fall.

use nalgebra::{RealField, SVector};

use crate::trajectory::State;

/// One step's interpolant, from `(t0, q0, q̇0, q̈0)` to `(t1, q1, q̇1, q̈1)`.
pub(crate) struct Hermite<S, const N: usize> {
    t0: S,
    h: S,
    start: State<S, N>,
    end: State<S, N>,
    /// `q̈` at the ends: the slopes of `q̇`.
    qddot: (SVector<S, N>, SVector<S, N>),
}

impl<S: RealField + Copy, const N: usize> Hermite<S, N> {
    pub(crate) fn new(
        (t0, start, qddot0): (S, State<S, N>, SVector<S, N>),
        (t1, end, qddot1): (S, State<S, N>, SVector<S, N>),
    ) -> Self {
        Self {
            t0,
            h: t1 - t0,
            start,
            end,
            qddot: (qddot0, qddot1),
        }
    }

    /// The state at `t`, in the step.
    pub(crate) fn at(&self, t: S) -> State<S, N> {
        let (one, two, three) = (
            S::one(),
            S::one() + S::one(),
            nalgebra::convert::<f64, S>(3.0),
        );
        let s = (t - self.t0) / self.h;
        let (s2, s3) = (s * s, s * s * s);
        // The Hermite basis: values at 0 and 1, and slopes (times h).
        let h00 = two * s3 - three * s2 + one;
        let h01 = three * s2 - two * s3;
        let h10 = (s3 - two * s2 + s) * self.h;
        let h11 = (s3 - s2) * self.h;
        let ((q0, v0), (q1, v1)) = (self.start, self.end);
        let (a0, a1) = self.qddot;
        (
            q0 * h00 + q1 * h01 + v0 * h10 + v1 * h11,
            v0 * h00 + v1 * h01 + a0 * h10 + a1 * h11,
        )
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector1;

    use super::*;

    #[test]
    fn exact_for_free_fall_and_fourth_order_on_a_cosine() {
        // z = 1 − g t²/2 on [0.3, 0.7]: a quadratic, reproduced to rounding.
        let g = 9.81;
        let fall = |t: f64| (Vector1::new(1.0 - g * t * t / 2.0), Vector1::new(-g * t));
        let a = Vector1::new(-g);
        let hermite = Hermite::new((0.3, fall(0.3), a), (0.7, fall(0.7), a));
        for t in [0.3, 0.41, 0.5, 0.69, 0.7] {
            let ((q, v), (qe, ve)) = (hermite.at(t), fall(t));
            assert!((q - qe).amax() < 1e-15 && (v - ve).amax() < 1e-14, "{t}");
        }
        // cos t: the mid-step error falls 16-fold per halving of h (the
        // leading term h⁴/384 |x⁗|, next terms O(h⁵)); 12 allows for them.
        let wave = |t: f64| (Vector1::new(t.cos()), Vector1::new(-t.sin()));
        let error = |h: f64| {
            let ends = |t: f64| (t, wave(t), Vector1::new(-t.cos()));
            let hermite = Hermite::new(ends(1.0), ends(1.0 + h));
            (hermite.at(1.0 + h / 2.0).0 - wave(1.0 + h / 2.0).0).amax()
        };
        let (coarse, fine) = (error(0.2), error(0.1));
        assert!(coarse / fine > 12.0, "{coarse} / {fine}");
        assert!(coarse < 0.2f64.powi(4) / 384.0 * 1.1, "{coarse}");
    }
}
