//! `M q̈ = f` solved in `O(N)` without forming `M`, for a model whose
//! masses hang on a tree of increments: what `lagrangian!` finds in a chain
//! or a tree of links written as positions summed along the links before
//! (in absolute or in relative angles), and calls through
//! [`Lagrangian::accelerations`](crate::model::Lagrangian::accelerations).
//!
//! The form, which the engine proves of the model's `T` before it emits the
//! call: `N` joints, joint `j` an angle `φ_j` (a coordinate, or another
//! joint's angle plus a coordinate, `φ_j = φ_base(j) + c_j q_σ(j)`), and
//! each joint an increment `r_j(φ_j)` in `D` axes added to its parent's
//! end, so that the end of joint `j` moves with
//! `v_j = v_parent(j) + u_j φ̇_j`, `u_j = r_j'(φ_j)`; then
//!
//! ```text
//! T = ½ Σ_j Σ_a m_ja v_ja² + ½ Σ_j J_j φ̇_j²
//! ```
//!
//! with `m_ja` the mass at the end of joint `j` along axis `a` and `J_j`
//! an inertia of the joint itself. The generalized forces `f_other` (the
//! potential's, the forces', the dissipation's) come in the coordinates
//! `q`. The articulated-body recursion (Featherstone's, for point masses):
//! leaves to root, each joint's subtree reduced to an inertia `I` (`D × D`)
//! and a bias force `b` as seen from its parent's end; root to leaves, the
//! joints' accelerations. About `10 D²` operations a joint.
//!
//! `None` where a joint's articulated inertia `u·I u + J` is not positive
//! or the result is not finite: the caller then solves `M q̈ = f` whole,
//! which tells a singular `M` from a non-finite forcing in its errors.
//! Written once for scalars and for SIMD lanes ([`lanes`], which says per
//! lane whether it answered): the same operations in the same order, so
//! that a lane of an [`Ensemble`](crate::ensemble::Ensemble) is its scalar
//! run, bit for bit.
//!
//! Where a method needs `M` or `f` themselves (that dense solve, the
//! variational integrators, the sensitivities), [`mass_matrix`] and
//! [`forcing`] form them from the same parts, in `O(N²)` and `O(N)`: a
//! model with the form from 18 coordinates (or at any size under
//! `#[lagrange(articulated)]`) has no generated code for `M`'s entries, so
//! its build is that of the parts alone; below, the generated `M` and `f`
//! are faster and stay.

use nalgebra::{RealField, SMatrix, SVector, SimdRealField};

/// No joint: a root's parent, an angle that is a coordinate alone.
pub const NONE: usize = usize::MAX;

/// The joints of a model, in an order where each joint's parent and base
/// come before it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tree<const N: usize> {
    /// Each joint's parent in the tree of increments, or [`NONE`].
    pub parent: [usize; N],
    /// The joint whose angle each joint's adds to, or [`NONE`].
    pub base: [usize; N],
    /// The coordinate each joint's angle adds, `σ(j)`: every coordinate
    /// once.
    pub coordinate: [usize; N],
    /// Its factor, `c_j`, never zero.
    pub scale: [f64; N],
}

/// What the model computes at a state for [`accelerations`]: the joints'
/// axes, bends, masses, inertias, and the generalized forces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parts<S, const N: usize, const D: usize> {
    /// `u_j = ∂r_j/∂φ_j`.
    pub axes: [[S; D]; N],
    /// `∂²r_j/∂φ_j²`: the end's acceleration at `φ̈ = 0` is `bend φ̇_j²`.
    pub bends: [[S; D]; N],
    /// The mass at the end of each joint, along each axis.
    pub masses: [[S; D]; N],
    /// `J_j`: the kinetic energy's `½ J_j φ̇_j²`.
    pub inertia: [S; N],
    /// The generalized forces other than the kinetic energy's, in the
    /// coordinates `q`: `−∂V/∂q + Q − ∂R/∂q̇`.
    pub forcing: SVector<S, N>,
}

