//! `M = L D Lᵀ` on the stack, for the mass matrix of every right-hand side.
//!
//! The square-root-free form of Cholesky (`L` unit lower triangular, `D`
//! diagonal, the pivots), written out rather than nalgebra's `Cholesky`
//! because this is the hot path of every integrator and each stage waits
//! for it: for the small `N` of most models, the generic factorization's
//! call, copies, square roots and divisions took longer than the model's
//! own `M` and `f` (`BENCHMARKS.md`, "What an adaptive step adds"). Here it
//! is inlined, takes no square root, and divides once per column: the
//! reciprocal of each pivot is kept, and the solve multiplies by it.
//! Without pivoting it is as backward stable as Cholesky on the symmetric
//! positive definite matrices it accepts (Higham, *Accuracy and Stability
//! of Numerical Algorithms*, §10.1); the pivots `dⱼ` are Cholesky's `Lⱼⱼ²`.

use nalgebra::{RealField, SMatrix, SVector, SimdRealField};

/// From this many coordinates on, `L D Lᵀ` is factored (and `L z = b`
/// solved) column by column; below it, row by row. Measured on the 2-core
/// development machine, old and new builds in interleaved rounds:
/// `solve_mass_matrix` alone took 1.1× to 1.5× longer by columns at 5 to
/// 12 coordinates and about the same at 16 and 24 (three rounds); from 32
/// on, the column form's time over the row form's was 0.90 at 40 and 0.88
/// at 64 (medians of six rounds), and one RK4 step of the 64-link chain
/// 0.79 (five rounds; `cargo bench -p lagrange-studies --bench mujoco --
/// --lagrange OTHER_CHECKOUT` builds the chain against either tree).
pub(crate) const BY_COLUMNS: usize = 32;

/// Entries of a column the column form keeps in registers at once (four
/// SSE2 registers of two `f64`).
const BLOCK: usize = 8;

