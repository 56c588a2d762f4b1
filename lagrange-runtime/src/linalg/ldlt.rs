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

use nalgebra::{RealField, SMatrix, SVector};

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
    #[inline]
    pub(crate) fn new(m: &SMatrix<S, N, N>) -> Option<Self> {
        let mut l = SMatrix::<S, N, N>::zeros();
        let mut d = SVector::<S, N>::zeros();
        let mut inverse_d = SVector::<S, N>::zeros();
        for j in 0..N {
            // w[k] = L_jk d_k, reused by every row below.
            let mut w = SVector::<S, N>::zeros();
            let mut pivot = m[(j, j)];
            for k in 0..j {
                w[k] = l[(j, k)] * d[k];
                pivot -= l[(j, k)] * w[k];
            }
            // Not `pivot <= 0`: a NaN pivot is refused too.
            if pivot.partial_cmp(&S::zero()) != Some(core::cmp::Ordering::Greater) {
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
    /// constrained solve's Schur complement.
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
        let (l, inverse_d) = (&self.l, &self.inverse_d);
        let mut x = *b;
        for i in 0..N {
            let mut s = x[i];
            for k in 0..i {
                s -= l[(i, k)] * x[k];
            }
            x[i] = s;
        }
        for i in (0..N).rev() {
            let mut s = x[i] * inverse_d[i];
            for k in i + 1..N {
                s -= l[(k, i)] * x[k];
            }
            x[i] = s;
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Matrix2, SMatrix, SVector, Vector2};

    use super::Ldlt;

    /// SplitMix64 in [-1, 1): the same matrices on every run.
    fn uniform(state: &mut u64) -> f64 {
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