/// `q̈` from `M q̈ = f` by the articulated-body recursion; `None` where a
/// joint's articulated inertia is not positive or the result is not
/// finite (the caller then solves with `M`).
#[inline]
pub fn accelerations<S: RealField + Copy, const N: usize, const D: usize>(
    tree: &Tree<N>,
    parts: &Parts<S, N, D>,
    qdot: &SVector<S, N>,
) -> Option<SVector<S, N>> {
    let (qddot, answered) = lanes(tree, parts, qdot);
    answered.then_some(qddot)
}

/// [`accelerations`] on SIMD lanes (or a scalar, one lane): `q̈` of every
/// lane, and which lanes it answers for (each as [`accelerations`] would
/// for that lane alone, with the same bits); the others' values are
/// meaningless.
#[inline]
#[allow(clippy::needless_range_loop)] // (a, b) index D × D inertias: the clearest form
pub fn lanes<S: SimdRealField + Copy, const N: usize, const D: usize>(
    tree: &Tree<N>,
    parts: &Parts<S, N, D>,
    qdot: &SVector<S, N>,
) -> (SVector<S, N>, S::SimdBool) {
    // A factor of 1 (every angle of a chain or a tree of hinges) costs
    // nothing; another one divides once.
    let over = |x: S, j: usize| match tree.scale[j] {
        1.0 => x,
        c => x / nalgebra::convert::<f64, S>(c),
    };
    let zero = S::zero();
    let dot = |a: &[S; D], b: &[S; D]| {
        let mut sum = a[0] * b[0];
        for k in 1..D {
            sum += a[k] * b[k];
        }
        sum
    };
    // `I x` for a symmetric `I` stored whole.
    let apply = |i: &[[S; D]; D], x: &[S; D]| core::array::from_fn(|a| dot(&i[a], x));
    // The joints' rates, `φ̇ = A q̇`, and their forces, `τ = A⁻ᵀ f`.
    let rate = rates(tree, qdot);
    let mut tau = [zero; N];
    for j in 0..N {
        tau[j] = over(parts.forcing[tree.coordinate[j]], j);
    }
    for j in (0..N).rev() {
        let base = tree.base[j];
        if base != NONE {
            tau[base] -= over(parts.forcing[tree.coordinate[j]], j);
        }
    }
    // Leaves to root: each subtree's articulated inertia and bias force,
    // accumulated into its parent's; one division a joint.
    let mut inertia = [[[zero; D]; D]; N];
    let mut force = [[zero; D]; N];
    let mut bias = [[zero; D]; N];
    let mut pull = [[zero; D]; N];
    let mut free = [zero; N];
    let mut positive = zero.simd_eq(zero);
    for j in (0..N).rev() {
        let mut i = inertia[j];
        for a in 0..D {
            i[a][a] += parts.masses[j][a];
        }
        let u = &parts.axes[j];
        let squared = rate[j] * rate[j];
        let w: [S; D] = core::array::from_fn(|a| parts.bends[j][a] * squared);
        let h = apply(&i, u);
        let d = dot(u, &h) + parts.inertia[j];
        // Not positive, or NaN: the dense solve's to judge, for this lane.
        positive = positive & d.simd_gt(zero);
        let iw = apply(&i, &w);
        let z: [S; D] = core::array::from_fn(|a| iw[a] + force[j][a]);
        let e = tau[j] - dot(u, &z);
        let hd: [S; D] = core::array::from_fn(|a| h[a] / d);
        let ed = e / d;
        let parent = tree.parent[j];
        if parent != NONE {
            for a in 0..D {
                for b in 0..D {
                    inertia[parent][a][b] += i[a][b] - hd[a] * h[b];
                }
                force[parent][a] += z[a] + h[a] * ed;
            }
        }
        (bias[j], pull[j], free[j]) = (w, hd, ed);
    }
    // Root to leaves: each joint's acceleration, then its end's.
    let mut end = [[zero; D]; N];
    let mut angle = [zero; N];
    for j in 0..N {
        let parent = tree.parent[j];
        let from = if parent == NONE {
            [zero; D]
        } else {
            end[parent]
        };
        angle[j] = free[j] - dot(&pull[j], &from);
        end[j] = core::array::from_fn(|a| from[a] + parts.axes[j][a] * angle[j] + bias[j][a]);
    }
    // `q̈ = A⁻¹ φ̈`.
    let mut qddot = SVector::<S, N>::zeros();
    for j in 0..N {
        let base = tree.base[j];
        let relative = if base == NONE {
            angle[j]
        } else {
            angle[j] - angle[base]
        };
        qddot[tree.coordinate[j]] = over(relative, j);
    }
    let finite = super::finite_lanes(&[qddot.as_slice()]);
    (qddot, positive & finite)
}

