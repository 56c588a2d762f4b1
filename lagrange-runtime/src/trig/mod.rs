//! Sine and cosine for the generated code: within one unit in the last
//! place of exact, several angles side by side, in a third to a half of the
//! platform's time per angle (three quarters for one angle alone; `cargo
//! bench --bench trig`).
//!
//! Every model `lagrangian!` derives calls [`sin_cos_array`] (or
//! [`sin_cos`] for a single angle) for the trigonometry a user wrote in `T`,
//! `V` and the other sections: one call for all the angles known at that
//! point of a generated function. For `f64` they evaluate an inline kernel
//! (`kernel.rs`) on all the angles at once, lane by lane, without a branch,
//! so that the compiler runs two (SSE2) or four (AVX) lanes per
//! instruction: the argument reduced
//! by `π/2` in two parts, with its rounding error carried as a tail, then the
//! minimax polynomials of fdlibm's `__kernel_sin` and `__kernel_cos`, and the
//! quadrant chosen without a branch. Arguments whose reduction would lose
//! accuracy, `|x| ≥ 10⁵` or within `2⁻¹⁶ |x|` of a nonzero multiple of `π/2`,
//! and NaN and the infinities, take the platform's `sin_cos`: the kernel
//! never answers where it cannot be accurate.
//!
//! Why not the platform's own: a `sincos` from libm is an opaque call with
//! branches on the argument's size, made once per angle on every evaluation
//! of `M` and `f`. For a small model those calls are most of the time
//! (`BENCHMARKS.md`, "Against SymPy → C": the two `sincos` calls alone take
//! 18.6 of the 2-link chain's 21.2 ns in C); inlined, the kernel's
//! arithmetic overlaps the model's own.
//!
//! Accuracy (`tests.rs`, against a double-double reference): below one unit
//! in the last place over `|x| < 10⁵`, the multiples of `π/2` and the
//! points near them included (0.77 at worst over 1.6 million points, `cargo
//! test -p lagrange-runtime --lib trig -- --nocapture`); `sin(−0) = −0`;
//! NaN for NaN and ±∞. A lane's value depends on its own argument alone,
//! not on the others computed with it.
//! Built for a CPU with fused multiply-add (`-C target-cpu=native`), the
//! polynomials use it and the last bit may differ from the default build.
//!
//! An `f32` takes the same kernel, computed in `f64` and rounded once to
//! `f32` (within half a unit in the last place of `f32`, but for a double
//! rounding in rare ties). SIMD lanes of `f64` or `f32` (nalgebra's
//! `SimdRealField`, what an [`Ensemble`](crate::ensemble) evaluates) take
//! it lane by lane, each lane's value the one its scalar would get. Other
//! scalars (dual numbers, any other `RealField` or `SimdRealField`) go to
//! their own `simd_sin_cos`: the choice is made at compile time, by type.
//!
//! ```
//! let (s, c) = lagrange_runtime::trig::sin_cos(0.5_f64);
//! let (s0, c0) = 0.5_f64.sin_cos();
//! assert!((s - s0).abs() <= f64::EPSILON * s0 && (c - c0).abs() <= f64::EPSILON * c0);
//! assert_eq!(lagrange_runtime::trig::sin(-0.0_f64).to_bits(), (-0.0_f64).to_bits());
//! ```

mod kernel;
#[cfg(test)]
mod tests;

use core::any::TypeId;
use nalgebra::{RealField, SimdComplexField, SimdRealField};
use simba::scalar::SupersetOf;

/// Whether the kernel answers for `S`: lanes (one or more) of `f64` or
/// `f32`. An `f32` is computed in `f64` and rounded once: the same value
/// alone or in a lane.
#[inline(always)]
fn by_kernel<S: SimdRealField>() -> bool
where
    S::Element: RealField,
{
    let element = TypeId::of::<S::Element>();
    element == TypeId::of::<f64>() || element == TypeId::of::<f32>()
}

/// `(sin x, cos x)`; for `f64` and `f32` by the inline kernel (module
/// docs): the one-lane [`sin_cos_array`].
#[inline(always)]
pub fn sin_cos<S: SimdRealField + Copy>(x: S) -> (S, S)
where
    S::Element: RealField + Copy,
{
    let ([s], [c]) = sin_cos_array([x]);
    (s, c)
}

/// `(sin xᵢ, cos xᵢ)` of several angles at once: for `f64` and `f32` the
/// kernel on all lanes together, which the compiler vectorizes (two or
/// four lanes to an instruction). The generated code calls it with every
/// angle whose sine and cosine it needs, where they are all known. For
/// SIMD lanes of them (`f64x4`, …, what an [`Ensemble`](crate::ensemble)
/// evaluates), the kernel runs on four lanes at a time, every lane of
/// every angle: each lane's value is the one its scalar would get.
#[inline(always)]
pub fn sin_cos_array<S: SimdRealField + Copy, const K: usize>(x: [S; K]) -> ([S; K], [S; K])
where
    S::Element: RealField + Copy,
{
    // Decided per type at compile time: `TypeId`s of known types are
    // constants, and for `f64` both conversions are the identity.
    if !by_kernel::<S>() {
        let sc = x.map(SimdComplexField::simd_sin_cos);
        return (sc.map(|(s, _)| s), sc.map(|(_, c)| c));
    }
    let wide = |v: S::Element| -> f64 { v.to_subset_unchecked() };
    let narrow = |v: f64| -> S::Element { S::Element::from_subset(&v) };
    if S::LANES == 1 {
        let (s, c) = kernel::sin_cos_many::<kernel::Native, K>(x.map(|x| wide(x.extract(0))));
        return (
            s.map(|s| S::splat(narrow(s))),
            c.map(|c| S::splat(narrow(c))),
        );
    }
    // Every (angle, lane) in turn, four to a pass of the kernel; the last
    // pass filled out with zeros.
    let (mut sin, mut cos) = (x, x);
    let total = K * S::LANES;
    for start in (0..total).step_by(LANE_PASS) {
        let at = |j: usize| ((start + j) / S::LANES, (start + j) % S::LANES);
        let args: [f64; LANE_PASS] = core::array::from_fn(|j| {
            let (k, lane) = at(j);
            if start + j < total {
                wide(x[k].extract(lane))
            } else {
                0.0
            }
        });
        let (s, c) = kernel::sin_cos_many::<kernel::Native, LANE_PASS>(args);
        for j in 0..LANE_PASS.min(total - start) {
            let (k, lane) = at(j);
            sin[k].replace(lane, narrow(s[j]));
            cos[k].replace(lane, narrow(c[j]));
        }
    }
    (sin, cos)
}

/// Lanes of SIMD values per pass of the kernel: four `f64`, one AVX
/// register.
const LANE_PASS: usize = 4;

/// `sin x`; for `f64` and `f32` the sine of [`sin_cos`], the cosine's
/// arithmetic left out by the optimizer.
#[inline(always)]
pub fn sin<S: SimdRealField + Copy>(x: S) -> S
where
    S::Element: RealField + Copy,
{
    if by_kernel::<S>() {
        return sin_cos(x).0;
    }
    x.simd_sin()
}

/// `cos x`; for `f64` and `f32` the cosine of [`sin_cos`].
#[inline(always)]
pub fn cos<S: SimdRealField + Copy>(x: S) -> S
where
    S::Element: RealField + Copy,
{
    if by_kernel::<S>() {
        return sin_cos(x).1;
    }
    x.simd_cos()
}
