//! The kernel against a double-double reference, in units in the last place,
//! both roundings of its polynomials (`Plain`, `Fused`) whatever the target.

use super::kernel::{self, Fused, MulAdd, Plain};

/// A double-double `hi + lo`, about 106 bits.
#[derive(Clone, Copy)]
struct Dd(f64, f64);

fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    Dd(s, (a - (s - bb)) + (b - bb))
}

fn add(a: Dd, b: Dd) -> Dd {
    let s = two_sum(a.0, b.0);
    let t = two_sum(s.1, a.1 + b.1);
    let u = two_sum(s.0, t.0);
    two_sum(u.0, u.1 + t.1)
}

fn mul(a: Dd, b: Dd) -> Dd {
    let p = a.0 * b.0;
    // The exact error of the product: fma, software or not, is exact.
    let e = a.0.mul_add(b.0, -p);
    two_sum(p, e + a.0 * b.1 + a.1 * b.0)
}

fn scale(a: Dd, k: f64) -> Dd {
    mul(a, Dd(k, 0.0))
}

/// `π/2` as four 33-bit pieces (fdlibm's `pio2_1`, `pio2_2`, `pio2_3` and
/// the rest): `n ·` each is exact for `|n| < 2²⁰`, so `x − n π/2` is good to
/// about 2⁻¹²⁰ of `|x|`, far beyond what an `f64` reduction keeps.
const PIO2: [f64; 4] = [
    f64::from_bits(0x3FF921FB_54400000),
    f64::from_bits(0x3DD0B461_1A600000),
    f64::from_bits(0x3BA3198A_2E000000),
    f64::from_bits(0x397B839A_252049C1),
];

/// `(sin x, cos x)` to about 100 bits, for `|x| < 10⁵`, by Taylor series of
/// the argument reduced in double-double.
fn reference(x: f64) -> (Dd, Dd) {
    let n = (x * (2.0 / core::f64::consts::PI)).round();
    let mut r = Dd(x, 0.0);
    for p in PIO2 {
        r = add(r, Dd(-n * p, 0.0));
    }
    // Taylor series of sin and cos at |r| ≤ 0.8: the 30th term is below
    // 10⁻³⁵.
    let r2 = mul(r, r);
    let (mut s, mut c) = (r, Dd(1.0, 0.0));
    let (mut ts, mut tc) = (r, Dd(1.0, 0.0));
    for k in 1..16 {
        let k = k as f64;
        ts = scale(mul(ts, r2), -1.0 / ((2.0 * k) * (2.0 * k + 1.0)));
        tc = scale(mul(tc, r2), -1.0 / ((2.0 * k - 1.0) * (2.0 * k)));
        s = add(s, ts);
        c = add(c, tc);
    }
    let neg = |a: Dd| Dd(-a.0, -a.1);
    match (n as i64).rem_euclid(4) {
        0 => (s, c),
        1 => (c, neg(s)),
        2 => (neg(s), neg(c)),
        _ => (neg(c), s),
    }
}

/// The error of `a` against the exact `b`, in units in the last place of
/// `b`'s rounding: 0.5 is the best an `f64` can do, and under 1 means `a` is
/// one of the two `f64`s next to the exact value.
fn ulps(a: f64, b: Dd) -> f64 {
    let r = b.0 + b.1;
    let e = (r.abs().to_bits() >> 52) as i64;
    let ulp = if e <= 52 {
        f64::from_bits(1)
    } else {
        f64::from_bits(((e - 52) as u64) << 52)
    };
    ((a - b.0) - b.1).abs() / ulp
}

/// SplitMix64, seeded: the same points on every run.
fn points(seed: u64, count: usize, scale: f64) -> impl Iterator<Item = f64> {
    let mut state = seed;
    (0..count).map(move |_| {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        let u = (z >> 11) as f64 / (1u64 << 53) as f64;
        (2.0 * u - 1.0) * scale
    })
}

/// The worst error of the kernel with rounding `A` over `xs`, in ulps, and
/// where.
fn worst<A: MulAdd>(xs: impl Iterator<Item = f64>) -> (f64, f64) {
    let mut worst = (0.0, 0.0);
    for x in xs {
        let ([s], [c]) = kernel::sin_cos_lanes::<A, 1>([x]);
        let (s0, c0) = reference(x);
        let e = ulps(s, s0).max(ulps(c, c0));
        if e > worst.0 {
            worst = (e, x);
        }
    }
    worst
}