/// `M` of the form in the coordinates `q`, formed from the parts in
/// `O(N²)`: what a model with the form returns as its `mass_matrix` (for
/// the dense solve where the recursion declines, the variational
/// integrators, the sensitivities), instead of generated code for every
/// entry.
///
/// In the joints' angles, `M_φ[i][j] = Σ_a u_ia u_ja C_ia` for `j` on
/// `i`'s path (and its mirror), `C_ia` the masses of `i`'s subtree along
/// axis `a`, plus `J_i` on the diagonal; then `M = Aᵀ M_φ A`.
#[inline]
#[allow(clippy::needless_range_loop)] // joints and axes index several arrays at once
pub fn mass_matrix<S: SimdRealField + Copy, const N: usize, const D: usize>(
    tree: &Tree<N>,
    parts: &Parts<S, N, D>,
) -> SMatrix<S, N, N> {
    let zero = S::zero();
    // Each joint's subtree's masses, axis by axis.
    let mut held = parts.masses;
    for j in (0..N).rev() {
        let parent = tree.parent[j];
        if parent != NONE {
            for a in 0..D {
                held[parent][a] += held[j][a];
            }
        }
    }
    let mut m = SMatrix::<S, N, N>::zeros();
    for i in 0..N {
        let mut j = i;
        while j != NONE {
            let mut entry = zero;
            for a in 0..D {
                entry += parts.axes[i][a] * parts.axes[j][a] * held[i][a];
            }
            if j == i {
                m[(i, i)] = entry + parts.inertia[i];
            } else {
                m[(i, j)] = entry;
                m[(j, i)] = entry;
            }
            j = tree.parent[j];
        }
    }
    to_coordinates(tree, m)
}

/// `f` of the form in the coordinates `q`, from the parts in `O(N)`: the
/// generalized forces other than `T`'s less `T`'s velocity terms, what a
/// model with the form returns as its `forcing`.
///
/// In the joints' angles `T`'s terms are `b_i = Σ_a u_ia Σ_{n in i's
/// subtree} m_na c_na`, `c_n` the end of joint `n`'s acceleration at
/// `φ̈ = 0` (its bends times the rates squared, summed along its path); in
/// `q`, `f = f_other − Aᵀ b`.
#[inline]
#[allow(clippy::needless_range_loop)] // joints and axes index several arrays at once
pub fn forcing<S: SimdRealField + Copy, const N: usize, const D: usize>(
    tree: &Tree<N>,
    parts: &Parts<S, N, D>,
    qdot: &SVector<S, N>,
) -> SVector<S, N> {
    let zero = S::zero();
    let rate = rates(tree, qdot);
    // Root to leaves: each end's acceleration at φ̈ = 0, times its masses.
    let mut end = [[zero; D]; N];
    let mut pulled = [[zero; D]; N];
    for j in 0..N {
        let parent = tree.parent[j];
        let squared = rate[j] * rate[j];
        for a in 0..D {
            let from = if parent == NONE { zero } else { end[parent][a] };
            end[j][a] = from + parts.bends[j][a] * squared;
            pulled[j][a] = parts.masses[j][a] * end[j][a];
        }
    }
    // Leaves to root: each subtree's pull, projected on its joint's axis.
    let mut b = [zero; N];
    for j in (0..N).rev() {
        let parent = tree.parent[j];
        let mut along = zero;
        for a in 0..D {
            along += parts.axes[j][a] * pulled[j][a];
            if parent != NONE {
                pulled[parent][a] += pulled[j][a];
            }
        }
        b[j] = along;
    }
    // `Aᵀ b`: each joint's term to the coordinates its angle holds.
    for j in (0..N).rev() {
        let base = tree.base[j];
        if base != NONE {
            b[base] += b[j];
        }
    }
    let mut f = parts.forcing;
    for j in 0..N {
        f[tree.coordinate[j]] -= scaled(tree, b[j], j);
    }
    f
}

