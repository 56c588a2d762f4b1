//! A branched tree of links in relative angles, as a robot's hinges or
//! MuJoCo's are written: the model on which `lagrangian!` finds the masses
//! hanging on a tree of increments and the runtime solves `M q̈ = f` in
//! `O(N)` without forming `M` (`lagrange::linalg::articulated`).

use crate::lagrangian;

lagrangian! {
    /// Two branches of five links (point masses `m` at the ends of massless
    /// rods `l`), every angle relative to the link it hangs from: branch
    /// `a` (`phi`) from the origin, branch `b` (`psi`) from the end of
    /// `a`'s first link; gravity `g` along `−y`. Ten coordinates, the
    /// angles of the links as sums of the hinges before them. The form is
    /// asked for (`#[lagrange(articulated)]`), so that `M` and `f` too are
    /// formed from the parts, as they are unasked from 18 coordinates.
    #[lagrange(articulated)]
    pub struct Tree {
        const B = 5;
        coordinates: phi[B], psi[B];
        parameters: m, l, g;
        let ta[i in 0..B] = sum(j in 0..=i, phi[j]);
        let tb[i in 0..B] = ta[0] + sum(j in 0..=i, psi[j]);
        let xa[i in 0..B] = l*sum(j in 0..=i, sin(ta[j]));
        let ya[i in 0..B] = -l*sum(j in 0..=i, cos(ta[j]));
        let xb[i in 0..B] = xa[0] + l*sum(j in 0..=i, sin(tb[j]));
        let yb[i in 0..B] = ya[0] - l*sum(j in 0..=i, cos(tb[j]));
        kinetic: m/2*sum(i in 0..B, dot(xa[i])^2 + dot(ya[i])^2 + dot(xb[i])^2 + dot(yb[i])^2);
        potential: m*g*sum(i in 0..B, ya[i] + yb[i]);
    }
}

impl Tree<f64> {
    /// Unit masses and rods, `g = 9.81`.
    pub fn unit() -> Self {
        Self::new(1.0, 1.0, 9.81)
    }
}