#[test]
fn reference_agrees_with_the_platform_to_an_ulp() {
    // The reference is only as good as its code: checked against the
    // platform's sin_cos first (glibc's is within one ulp).
    for x in points(1, 20_000, 100.0) {
        let (s, c) = x.sin_cos();
        let (s0, c0) = reference(x);
        assert!(ulps(s, s0) < 1.0 && ulps(c, c0) < 1.0, "x = {x:e}");
    }
}

#[test]
fn kernel_is_within_one_ulp_of_the_reference() {
    // fdlibm's kernels are documented below one ulp; the reduction's tail
    // keeps them there. 200,000 points per range and rounding.
    for (seed, scale) in [(2, 0.8), (3, 4.0), (4, 100.0), (5, 1.0e5)] {
        let (e, x) = worst::<Plain>(points(seed, 200_000, scale));
        println!("|x| < {scale:e}: plain worst {e:.3} ulp at x = {x:e}");
        assert!(e < 1.0, "plain: {e} ulp at x = {x:e}");
        let (e, x) = worst::<Fused>(points(seed, 200_000, scale));
        println!("|x| < {scale:e}: fused worst {e:.3} ulp at x = {x:e}");
        assert!(e < 1.0, "fused: {e} ulp at x = {x:e}");
    }
}

#[test]
fn kernel_is_accurate_at_and_near_multiples_of_half_pi() {
    // Where sin or cos is near zero the reduced argument is small and
    // cancellation is the danger: the kernel must hand these to the
    // platform or get them right itself.
    let mut xs = Vec::new();
    for k in -2000..=2000 {
        let x = k as f64 * core::f64::consts::FRAC_PI_2;
        let mut y = x;
        for _ in 0..40 {
            xs.push(y);
            y = f64::from_bits(y.to_bits() + 1);
        }
        xs.extend((1..40).map(|i| x + i as f64 * 1e-3 * x.abs().max(1.0)));
    }
    let (e, x) = worst::<Plain>(xs.iter().copied());
    assert!(e < 1.0, "plain: {e} ulp at x = {x:e}");
    let (e, x) = worst::<Fused>(xs.iter().copied());
    assert!(e < 1.0, "fused: {e} ulp at x = {x:e}");
}

#[test]
fn special_values_are_those_of_the_platform() {
    let s = |x: f64| {
        let ([s], [c]) = kernel::sin_cos_lanes::<Plain, 1>([x]);
        (s, c)
    };
    assert_eq!(s(0.0).0.to_bits(), 0.0f64.to_bits());
    assert_eq!(s(-0.0).0.to_bits(), (-0.0f64).to_bits());
    assert_eq!(s(0.0).1, 1.0);
    assert_eq!(s(-0.0).1, 1.0);
    let tiny = f64::from_bits(1);
    assert_eq!(s(tiny), (tiny, 1.0));
    assert_eq!(s(-tiny), (-tiny, 1.0));
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let (a, b) = s(x);
        assert!(a.is_nan() && b.is_nan(), "x = {x}");
    }
    // Beyond the kernel's range: the platform's values exactly.
    for x in [1.0e5, -1.0e5, 3.0e7, 1.0e300, f64::MAX] {
        assert_eq!(s(x), x.sin_cos(), "x = {x:e}");
    }
}

#[test]
fn generic_entry_points_dispatch_by_type() {
    // f64 takes the kernel, f32 the kernel's f64 values rounded once.
    let x = 0.7_f64;
    let ([s], [c]) = kernel::sin_cos_lanes::<kernel::Native, 1>([x]);
    assert_eq!(super::sin_cos(x), (s, c));
    assert_eq!(super::sin(x), super::sin_cos(x).0);
    assert_eq!(super::cos(x), super::sin_cos(x).1);
    let y = 0.7_f32;
    let ([s], [c]) = kernel::sin_cos_lanes::<kernel::Native, 1>([f64::from(y)]);
    assert_eq!(super::sin_cos(y), (s as f32, c as f32));
    assert_eq!(super::sin(y), s as f32);
    assert_eq!(super::cos(y), c as f32);
}

