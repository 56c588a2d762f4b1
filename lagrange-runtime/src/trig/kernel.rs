//! The `f64` kernel: reduction by `π/2`, fdlibm's polynomials, the quadrant,
//! on `K` lanes at once.
//!
//! The constants and both polynomial kernels are fdlibm's (`k_sin.c`,
//! `k_cos.c`, `e_rem_pio2.c`, as musl carries them): `sin` on
//! `[−π/4, π/4]` to degree 13, `cos` to degree 14, each within `2⁻⁵⁸` of
//! the function, evaluated on the reduced argument `r + t` (head and tail).
//! They are written as fdlibm writes them in hex, bit for bit.
//!
//! Every step is written over all lanes ([`Lanes`]) with no branch, so that
//! the compiler vectorizes it; a lane the kernel cannot take is redone by
//! the platform's `sin_cos` out of line, after.

use core::ops::{Add, Mul, Sub};

/// How a polynomial step `a · b + c` is rounded: once where the target has
/// fused multiply-add in hardware, else as written. The tests run both.
pub(crate) trait MulAdd {
    fn mul_add(a: f64, b: f64, c: f64) -> f64;
}

/// `a * b + c`, two roundings (with hardware FMA: only the tests use it).
#[cfg_attr(target_feature = "fma", allow(dead_code))]
pub(crate) struct Plain;
/// `a.mul_add(b, c)`, one rounding (a software call without hardware FMA:
/// only the tests use it there).
#[cfg_attr(not(target_feature = "fma"), allow(dead_code))]
pub(crate) struct Fused;

impl MulAdd for Plain {
    #[inline(always)]
    fn mul_add(a: f64, b: f64, c: f64) -> f64 {
        a * b + c
    }
}

impl MulAdd for Fused {
    #[inline(always)]
    fn mul_add(a: f64, b: f64, c: f64) -> f64 {
        a.mul_add(b, c)
    }
}

/// What the build uses.
#[cfg(target_feature = "fma")]
pub(crate) type Native = Fused;
/// What the build uses.
#[cfg(not(target_feature = "fma"))]
pub(crate) type Native = Plain;

/// `2/π`, rounded.
const INV_PIO2: f64 = core::f64::consts::FRAC_2_PI;
/// The first 33 bits of `π/2`: `n · PIO2_HI` is exact for `|n| < 2²⁰`.
const PIO2_HI: f64 = f64::from_bits(0x3FF921FB_54400000);
/// `π/2 − PIO2_HI`, rounded.
const PIO2_LO: f64 = f64::from_bits(0x3DD0B461_1A626331);
/// `1.5 · 2⁵²`: adding it rounds to an integer, kept in the low bits.
const TO_INT: f64 = 1.5 / f64::EPSILON;
/// Beyond this the two-part reduction loses bits: the platform's.
const LARGE: f64 = 1.0e5;
/// A reduced argument this much smaller than `|x|` lost bits to
/// cancellation (fdlibm's test, an exponent drop of 16): the platform's.
const CANCELLED: f64 = 1.0 / 65536.0;

const S1: f64 = f64::from_bits(0xBFC55555_55555549);
const S2: f64 = f64::from_bits(0x3F811111_1110F8A6);
const S3: f64 = f64::from_bits(0xBF2A01A0_19C161D5);
const S4: f64 = f64::from_bits(0x3EC71DE3_57B1FE7D);
const S5: f64 = f64::from_bits(0xBE5AE5E6_8A2B9CEB);
const S6: f64 = f64::from_bits(0x3DE5D93A_5ACFD57C);

const C1: f64 = f64::from_bits(0x3FA55555_5555554C);
const C2: f64 = f64::from_bits(0xBF56C16C_16C15177);
const C3: f64 = f64::from_bits(0x3EFA01A0_19CB1590);
const C4: f64 = f64::from_bits(0xBE927E4F_809C52AD);
const C5: f64 = f64::from_bits(0x3E21EE9E_BDB4B1C4);
const C6: f64 = f64::from_bits(0xBDA8FAE9_BE8838D4);

/// `K` values, operated on lane by lane.
#[derive(Clone, Copy)]
struct Lanes<const K: usize>([f64; K]);

impl<const K: usize> Lanes<K> {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        Lanes([v; K])
    }

    #[inline(always)]
    fn mul_add<A: MulAdd>(self, b: Self, c: Self) -> Self {
        Lanes(core::array::from_fn(|i| {
            A::mul_add(self.0[i], b.0[i], c.0[i])
        }))
    }
}

