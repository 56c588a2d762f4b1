//! Where a linearized motion turns stable or unstable: the eigenvalues of a
//! state matrix, its largest growth rate, and the parameter (a speed) where
//! that rate changes sign. Shared by `tests/trajectories/bicycle.rs` and the
//! `bicycle` example (which includes this file by path).

use lagrange::nalgebra::{DMatrix, Matrix4};

/// The eigenvalues of `a` as `(re, im)`, sorted by real part, then
/// imaginary part.
pub fn eigenvalues(a: &Matrix4<f64>) -> Vec<(f64, f64)> {
    let mut e: Vec<(f64, f64)> = DMatrix::from_iterator(4, 4, a.iter().copied())
        .complex_eigenvalues()
        .iter()
        .map(|l| (l.re, l.im))
        .collect();
    e.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    e
}

/// The largest real part among the eigenvalues of `a`.
pub fn growth(a: &Matrix4<f64>) -> f64 {
    eigenvalues(a)
        .iter()
        .map(|e| e.0)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The point in `lo..hi` where `f` changes sign (once), by 60 bisections:
/// to the last bits of an interval of order 1.
pub fn crossing(mut lo: f64, mut hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    let below = f(lo) > 0.0;
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if (f(mid) > 0.0) == below {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