/// Asserts that each lane of a `K`-lane call is the one-lane call's value,
/// to the bit.
fn lanes_match_single_calls<const K: usize>(x: [f64; K]) {
    let (s, c) = kernel::sin_cos_many::<Plain, K>(x);
    for i in 0..K {
        let ([s1], [c1]) = kernel::sin_cos_lanes::<Plain, 1>([x[i]]);
        assert_eq!(s[i].to_bits(), s1.to_bits(), "sin, lane {i} of {x:?}");
        assert_eq!(c[i].to_bits(), c1.to_bits(), "cos, lane {i} of {x:?}");
    }
}

#[test]
fn each_lane_is_its_own_single_call_even_beside_a_declined_lane() {
    // Lanes share instructions, not values: a lane's result is the
    // one-lane kernel's to the bit, whether or not a neighbour (NaN, huge,
    // a multiple of π/2) went to the platform.
    let xs: Vec<f64> = points(6, 63, 10.0).collect();
    let declined = [f64::NAN, 3.0e7, core::f64::consts::PI, f64::INFINITY];
    for (k, chunk) in xs.chunks_exact(7).enumerate() {
        let mut x = [0.0; 8];
        x[..7].copy_from_slice(chunk);
        x[7] = declined[k % declined.len()];
        lanes_match_single_calls::<7>(x[..7].try_into().expect("7 lanes"));
        lanes_match_single_calls::<8>(x);
        lanes_match_single_calls::<2>([x[0], x[7]]);
    }
    // Beyond one pass (passes of 8 lanes, the last one padded).
    let mut x = [0.0; 29];
    for (x, p) in x.iter_mut().zip(points(7, 29, 50.0)) {
        *x = p;
    }
    x[17] = f64::NAN;
    lanes_match_single_calls::<29>(x);
    // And through the generic entry point, for f64 and f32.
    let x = [0.3, -2.0, 1.0e6];
    let (s, c) = super::sin_cos_array(x);
    for i in 0..3 {
        assert_eq!((s[i], c[i]), super::sin_cos(x[i]));
    }
    let y = [0.3_f32, -2.0, 1.0e6];
    let (s, c) = super::sin_cos_array(y);
    for i in 0..3 {
        assert_eq!((s[i], c[i]), y[i].sin_cos());
    }
}

/// SIMD lanes of `f64` and `f32` (what an ensemble evaluates) take the
/// kernel lane by lane: every lane's bits are its scalar's, for any number
/// of angles (a pass of the kernel spans angles), the arguments the kernel
/// leaves to the platform included; an `f32` is the `f64` value rounded.
#[test]
fn lanes_take_their_scalars_values() {
    use simba::simd::{AutoF32x8, AutoF64x2, AutoF64x4};

    let args = [
        0.3,
        -0.0,
        1e6,
        f64::NAN,
        -2.5,
        f64::INFINITY,
        core::f64::consts::FRAC_PI_2,
        7.0,
    ];
    let bits64 = f64::to_bits;
    let bits32 = |x: f32| u64::from(x.to_bits());
    fn check<V: nalgebra::SimdRealField + Copy, const K: usize>(
        args: &[f64; 8],
        bits: impl Fn(V::Element) -> u64,
    ) where
        V::Element: nalgebra::RealField + Copy,
    {
        // Angle k, lane i: args[(k * 3 + i) % 8].
        let x: [V; K] = core::array::from_fn(|k| {
            let mut v = V::splat(nalgebra::convert(args[0]));
            for i in 0..V::LANES {
                v.replace(i, nalgebra::convert(args[(k * 3 + i) % 8]));
            }
            v
        });
        let (s, c) = super::sin_cos_array(x);
        for k in 0..K {
            for i in 0..V::LANES {
                let (s0, c0) = super::sin_cos(x[k].extract(i));
                assert_eq!(bits(s[k].extract(i)), bits(s0), "sin, angle {k}, lane {i}");
                assert_eq!(bits(c[k].extract(i)), bits(c0), "cos, angle {k}, lane {i}");
            }
        }
    }
    check::<AutoF64x4, 3>(&args, bits64);
    check::<AutoF64x2, 1>(&args, bits64);
    check::<AutoF64x2, 5>(&args, bits64);
    check::<AutoF32x8, 2>(&args, bits32);
    // f32 lanes and scalars: the f64 value rounded once.
    for &x in &args {
        let (s, c) = super::sin_cos(x as f32);
        let (s64, c64) = super::sin_cos(f64::from(x as f32));
        assert_eq!(
            (s.to_bits(), c.to_bits()),
            ((s64 as f32).to_bits(), (c64 as f32).to_bits())
        );
    }
}
