//! The pendulum chain in the indexed language: `N` links written once. The
//! closed form of its `M` and `f` is in `tests/models/indexed_models.rs`;
//! `lagrange-studies/examples/chain.rs` writes an 8-link one with wind and a damper.

use crate::lagrangian;

lagrangian! {
    /// A chain of N point masses on massless rods, angles from the downward
    /// vertical.
    pub struct Chain {
        const N = 5;
        coordinates: theta[N];
        parameters: m[N], l[N];
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
    }
}