/// `L` (unit lower triangular, its strict lower part stored), the pivots
/// `D` and their reciprocals, of a symmetric positive definite `M`.
#[derive(Clone, Copy)]
pub(crate) struct Ldlt<S: RealField + Copy, const N: usize> {
    l: SMatrix<S, N, N>,
    d: SVector<S, N>,
    inverse_d: SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Ldlt<S, N> {
    /// Factors `M`, reading its lower triangle; `None` where a pivot is not
    /// positive (or NaN): `M` is not numerically positive definite.
    ///
    /// Two orders of the same arithmetic, chosen by size. Below
    /// [`BY_COLUMNS`] coordinates, row by row: each entry of `L` is `M`'s
    /// minus a dot product with the row of `w = L_jk dₖ`, which the
    /// compiler unrolls into straight-line code at these sizes. From
    /// [`BY_COLUMNS`] on, column by column: each column `j` made from `M`'s
    /// by one update per column `k < j` before it,
    /// `L[j.., j] −= L[j.., k] wₖ`, [`BLOCK`] entries at a time held in
    /// registers across all those updates; the entries of a block are
    /// independent and contiguous, so the updates pipeline and vectorize
    /// where the dot products wait on each subtraction and stride across
    /// columns. Every entry subtracts its terms in the order
    /// `k = 0, 1, …, j − 1` either way, so both give the same bits
    /// (`same_bits_as_the_dot_product_form`).
    #[inline]
    pub(crate) fn new(m: &SMatrix<S, N, N>) -> Option<Self> {
        if N >= BY_COLUMNS {
            Self::by_columns(m)
        } else {
            Self::by_rows(m)
        }
    }

    #[inline]
    fn by_rows(m: &SMatrix<S, N, N>) -> Option<Self> {
        // Not `pivot <= 0`: a NaN pivot is refused too.
        let refused =
            |pivot: S| pivot.partial_cmp(&S::zero()) != Some(core::cmp::Ordering::Greater);
        let (l, d, inverse_d) = factor_rows(m, refused)?;
        Some(Self { l, d, inverse_d })
    }

    #[inline]
    fn by_columns(m: &SMatrix<S, N, N>) -> Option<Self> {
        let mut l = *m;
        let mut d = SVector::<S, N>::zeros();
        let mut inverse_d = SVector::<S, N>::zeros();
        if !factor_in_place(&mut l, &mut d, &mut inverse_d) {
            return None;
        }
        // Zeros on and above the diagonal, as the row form leaves them
        // (never read).
        for (j, column) in l.as_mut_slice().chunks_exact_mut(N).enumerate() {
            column[..=j].fill(S::zero());
        }
        Some(Self { l, d, inverse_d })
    }

    /// The smallest and the largest pivot, `(min dⱼ, max dⱼ)`: what the
    /// conditioning is judged on (`(0, 0)` for `N = 0`).
    #[inline]
    pub(crate) fn pivot_range(&self) -> (S, S) {
        match N {
            0 => (S::zero(), S::zero()),
            _ => (self.d.min(), self.d.max()),
        }
    }

    /// Cholesky's factor `L √D` (zeros above the diagonal), for the
    /// normal modes' eigenproblem (`analysis/modes.rs`).
    pub(crate) fn cholesky_factor(&self) -> SMatrix<S, N, N> {
        SMatrix::from_fn(|i, j| match i.cmp(&j) {
            core::cmp::Ordering::Less => S::zero(),
            core::cmp::Ordering::Equal => self.d[j].sqrt(),
            core::cmp::Ordering::Greater => self.l[(i, j)] * self.d[j].sqrt(),
        })
    }

    /// `M⁻¹ b`: `L z = b`, then `Lᵀ x = D⁻¹ z`.
    #[inline]
    pub(crate) fn solve(&self, b: &SVector<S, N>) -> SVector<S, N> {
        let mut x = *b;
        self.forward(&mut x);
        self.backward(&mut x);
        x
    }

    /// The pivots `D`.
    pub(crate) fn pivots(&self) -> &SVector<S, N> {
        &self.d
    }

    /// Their reciprocals, `D⁻¹`'s diagonal.
    pub(crate) fn inverse_pivots(&self) -> &SVector<S, N> {
        &self.inverse_d
    }

    /// `x ← L⁻¹ x`: row by row below [`BY_COLUMNS`] coordinates, by
    /// columns from there (once `z_k` is known, it leaves every row below,
    /// `x[k+1..] −= L[k+1.., k] z_k`, a contiguous column). Each row
    /// subtracts its terms in the order `k = 0, 1, …` either way.
    #[inline]
    pub(crate) fn forward(&self, x: &mut SVector<S, N>) {
        forward(&self.l, x);
    }

    /// `x ← L⁻ᵀ D⁻¹ x`, row by row from the last: row `i` of `Lᵀ` is
    /// column `i` of `L`, contiguous at any size.
    #[inline]
    pub(crate) fn backward(&self, x: &mut SVector<S, N>) {
        backward(&self.l, &self.inverse_d, x);
    }
}

/// The row form of [`Ldlt::new`]: `L` (its strict lower triangle), the
/// pivots and their reciprocals, for scalars or SIMD lanes of them; `None`
/// as soon as `refused` refuses a pivot. The scalar factorization refuses
/// a pivot that is not positive; lanes refuse none, and their caller
/// judges each lane's pivots after (an [`Ensemble`](crate::ensemble)):
/// the same arithmetic, so each lane's factor is its scalar's.
#[inline]
#[allow(clippy::type_complexity)]
pub(crate) fn factor_rows<S: SimdRealField + Copy, const N: usize>(
    m: &SMatrix<S, N, N>,
    mut refused: impl FnMut(S) -> bool,
) -> Option<(SMatrix<S, N, N>, SVector<S, N>, SVector<S, N>)> {
    let (mut l, mut d) = (zeros::<S, N, N>(), zeros::<S, N, 1>());
    let mut inverse_d = d;
    for j in 0..N {
        // w[k] = L_jk d_k, reused by every row below.
        let mut w = zeros::<S, N, 1>();
        let mut pivot = m[(j, j)];
        for k in 0..j {
            w[k] = l[(j, k)] * d[k];
            pivot -= l[(j, k)] * w[k];
        }
        if refused(pivot) {
            return None;
        }
        let inverse = S::one() / pivot;
        d[j] = pivot;
        inverse_d[j] = inverse;
        for i in j + 1..N {
            let mut s = m[(i, j)];
            for k in 0..j {
                s -= l[(i, k)] * w[k];
            }
            l[(i, j)] = s * inverse;
        }
    }
    Some((l, d, inverse_d))
}

/// A matrix of zeros written in place: nalgebra's `zeros` goes through an
/// iterator, which the optimizer reduces to stores for `f64` but not for
/// SIMD lanes, where it took as long as the factorization.
#[inline(always)]
pub(crate) fn zeros<S: SimdRealField + Copy, const R: usize, const C: usize>() -> SMatrix<S, R, C> {
    SMatrix::from_array_storage(nalgebra::ArrayStorage([[S::zero(); R]; C]))
}

/// The column form of [`Ldlt::new`] on `M` in place: the strict lower
/// triangle of `l` becomes `L`'s, `d` and `inverse_d` the pivots and their
/// reciprocals; `false` where a pivot is not positive (or NaN). The
/// diagonal and the upper triangle of `l` are left as they are on the way
/// (never read). The hot path of a large model factors the `M` its model
/// returned this way ([`solve_mass_matrix_in_place`](super::mass::solve_mass_matrix_in_place)),
/// where a copy of it and of its factor (32 kB each at 64 coordinates)
/// cost a few percent of a right-hand side.
#[inline]
pub(crate) fn factor_in_place<S: RealField + Copy, const N: usize>(
    l: &mut SMatrix<S, N, N>,
    d: &mut SVector<S, N>,
    inverse_d: &mut SVector<S, N>,
) -> bool {
    // The lower triangle of `M`, overwritten column by column.
    // w[k] = L_jk d_k for the column being made.
    let mut w = [S::zero(); N];
    for j in 0..N {
        let (done, rest) = l.as_mut_slice().split_at_mut(j * N);
        for (k, earlier) in done.chunks_exact(N).enumerate() {
            w[k] = earlier[j] * d[k];
        }
        let w = &w[..j];
        // Blocks of the column held in registers while every earlier
        // column updates them: each entry is loaded and stored once,
        // not once per column before it, and still subtracts its terms
        // in the order k = 0, 1, …, j − 1.
        let column = &mut rest[j..N];
        let mut blocks = column.chunks_exact_mut(BLOCK);
        for (b, block) in blocks.by_ref().enumerate() {
            let from = j + b * BLOCK;
            let mut sum: [S; BLOCK] = core::array::from_fn(|i| block[i]);
            for (earlier, &w_k) in done.chunks_exact(N).zip(w) {
                let earlier = &earlier[from..from + BLOCK];
                for (entry, &l_ik) in sum.iter_mut().zip(earlier) {
                    *entry -= l_ik * w_k;
                }
            }
            block.copy_from_slice(&sum);
        }
        let tail = blocks.into_remainder();
        let from = N - tail.len();
        for (earlier, &w_k) in done.chunks_exact(N).zip(w) {
            for (entry, &l_ik) in tail.iter_mut().zip(&earlier[from..]) {
                *entry -= l_ik * w_k;
            }
        }
        let pivot = rest[j];
        // Not `pivot <= 0`: a NaN pivot is refused too.
        if pivot.partial_cmp(&S::zero()) != Some(core::cmp::Ordering::Greater) {
            return false;
        }
        let inverse = S::one() / pivot;
        d[j] = pivot;
        inverse_d[j] = inverse;
        for entry in &mut rest[j + 1..N] {
            *entry *= inverse;
        }
    }
    true
}

/// `x ← L⁻¹ x` with the strict lower triangle of `l` (see [`Ldlt::forward`]).
#[inline]
pub(crate) fn forward<S: SimdRealField + Copy, const N: usize>(
    l: &SMatrix<S, N, N>,
    x: &mut SVector<S, N>,
) {
    if N < BY_COLUMNS {
        for i in 0..N {
            let mut s = x[i];
            for k in 0..i {
                s -= l[(i, k)] * x[k];
            }
            x[i] = s;
        }
        return;
    }
    for (k, column) in l.as_slice().chunks_exact(N.max(1)).take(N).enumerate() {
        let (known, below) = x.as_mut_slice().split_at_mut(k + 1);
        let z = known[k];
        for (entry, &l_ik) in below.iter_mut().zip(&column[k + 1..]) {
            *entry -= l_ik * z;
        }
    }
}

/// `x ← L⁻ᵀ D⁻¹ x` with the strict lower triangle of `l` and `D⁻¹`'s
/// diagonal (see [`Ldlt::backward`]).
#[inline]
pub(crate) fn backward<S: SimdRealField + Copy, const N: usize>(
    l: &SMatrix<S, N, N>,
    inverse_d: &SVector<S, N>,
    x: &mut SVector<S, N>,
) {
    for i in (0..N).rev() {
        let mut s = x[i] * inverse_d[i];
        for k in i + 1..N {
            s -= l[(k, i)] * x[k];
        }
        x[i] = s;
    }
}

#[cfg(test)]
pub(in crate::linalg) mod tests {
    use nalgebra::{Matrix2, SMatrix, SVector, Vector2};

