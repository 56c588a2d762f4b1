//! What the model tests share: seeded random states, closed forms
//! written as lists of terms, and a comparison scaled to those terms.
use lagrange::Lagrangian;
use lagrange::nalgebra::{SMatrix, SVector};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::f64::consts::PI;

/// Random states per test: enough to visit every sign and quadrant, few
/// enough that the whole run stays well under a second.
pub const SAMPLES: usize = 200;

/// Relative tolerance for an `f64` model against its hand-derived closed
/// form. Either side is a few dozen flops and a handful of `sin`/`cos`, each
/// good to an ulp, so their round-off is ~1e-14 of the largest term; 1e-10
/// leaves four orders of margin. A wrong, missing or mis-signed term moves
/// the result by the size of that term, which at random states is a sizable
/// fraction of the scale, far above 1e-10 of it.
pub const TOL: f64 = 1e-10;

/// A seeded generator, so that a failure reproduces.
pub fn rng(seed: u64) -> StdRng {
    StdRng::seed_from_u64(seed)
}

/// A uniform sample in `[lo, hi)`.
pub fn uniform(rng: &mut StdRng, lo: f64, hi: f64) -> f64 {
    rng.gen_range(lo..hi)
}

/// An angle anywhere on the circle.
pub fn angle(rng: &mut StdRng) -> f64 {
    rng.gen_range(-PI..PI)
}

/// A generalized velocity or acceleration of either sign.
pub fn rate(rng: &mut StdRng) -> f64 {
    rng.gen_range(-3.0..3.0)
}

/// A positive physical parameter (mass, length, stiffness...) of order one.
pub fn positive(rng: &mut StdRng) -> f64 {
    rng.gen_range(0.5..2.0)
}

/// Gravity, near Earth's.
pub fn gravity(rng: &mut StdRng) -> f64 {
    rng.gen_range(9.0..10.0)
}

/// A time far enough from zero that `cos(ω t)`, `sin(ω t)` take every phase.
pub fn time(rng: &mut StdRng) -> f64 {
    rng.gen_range(-10.0..10.0)
}

/// A closed-form quantity written as its terms: its value is their sum, and
/// the sum of their magnitudes is the scale its round-off is relative to.
#[derive(Clone, Copy, Debug)]
pub struct Closed {
    pub value: f64,
    pub scale: f64,
}

impl Closed {
    pub fn sum(terms: &[f64]) -> Self {
        Closed {
            value: terms.iter().sum(),
            scale: terms.iter().map(|x| x.abs()).sum(),
        }
    }
}

/// `|got − want| ≤ tol · max(1, |want|, Σ|terms|)`: relative to the size of
/// the terms, absolute (`tol`) for quantities that are small or cancel to 0.
#[track_caller]
pub fn assert_close_tol(what: &str, got: f64, want: Closed, tol: f64) {
    let bound = tol * want.value.abs().max(want.scale).max(1.0);
    assert!(
        (got - want.value).abs() <= bound,
        "{what}: derived {got:e}, closed form {:e} (difference {:e}, allowed {bound:e})",
        want.value,
        (got - want.value).abs(),
    );
}

#[track_caller]
pub fn assert_close(what: &str, got: f64, want: Closed) {
    assert_close_tol(what, got, want, TOL);
}

/// Entry by entry, `M` against its closed form.
#[track_caller]
pub fn assert_matrix_close<const N: usize>(
    what: &str,
    got: &SMatrix<f64, N, N>,
    want: &[[Closed; N]; N],
) {
    for i in 0..N {
        for j in 0..N {
            assert_close(&format!("{what}[{i},{j}]"), got[(i, j)], want[i][j]);
        }
    }
}

/// Component by component, a vector against its closed form.
#[track_caller]
pub fn assert_vector_close<const N: usize>(what: &str, got: &SVector<f64, N>, want: &[Closed; N]) {
    for i in 0..N {
        assert_close(&format!("{what}[{i}]"), got[i], want[i]);
    }
}

/// `M q̈ − f` as the model computes it: the left-hand side of the equation
/// of motion with everything moved to one side, at an arbitrary `q̈`.
pub fn residual<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    model: &L,
    t: f64,
    q: &SVector<f64, N>,
    qdot: &SVector<f64, N>,
    qddot: &SVector<f64, N>,
) -> SVector<f64, N> {
    model.mass_matrix(t, q) * qddot - model.forcing(t, q, qdot)
}

/// `mass_matrix_and_forcing` computes `M` and `f` in one pass over shared
/// subexpressions; it must give exactly what the two separate calls give,
/// bit for bit, at any state.
#[track_caller]
pub fn assert_combined_call_is_bitwise_separate<L, const N: usize>(model: &L, seed: u64)
where
    L: Lagrangian<N, Scalar = f64>,
{
    let mut rng = rng(seed);
    for _ in 0..SAMPLES {
        let t = time(&mut rng);
        let q = SVector::<f64, N>::from_fn(|_, _| uniform(&mut rng, -3.0, 3.0));
        let qdot = SVector::<f64, N>::from_fn(|_, _| rate(&mut rng));
        let (m, f) = model.mass_matrix_and_forcing(t, &q, &qdot);
        let (m_alone, f_alone) = (model.mass_matrix(t, &q), model.forcing(t, &q, &qdot));
        let bits = |xs: &[f64]| xs.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(
            bits(m.as_slice()),
            bits(m_alone.as_slice()),
            "M differs at t = {t}, q = {q:?}: {m} vs {m_alone}"
        );
        assert_eq!(
            bits(f.as_slice()),
            bits(f_alone.as_slice()),
            "f differs at t = {t}, q = {q:?}, q̇ = {qdot:?}: {f} vs {f_alone}"
        );
    }
}