/// [`mass_matrix`] and [`forcing`] together.
#[inline]
pub fn mass_matrix_and_forcing<S: SimdRealField + Copy, const N: usize, const D: usize>(
    tree: &Tree<N>,
    parts: &Parts<S, N, D>,
    qdot: &SVector<S, N>,
) -> (SMatrix<S, N, N>, SVector<S, N>) {
    (mass_matrix(tree, parts), forcing(tree, parts, qdot))
}

/// The joints' rates `φ̇ = A q̇`.
#[inline(always)]
fn rates<S: SimdRealField + Copy, const N: usize>(tree: &Tree<N>, qdot: &SVector<S, N>) -> [S; N] {
    let mut rate = [S::zero(); N];
    for j in 0..N {
        let (base, i) = (tree.base[j], tree.coordinate[j]);
        let own = scaled(tree, qdot[i], j);
        rate[j] = if base == NONE { own } else { rate[base] + own };
    }
    rate
}

/// `c_j x`: a factor of 1 (every angle of a chain or a tree of hinges)
/// costs nothing.
#[inline(always)]
fn scaled<S: SimdRealField + Copy, const N: usize>(tree: &Tree<N>, x: S, j: usize) -> S {
    match tree.scale[j] {
        1.0 => x,
        c => x * nalgebra::convert::<f64, S>(c),
    }
}