    use super::Ldlt;

    /// SplitMix64 in [-1, 1): the same matrices on every run (the
    /// Schur complement's tests draw theirs from it too).
    pub(in crate::linalg) fn uniform(state: &mut u64) -> f64 {
        *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        2.0 * ((z >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }

    /// `A Aᵀ + N I` for a random `A`: symmetric positive definite, with a
    /// condition number of a few tens.
    fn spd<const N: usize>(state: &mut u64) -> SMatrix<f64, N, N> {
        let a = SMatrix::<f64, N, N>::from_fn(|_, _| uniform(state));
        a * a.transpose() + SMatrix::identity() * N as f64
    }

    fn agrees_with_nalgebra<const N: usize>(seed: u64) {
        let mut state = seed;
        for _ in 0..200 {
            let m = spd::<N>(&mut state);
            let b = SVector::<f64, N>::from_fn(|_, _| uniform(&mut state));
            let ldlt = Ldlt::new(&m).expect("positive definite");
            let chol = m.cholesky().expect("positive definite");
            // Both backward stable: the solutions differ by about
            // cond(M) ε |x| (cond < 100 here), the factors by a few ε |L|.
            let (x, x0) = (ldlt.solve(&b), chol.solve(&b));
            assert!((x - x0).amax() <= 1e-13 * x0.amax(), "N = {N}: {x} vs {x0}");
            let (l, l0) = (ldlt.cholesky_factor(), chol.l());
            assert!((l - l0).amax() <= 1e-14 * l0.amax(), "N = {N}: {l} vs {l0}");
            // The residual of the solve itself.
            assert!((m * x - b).amax() <= 1e-14 * m.amax() * x.amax().max(1.0));
            let (small, large) = ldlt.pivot_range();
            let pivots = l0.diagonal().map(|l| l * l);
            assert!((small - pivots.min()).abs() <= 1e-14 * pivots.max());
            assert!((large - pivots.max()).abs() <= 1e-14 * pivots.max());
        }
    }

    #[test]
    fn factors_and_solves_as_nalgebras_cholesky_does() {
        agrees_with_nalgebra::<1>(1);
        agrees_with_nalgebra::<2>(2);
        agrees_with_nalgebra::<3>(3);
        agrees_with_nalgebra::<6>(6);
        agrees_with_nalgebra::<10>(10);
    }

    /// The row (dot-product) form the factorization was first written in,
    /// kept apart from the code under test: both forms, on either side of
    /// `BY_COLUMNS`, must give its bits, so that no method's results move.
    fn dot_product_form<const N: usize>(
        m: &SMatrix<f64, N, N>,
        b: &SVector<f64, N>,
    ) -> (SMatrix<f64, N, N>, SVector<f64, N>, SVector<f64, N>) {
        let mut l = SMatrix::<f64, N, N>::zeros();
        let mut d = SVector::<f64, N>::zeros();
        for j in 0..N {
            let mut w = SVector::<f64, N>::zeros();
            let mut pivot = m[(j, j)];
            for k in 0..j {
                w[k] = l[(j, k)] * d[k];
                pivot -= l[(j, k)] * w[k];
            }
            let inverse = 1.0 / pivot;
            d[j] = pivot;
            for i in j + 1..N {
                let mut s = m[(i, j)];
                for k in 0..j {
                    s -= l[(i, k)] * w[k];
                }
                l[(i, j)] = s * inverse;
            }
        }
        let mut x = *b;
        for i in 0..N {
            let mut s = x[i];
            for k in 0..i {
                s -= l[(i, k)] * x[k];
            }
            x[i] = s;
        }
        for i in (0..N).rev() {
            let mut s = x[i] * (1.0 / d[i]);
            for k in i + 1..N {
                s -= l[(k, i)] * x[k];
            }
            x[i] = s;
        }
        (l, d, x)
    }

    fn same_bits<const N: usize>(seed: u64) {
        let mut state = seed;
        for _ in 0..50 {
            let m = spd::<N>(&mut state);
            let b = SVector::<f64, N>::from_fn(|_, _| uniform(&mut state));
            let ldlt = Ldlt::new(&m).expect("positive definite");
            let (l, d, x) = dot_product_form(&m, &b);
            // Zeros on and above the diagonal, as the dot-product form left them.
            assert_eq!(ldlt.l.as_slice(), l.as_slice(), "N = {N}: L");
            assert_eq!(ldlt.d.as_slice(), d.as_slice(), "N = {N}: D");
            assert_eq!(ldlt.solve(&b).as_slice(), x.as_slice(), "N = {N}: x");
        }
    }

    #[test]
    fn same_bits_as_the_dot_product_form() {
        same_bits::<1>(11);
        same_bits::<2>(12);
        same_bits::<5>(15);
        same_bits::<13>(23);
        same_bits::<{ super::BY_COLUMNS }>(32);
        same_bits::<40>(50);
        same_bits::<67>(77);
    }

    #[test]
    fn refuses_what_is_not_positive_definite() {
        for m in [
            Matrix2::new(1.0, 0.0, 0.0, 0.0),
            Matrix2::new(1.0, 0.0, 0.0, -1.0),
            Matrix2::new(0.0, 1.0, 1.0, 0.0),
            Matrix2::new(1.0, 2.0, 2.0, 1.0),
            Matrix2::new(f64::NAN, 0.0, 0.0, 1.0),
            Matrix2::new(1.0, 0.0, 0.0, f64::NAN),
        ] {
            assert!(Ldlt::new(&m).is_none(), "{m}");
        }
        // The upper triangle is not read.
        let m = Matrix2::new(4.0, f64::NAN, 2.0, 3.0);
        let x = Ldlt::new(&m).unwrap().solve(&Vector2::new(6.0, 5.0));
        assert!((x - Vector2::new(1.0, 1.0)).amax() < 1e-15, "{x}");
    }
}