macro_rules! lanewise {
    ($trait:ident, $method:ident, $op:tt) => {
        impl<const K: usize> $trait for Lanes<K> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, o: Self) -> Self {
                Lanes(core::array::from_fn(|i| self.0[i] $op o.0[i]))
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);
lanewise!(Mul, mul, *);

/// Whether the kernel can take `x`, given its reduced argument's head `r`:
/// not for NaN, ±∞, `|x| ≥ 10⁵`, or a reduction that cancelled.
#[inline(always)]
fn takes(x: f64, r: f64) -> bool {
    let ax = x.abs();
    // `ax < LARGE` is also false for NaN.
    ax < LARGE && r.abs() >= ax * CANCELLED
}

/// The most lanes the kernel takes in one pass. Beyond, the compiler stops
/// unrolling the lanes and passes of [`PASS`] lanes are faster per angle
/// (the rows for 20, 21 and 30 angles of `cargo bench -p lagrange-studies --bench trig`).
const ONE_PASS: usize = 20;
/// The lanes of each pass beyond [`ONE_PASS`].
const PASS: usize = 8;

/// `(sin xᵢ, cos xᵢ)` of any number of angles: in one pass up to
/// [`ONE_PASS`], else in passes of [`PASS`] lanes (the last one padded with
/// zeros).
#[inline(always)]
pub(crate) fn sin_cos_many<A: MulAdd, const K: usize>(x: [f64; K]) -> ([f64; K], [f64; K]) {
    if K <= ONE_PASS {
        return sin_cos_lanes::<A, K>(x);
    }
    let (mut sin, mut cos) = ([0.0; K], [0.0; K]);
    for start in (0..K).step_by(PASS) {
        let pass: [f64; PASS] = core::array::from_fn(|i| x.get(start + i).copied().unwrap_or(0.0));
        let (s, c) = sin_cos_lanes::<A, PASS>(pass);
        let n = PASS.min(K - start);
        sin[start..start + n].copy_from_slice(&s[..n]);
        cos[start..start + n].copy_from_slice(&c[..n]);
    }
    (sin, cos)
}

/// `(sin xᵢ, cos xᵢ)` of each lane.
#[inline(always)]
pub(crate) fn sin_cos_lanes<A: MulAdd, const K: usize>(x: [f64; K]) -> ([f64; K], [f64; K]) {
    let c = Lanes::<K>::splat;
    let xs = Lanes(x);
    // x = n π/2 + (r + t), |r| ≤ π/4 (a little more near the ends).
    let shifted = xs * c(INV_PIO2) + c(TO_INT);
    let fnn = shifted - c(TO_INT);
    let head = xs - fnn * c(PIO2_HI);
    let w = fnn * c(PIO2_LO);
    let r = head - w;
    let t = (head - r) - w;
    // One flag for all lanes, or'ed without short-circuit: a branch per
    // lane would stop the vectorizer.
    let declined = x
        .iter()
        .zip(&r.0)
        .fold(false, |declined, (&x, &r)| declined | !takes(x, r));
    let z = r * r;
    let z2 = z * z;
    // sin(r + t), fdlibm's __kernel_sin with a tail.
    let ps = (z * z2).mul_add::<A>(
        z.mul_add::<A>(c(S6), c(S5)),
        z.mul_add::<A>(z.mul_add::<A>(c(S4), c(S3)), c(S2)),
    );
    let v = z * r;
    let s = r - ((z * (c(0.5) * t - v * ps) - t) - v * c(S1));
    // cos(r + t), fdlibm's __kernel_cos with a tail.
    let pc = (z2 * z2).mul_add::<A>(
        z.mul_add::<A>(z.mul_add::<A>(c(C6), c(C5)), c(C4)),
        z * z.mul_add::<A>(z.mul_add::<A>(c(C3), c(C2)), c(C1)),
    );
    let hz = c(0.5) * z;
    let one_hz = c(1.0) - hz;
    let co = one_hz + (((c(1.0) - one_hz) - hz) + (z * pc - r * t));
    // Quadrant n mod 4 (the low bits of `shifted`): odd swaps sine and
    // cosine; the sine is negated in quadrants 2 and 3, the cosine in 1 and
    // 2. Masks and sign flips, no branch (a data-dependent `if` compiles to
    // a jump, mispredicted about as often as angles change quadrant).
    let mut sin = [0.0; K];
    let mut cos = [0.0; K];
    for i in 0..K {
        let n = shifted.0[i].to_bits();
        let (s, c) = (s.0[i].to_bits(), co.0[i].to_bits());
        let swap = (n & 1).wrapping_neg();
        let a = (s & !swap) | (c & swap);
        let b = (c & !swap) | (s & swap);
        sin[i] = f64::from_bits(a ^ ((n & 2) << 62));
        cos[i] = f64::from_bits(b ^ ((n.wrapping_add(1) & 2) << 62));
    }
    if declined {
        platform(x, r.0, &mut sin, &mut cos);
    }
    (sin, cos)
}

/// The platform's `sin_cos` for the lanes the kernel declined, out of line:
/// the hot path keeps its registers, since the call is rare. Each lane's
/// value depends on its own argument alone.
#[cold]
#[inline(never)]
fn platform<const K: usize>(x: [f64; K], r: [f64; K], sin: &mut [f64; K], cos: &mut [f64; K]) {
    for (i, (&x, &r)) in x.iter().zip(&r).enumerate() {
        if !takes(x, r) {
            (sin[i], cos[i]) = x.sin_cos();
        }
    }
}