/// `Aᵀ X A` for `X` in the joints' angles: row `j` of `A` is its base's
/// plus `c_j` at its coordinate, so `X A`'s column `σ(k)` is `c_k` times
/// the sum of `X`'s columns over the joints whose angles hold joint `k`'s
/// (leaves to root, each into its base), and `Aᵀ` the same on the rows.
/// Nothing to do for absolute angles in the coordinates' order (`A = I`,
/// every chain written so).
fn to_coordinates<S: SimdRealField + Copy, const N: usize>(
    tree: &Tree<N>,
    mut x: SMatrix<S, N, N>,
) -> SMatrix<S, N, N> {
    for j in (0..N).rev() {
        let base = tree.base[j];
        if base != NONE {
            for r in 0..N {
                let v = x[(r, j)];
                x[(r, base)] += v;
            }
        }
    }
    for j in (0..N).rev() {
        let base = tree.base[j];
        if base != NONE {
            for c in 0..N {
                let v = x[(j, c)];
                x[(base, c)] += v;
            }
        }
    }
    let identity = (0..N).all(|j| tree.coordinate[j] == j && tree.scale[j] == 1.0);
    if identity {
        return x;
    }
    let mut m = SMatrix::<S, N, N>::zeros();
    for j in 0..N {
        for k in 0..N {
            let v = scaled(tree, x[(j, k)], j);
            m[(tree.coordinate[j], tree.coordinate[k])] = scaled(tree, v, k);
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{SMatrix, SVector};

    /// A chain of three links in relative angles, with a branch: joint 2
    /// hangs from joint 0's end; unequal masses per axis and a joint
    /// inertia. At rest, where the velocity terms vanish, against the
    /// dense solve of `M = Σ_n Σ_a m_na (∂v_na/∂q̇)ᵀ(∂v_na/∂q̇) + Aᵀ J A`
    /// written from the same form by hand. (The velocity terms, the bends,
    /// are checked on generated models against their dense `M` and `f`:
    /// `tests/trajectories/articulated.rs`.)
    #[test]
    fn matches_the_dense_solve_at_rest() {
        const N: usize = 3;
        let tree = Tree::<N> {
            parent: [NONE, 0, 0],
            base: [NONE, 0, 0],
            coordinate: [0, 1, 2],
            scale: [1.0, 1.0, -2.0],
        };
        let q: [f64; N] = [0.3, -0.7, 1.1];
        let phi = [q[0], q[0] + q[1], q[0] - 2.0 * q[2]];
        let lengths = [1.0, 0.8, 1.3];
        let axes: [[f64; 2]; N] =
            core::array::from_fn(|j| [lengths[j] * phi[j].cos(), lengths[j] * phi[j].sin()]);
        let masses = [[1.0, 1.5], [2.0, 2.0], [0.5, 0.7]];
        let inertia = [0.0, 0.3, 0.1];
        let forces = SVector::<f64, N>::new(0.4, -1.2, 0.9);
        let parts = Parts {
            axes,
            bends: [[0.0; 2]; N],
            masses,
            inertia,
            forcing: forces,
        };
        // ∂φ/∂q, and the ends' velocities per unit q̇: the Jacobian of the
        // end of joint n along axis a is Σ_{j on n's path} u_ja ∂φ_j/∂q.
        let a = SMatrix::<f64, N, N>::new(1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, -2.0);
        let paths: [&[usize]; N] = [&[0], &[0, 1], &[0, 2]];
        let mut m = SMatrix::<f64, N, N>::zeros();
        for (n, path) in paths.iter().enumerate() {
            for ax in 0..2 {
                let mut row = SVector::<f64, N>::zeros();
                for &j in *path {
                    row += a.row(j).transpose() * axes[j][ax];
                }
                m += row * row.transpose() * masses[n][ax];
            }
        }
        for (j, inertia) in inertia.iter().enumerate() {
            m += a.row(j).transpose() * a.row(j) * *inertia;
        }
        // `M` formed from the parts: the same sums in another order, to a
        // few ε of its largest entry (about 10 here).
        let formed = mass_matrix(&tree, &parts);
        assert!((formed - m).amax() < 1e-14 * m.amax(), "{formed} {m}");
        // At rest `f` is the forces alone.
        assert_eq!(forcing(&tree, &parts, &SVector::zeros()), forces);
        let dense = m.lu().solve(&forces).unwrap();
        let ours = accelerations(&tree, &parts, &SVector::zeros()).unwrap();
        // Both are backward stable solves of a 3 × 3 system with a
        // condition number of a few tens: agreement to 1e-13 relative.
        assert!(
            (ours - dense).amax() < 1e-13 * dense.amax(),
            "{ours} {dense}"
        );
    }

    /// A massless tip makes its joint's articulated inertia zero: the
    /// dense solve's business, not a division by zero.
    #[test]
    fn refuses_a_massless_tip() {
        let tree = Tree::<2> {
            parent: [NONE, 0],
            base: [NONE, NONE],
            coordinate: [0, 1],
            scale: [1.0, 1.0],
        };
        let parts = Parts {
            axes: [[1.0, 0.0], [0.0, 1.0]],
            bends: [[0.0; 2]; 2],
            masses: [[1.0, 1.0], [0.0, 0.0]],
            inertia: [0.0; 2],
            forcing: SVector::<f64, 2>::new(1.0, 1.0),
        };
        assert_eq!(accelerations(&tree, &parts, &SVector::zeros()), None);
    }
}
