//! Step-size control shared by the adaptive methods: the default tolerance,
//! Hairer's initial step guess, and the two checks before every attempt
//! (the step budget, and whether `h` still moves `t`).

use nalgebra::{RealField, SVector};

use super::record::{Evaluate, Recorder};

/// The adaptive methods' default `rtol = atol`: `1e-8`, raised to `100 ε`
/// for scalar types with fewer digits (`1.2e-5` for `f32`).
pub(crate) fn default_tolerance<S: RealField + Copy>() -> S {
    nalgebra::convert::<f64, S>(1e-8).max(nalgebra::convert::<f64, S>(100.0) * S::default_epsilon())
}

/// Hairer's `hinit`, shared by the adaptive methods: a first step for which
/// a method of order `order` would roughly meet the tolerance, from
/// estimates of the first and second derivative at `start = (t, q, q̇, q̈)`.
/// Costs one right-hand side (an explicit Euler probe).
pub(crate) fn initial_step<S, E, const N: usize>(
    rec: &mut Recorder<'_, S, N>,
    model: &E,
    (t, q, qdot, qddot): (S, &SVector<S, N>, &SVector<S, N>, &SVector<S, N>),
    h_max: S,
    scale: &FirstStep<S>,
) -> S
where
    S: RealField + Copy,
    E: Evaluate<S, N> + ?Sized,
{
    let h0 = scale.probe((q, qdot, qddot)).min(h_max);
    // One explicit Euler step estimates the second derivative.
    let (q1, qdot1) = (q + qdot * h0, qdot + qddot * h0);
    let Ok(qddot1) = rec.rhs(model, t + h0, &q1, &qdot1) else {
        // The model breaks down there; let the step control find out.
        return h0;
    };
    scale.finish(
        h0,
        h_max,
        scale.step(h0, (q, qdot, qddot), (&qdot1, &qddot1)),
    )
}

/// The arithmetic of Hairer's `hinit` for one state, apart from the
/// evaluation of its probe, so that a run and each lane of an
/// [`AdaptiveEnsemble`](crate::ensemble::AdaptiveEnsemble) guess alike.
pub(crate) struct FirstStep<S> {
    pub(crate) rtol: S,
    pub(crate) atol: S,
    pub(crate) order: u8,
}

impl<S: RealField + Copy> FirstStep<S> {
    /// The error scale of a component `y`.
    fn scale(&self, y: S) -> S {
        self.atol + self.rtol * y.abs()
    }

    /// The step `h0` of the explicit Euler probe, from the sizes of the
    /// state and of its derivative at `(q, q̇, q̈)`; never zero nor NaN.
    pub(crate) fn probe<const N: usize>(
        &self,
        (q, qdot, qddot): (&SVector<S, N>, &SVector<S, N>, &SVector<S, N>),
    ) -> S {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let y = q.iter().chain(qdot.iter());
        let f0 = qdot.iter().chain(qddot.iter());
        let dny = y
            .clone()
            .fold(S::zero(), |s, &y| s + (y / self.scale(y)).powi(2));
        let dnf = f0
            .zip(y)
            .fold(S::zero(), |s, (&f, &y)| s + (f / self.scale(y)).powi(2));
        let h0 = if dnf <= c(1e-10) || dny <= c(1e-10) {
            c(1e-6)
        } else {
            (dny / dnf).sqrt() * c(0.01)
        };
        // A sum of squares that overflowed (a tiny atol makes f / atol huge)
        // leaves no estimate, only 0 or NaN: take RADAU5's default first
        // step, as Radau5 does, and let the step control adapt it.
        if h0.is_finite() && h0 > S::zero() {
            h0
        } else {
            c(1e-6)
        }
    }

    /// The step from the probe of `h0`, which reached `(q̇₁, q̈₁)`:
    /// `h1` such that `h1^order · max(|f0|, |f'|) = 0.01`, at most `100 h0`.
    pub(crate) fn step<const N: usize>(
        &self,
        h0: S,
        (q, qdot, qddot): (&SVector<S, N>, &SVector<S, N>, &SVector<S, N>),
        (qdot1, qddot1): (&SVector<S, N>, &SVector<S, N>),
    ) -> S {
        let c = |x: f64| -> S { nalgebra::convert(x) };
        let y = q.iter().chain(qdot.iter());
        let dnf = qdot
            .iter()
            .chain(qddot.iter())
            .zip(y.clone())
            .fold(S::zero(), |s, (&f, &y)| s + (f / self.scale(y)).powi(2));
        let f1 = qdot1.iter().chain(qddot1.iter());
        let f0 = qdot.iter().chain(qddot.iter());
        let der2 = f1
            .zip(f0)
            .zip(y)
            .fold(S::zero(), |s, ((&f1, &f0), &y)| {
                s + ((f1 - f0) / self.scale(y)).powi(2)
            })
            .sqrt()
            / h0;
        let der12 = der2.max(dnf.sqrt());
        let h1 = if der12 <= c(1e-15) {
            c(1e-6).max(h0 * c(1e-3))
        } else {
            (c(0.01) / der12).powf(c(1.0 / f64::from(self.order)))
        };
        (h0 * c(100.0)).min(h1)
    }

    /// The first step: `step` bounded by `h_max`, or `h0` where it is not a
    /// positive number.
    pub(crate) fn finish(&self, h0: S, h_max: S, step: S) -> S {
        let h = step.min(h_max);
        if h.is_finite() && h > S::zero() {
            h
        } else {
            h0
        }
    }
}

/// Whether an attempt of size `h` from `t` is still possible: `h` above
/// `10 ε |t|` and `t + h ≠ t`. Below that, the adaptive methods stop with
/// [`StepSizeUnderflow`](crate::error::IntegrationError::StepSizeUnderflow) (or
/// the model failure that made them shrink `h`).
pub(crate) fn advances<S: RealField + Copy>(t: S, h: S) -> bool {
    let underflow = nalgebra::convert::<f64, S>(10.0) * S::default_epsilon();
    h > underflow * t.abs() && t + h != t
}
