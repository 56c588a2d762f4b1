//! Models whose masses hang on a tree of increments: `lagrangian!` finds
//! the form and the runtime solves `M q̈ = f` by the articulated-body
//! recursion, in `O(N)` without `M` (`lagrange::linalg::articulated`), and
//! forms `M` and `f` from the same parts where a method asks for them.
//! Here, on a chain, a tree and a cart under a chain, against the same
//! models with `#[lagrange(articulated = false)]` (`M` and `f` generated
//! from the derivation): that the formed `M` and `f` are the derived ones,
//! that the recursion solves that system, that runs through it follow the
//! dense runs, and that where it cannot answer (a massless link) the dense
//! solve's typed error comes out unchanged.

use lagrange::Lagrangian;
use lagrange::models::Tree;
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;

lagrangian! {
    /// The chain of ten links in absolute angles, masses and lengths as
    /// parameters. The form asked for, so that `M` and `f` are formed from
    /// the parts at ten links too (found unasked, they are from 18).
    #[lagrange(articulated)]
    pub struct Chain10 {
        const N = 10;
        coordinates: theta[N];
        parameters: m[N], l[N];
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
    }
}

lagrangian! {
    /// `Chain10` with `M` and `f` generated from the derivation.
    #[lagrange(articulated = false)]
    pub struct Chain10Derived {
        const N = 10;
        coordinates: theta[N];
        parameters: m[N], l[N];
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
    }
}

lagrangian! {
    /// `lagrange::models::Tree` (its source) with `M` and `f` generated
    /// from the derivation.
    #[lagrange(articulated = false)]
    pub struct TreeDerived {
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

lagrangian! {
    /// A cart along `x` under three rigid links in relative angles: the
    /// cart's joint moves along one axis only. Asked for at four
    /// coordinates, below the size the engine looks for it at unasked.
    #[lagrange(articulated)]
    pub struct CartChain {
        const N = 3;
        coordinates: s, theta[N];
        parameters: cart, m, l, inertia, g;
        let phi[i in 0..N] = sum(j in 0..=i, theta[j]);
        let x[i in 0..N] = s + l*sum(j in 0..=i, sin(phi[j]));
        let y[i in 0..N] = -l*sum(j in 0..=i, cos(phi[j]));
        kinetic: cart/2*dot(s)^2 + sum(i in 0..N, m/2*(dot(x[i])^2 + dot(y[i])^2) + inertia/2*dot(phi[i])^2);
        potential: sum(i in 0..N, m*g*y[i]);
    }
}

lagrangian! {
    /// `CartChain` with `M` and `f` generated from the derivation.
    #[lagrange(articulated = false)]
    pub struct CartChainDerived {
        const N = 3;
        coordinates: s, theta[N];
        parameters: cart, m, l, inertia, g;
        let phi[i in 0..N] = sum(j in 0..=i, theta[j]);
        let x[i in 0..N] = s + l*sum(j in 0..=i, sin(phi[j]));
        let y[i in 0..N] = -l*sum(j in 0..=i, cos(phi[j]));
        kinetic: cart/2*dot(s)^2 + sum(i in 0..N, m/2*(dot(x[i])^2 + dot(y[i])^2) + inertia/2*dot(phi[i])^2);
        potential: sum(i in 0..N, m*g*y[i]);
    }
}

fn cart() -> (CartChain<f64>, CartChainDerived<f64>) {
    let (cart, m, l, inertia, g) = (2.5, 0.8, 0.6, 0.05, 9.81);
    (
        CartChain::new(cart, m, l, inertia, g),
        CartChainDerived::new(cart, m, l, inertia, g),
    )
}

fn masses(last_mass: f64) -> [f64; 10] {
    std::array::from_fn(|i| {
        if i == 9 {
            last_mass
        } else {
            1.0 + 0.1 * i as f64
        }
    })
}

fn lengths() -> [f64; 10] {
    std::array::from_fn(|i| 1.0 - 0.04 * i as f64)
}

fn chain(last_mass: f64) -> Chain10<f64> {
    Chain10::new(masses(last_mass), lengths())
}

fn chain_derived(last_mass: f64) -> Chain10Derived<f64> {
    Chain10Derived::new(masses(last_mass), lengths())
}

fn tree_derived() -> TreeDerived<f64> {
    TreeDerived::new(1.0, 1.0, 9.81)
}

/// A state spread over the circle and over `±3` rad/s, `k` its seed.
fn state<const N: usize>(k: usize) -> (SVector<f64, N>, SVector<f64, N>) {
    let q = SVector::from_fn(|i, _| 3.0 * ((7 * i + 13 * k) as f64 * 0.37).sin());
    let v = SVector::from_fn(|i, _| 3.0 * ((5 * i + 11 * k) as f64 * 0.61).cos());
    (q, v)
}

/// `fast` has the form, `derived` is the same model without it.
fn formed_as_derived<L, D, const N: usize>(fast: &L, derived: &D)
where
    L: Lagrangian<N, Scalar = f64>,
    D: Lagrangian<N, Scalar = f64>,
{
    assert!(L::SOLVES_ACCELERATIONS, "the form was not found");
    assert!(!D::SOLVES_ACCELERATIONS, "the twin has the form");
    for k in 0..200 {
        let (q, v) = state::<N>(k);
        let (m, f) = fast.mass_matrix_and_forcing(0.0, &q, &v);
        let (dm, df) = derived.mass_matrix_and_forcing(0.0, &q, &v);
        assert_eq!(
            (m, f),
            (fast.mass_matrix(0.0, &q), fast.forcing(0.0, &q, &v))
        );
        // Both are sums of the same products in other orders, each rounded
        // once: an entry of `M` sums at most N² products of O(1) factors,
        // one of `f` up to 2 N² terms with the rates squared (up to 9 in the
        // chain, more in the tree, whose angles add)
        // that cancel in part, so its rounding is relative to terms larger
        // than the entry. 16 N ε of the largest entry bounds both (measured
        // 5.1e-16 for `M` and 4.5e-15 for `f` over these states); a wrong
        // term would be of the order of the entries themselves.
        let bound = |x: f64| 16.0 * N as f64 * f64::EPSILON * x;
        assert!(
            (m - dm).amax() <= bound(dm.amax()),
            "state {k}: M differs by {:e} of {:e}",
            (m - dm).amax(),
            dm.amax()
        );
        assert!(
            (f - df).amax() <= bound(df.amax()),
            "state {k}: f differs by {:e} of {:e}",
            (f - df).amax(),
            df.amax()
        );
    }
}

#[test]
fn m_and_f_formed_from_the_parts_are_the_derived_ones() {
    formed_as_derived(&chain(1.9), &chain_derived(1.9));
    formed_as_derived(&Tree::unit(), &tree_derived());
    let (fast, derived) = cart();
    formed_as_derived(&fast, &derived);
}

/// The recursion's `q̈` against `M` and `f` derived (`derived`, the same
/// model without the form).
fn solves_m_qddot_equals_f<L, D, const N: usize>(model: &L, derived: &D)
where
    L: Lagrangian<N, Scalar = f64>,
    D: Lagrangian<N, Scalar = f64>,
{
    assert!(L::SOLVES_ACCELERATIONS, "the form was not found");
    for k in 0..200 {
        let (q, v) = state::<N>(k);
        let a = model
            .accelerations(0.0, &q, &v)
            .expect("the recursion answers")
            .expect("a regular M");
        let (m, f) = derived.mass_matrix_and_forcing(0.0, &q, &v);
        // The recursion's backward error: each acceleration is a sum along
        // the tree of at most N joints' terms of a few operations in two
        // axes, each rounded once; 64 N ε of the sizes in play bounds it
        // (measured at most 4e-16 of them here, well inside).
        let scale = m.abs().row_sum().max() * a.amax() + f.amax();
        let residual = (m * a - f).amax();
        assert!(
            residual <= 64.0 * N as f64 * f64::EPSILON * scale,
            "state {k}: |M q̈ − f| = {residual:e} of {scale:e}"
        );
    }
}

#[test]
fn the_recursion_solves_the_dense_system() {
    solves_m_qddot_equals_f(&chain(1.9), &chain_derived(1.9));
    solves_m_qddot_equals_f(&Tree::unit(), &tree_derived());
    let (fast, derived) = cart();
    solves_m_qddot_equals_f(&fast, &derived);
}

#[test]
fn runs_through_the_recursion_follow_the_dense_runs() {
    // RK4 at h = 1e-3 for 1 s from a start at rest: the two runs differ by
    // the rounding of each q̈ (relative 1e-15, the test above), carried over
    // 1000 steps and grown by the motion; measured at 3e-14 (chain),
    // 1.1e-13 (tree) and 1.5e-15 (cart).
    // 1e-10 leaves room for a platform's rounding while catching any error
    // of the recursion's (a wrong term moves the state by 1e-3 or more).
    fn compare<L, D, const N: usize>(model: &L, derived: &D)
    where
        L: Lagrangian<N, Scalar = f64>,
        D: Lagrangian<N, Scalar = f64>,
    {
        let (qa, va) = end(model);
        let (qd, vd) = end(derived);
        let gap = (qa - qd).amax().max((va - vd).amax());
        assert!(
            gap < 1e-10,
            "the recursion's run is {gap:e} from the dense one"
        );
    }
    /// Where RK4 is after 1 s from `q = (1, 0.3, …)` at rest.
    fn end<L: Lagrangian<N, Scalar = f64>, const N: usize>(
        model: &L,
    ) -> (SVector<f64, N>, SVector<f64, N>) {
        let q0 = SVector::<f64, N>::from_fn(|i, _| if i == 0 { 1.0 } else { 0.3 });
        let run = Rk4::new(1e-3).integrate(model, 0.0, q0, SVector::zeros(), &[1.0]);
        let last = run.expect("the run").last().expect("one sample");
        (last.q, last.qdot)
    }
    compare(&chain(1.9), &chain_derived(1.9));
    compare(&Tree::unit(), &tree_derived());
    let (fast, derived) = cart();
    compare(&fast, &derived);
}

#[test]
fn a_massless_tip_gets_the_dense_solves_error() {
    // The last link's mass zero: its joint's articulated inertia vanishes,
    // the recursion declines, and the dense solve (of `M` formed from the
    // parts) reports the singular `M` at the same t, in the same state, as
    // the derived `M`'s solve does.
    let model = chain(0.0);
    let (q, v) = state::<10>(3);
    assert_eq!(model.accelerations(0.0, &q, &v), None);
    let times = [1.0];
    let ours = Rk4::new(1e-3).integrate(&model, 0.0, q, v, &times);
    let dense = Rk4::new(1e-3).integrate(&chain_derived(0.0), 0.0, q, v, &times);
    let (ours, dense) = (ours.expect_err("singular"), dense.expect_err("singular"));
    assert!(
        matches!(ours.error, IntegrationError::SingularMassMatrix { .. }),
        "{}",
        ours.error
    );
    assert_eq!(ours.error.to_string(), dense.error.to_string());
}

lagrangian! {
    /// The comb: a chain of 20 point masses on rods in relative angles,
    /// with a branch of two links hanging from the end of every fourth link
    /// (5 branches, 30 coordinates). Unasked, the engine finds its tree
    /// before deriving `M` and `f` and never derives them; its dense
    /// derivation is beyond the default budget, and its dense code beyond
    /// the limit on generated code (`lagrange-engine/tests/engine/articulated.rs`).
    pub struct Comb {
        const N = 20;
        const B = 5;
        coordinates: theta[N], psi[2*B];
        parameters: m[N], n[2*B], l;
        constants: g = 9.81;
        let a[i in 0..N] = sum(j in 0..=i, theta[j]);
        let x[i in 0..N] = l*sum(j in 0..=i, sin(a[j]));
        let y[i in 0..N] = -l*sum(j in 0..=i, cos(a[j]));
        let b1[k in 0..B] = a[4*k+3] + psi[2*k];
        let b2[k in 0..B] = b1[k] + psi[2*k+1];
        let u1[k in 0..B] = x[4*k+3] + l*sin(b1[k]);
        let v1[k in 0..B] = y[4*k+3] - l*cos(b1[k]);
        let u2[k in 0..B] = u1[k] + l*sin(b2[k]);
        let v2[k in 0..B] = v1[k] - l*cos(b2[k]);
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2))
            + sum(k in 0..B, n[2*k]/2*(dot(u1[k])^2 + dot(v1[k])^2) + n[2*k+1]/2*(dot(u2[k])^2 + dot(v2[k])^2));
        potential: g*(sum(i in 0..N, m[i]*y[i]) + sum(k in 0..B, n[2*k]*v1[k] + n[2*k+1]*v2[k]));
    }
}

/// The comb's masses and length, uneven so that no two branches are alike.
fn comb() -> Comb<f64> {
    Comb::new(
        std::array::from_fn(|i| 1.0 + 0.05 * i as f64),
        std::array::from_fn(|k| 0.5 + 0.1 * k as f64),
        0.7,
    )
}

/// The comb's `M` and `f` written by hand, independently of the engine:
/// each point mass `p` sits at the end of a path of links, each link at
/// the absolute angle `α = w · q` (`w` its coordinates, each 1), so that
/// `x_p = l Σ sin α`, `y_p = −l Σ cos α`; with `J` the rows `∂x_p/∂q` and
/// `∂y_p/∂q` and `b` their accelerations at `q̈ = 0`,
/// `M = Σ m_p Jᵀ J` and `f = −Σ m_p Jᵀ (b + (0, g))`.
fn comb_by_hand(
    model: &Comb<f64>,
    q: &SVector<f64, 30>,
    v: &SVector<f64, 30>,
) -> (lagrange::nalgebra::SMatrix<f64, 30, 30>, SVector<f64, 30>) {
    let chain = |i: usize| -> Vec<usize> { (0..=i).collect() };
    // Each link's coordinates, and each point's links and mass.
    let mut links: Vec<Vec<usize>> = (0..20).map(chain).collect();
    let mut points: Vec<(Vec<usize>, f64)> =
        (0..20).map(|i| ((0..=i).collect(), model.m[i])).collect();
    for k in 0..5 {
        let at = 4 * k + 3;
        let first = [chain(at), vec![20 + 2 * k]].concat();
        let second = [first.clone(), vec![20 + 2 * k + 1]].concat();
        links.push(first);
        links.push(second);
        let path = [chain(at), vec![20 + 2 * k]].concat();
        points.push((path.clone(), model.n[2 * k]));
        points.push(([path, vec![20 + 2 * k + 1]].concat(), model.n[2 * k + 1]));
    }
    let (mut mass, mut forcing) = (
        lagrange::nalgebra::SMatrix::<f64, 30, 30>::zeros(),
        SVector::<f64, 30>::zeros(),
    );
    for (path, m) in &points {
        let (mut jx, mut jy) = (SVector::<f64, 30>::zeros(), SVector::<f64, 30>::zeros());
        let (mut bx, mut by) = (0.0, 0.0);
        for &link in path {
            let w = &links[link];
            let alpha: f64 = w.iter().map(|&c| q[c]).sum();
            let rate: f64 = w.iter().map(|&c| v[c]).sum();
            let (s, c) = alpha.sin_cos();
            for &i in w {
                jx[i] += model.l * c;
                jy[i] += model.l * s;
            }
            bx -= model.l * s * rate * rate;
            by += model.l * c * rate * rate;
        }
        mass += *m * (jx * jx.transpose() + jy * jy.transpose());
        forcing -= *m * (jx * bx + jy * (by + 9.81));
    }
    (mass, forcing)
}

#[test]
fn the_comb_is_solved_by_the_recursion_as_by_its_m_and_f_written_by_hand() {
    let model = comb();
    // The tree found: the recursion answers for `accelerations`.
    const { assert!(<Comb<f64> as Lagrangian<30>>::SOLVES_ACCELERATIONS) };
    for k in 0..50 {
        let (q, v) = state::<30>(k);
        let (m, f) = comb_by_hand(&model, &q, &v);
        // The formed `M` and `f` are the hand-written ones up to rounding:
        // sums of the same products in other orders, bounded as in
        // `formed_as_derived` by 16 N ε of the largest entry.
        let (fm, ff) = model.mass_matrix_and_forcing(0.0, &q, &v);
        let bound = |x: f64| 16.0 * 30.0 * f64::EPSILON * x;
        assert!((fm - m).amax() <= bound(m.amax()), "state {k}: M");
        assert!((ff - f).amax() <= bound(f.amax()), "state {k}: f");
        let a = model
            .accelerations(0.0, &q, &v)
            .expect("the recursion answers")
            .expect("a regular M");
        // Its backward error, as `solves_m_qddot_equals_f`'s: 64 N ε of
        // the sizes in play.
        let scale = m.abs().row_sum().max() * a.amax() + f.amax();
        let residual = (m * a - f).amax();
        assert!(
            residual <= 64.0 * 30.0 * f64::EPSILON * scale,
            "state {k}: |M q̈ − f| = {residual:e} of {scale:e}"
        );
        // And the forward error against the dense solve of the same `M`
        // and `f`: the backward error times M's condition number (2-norm,
        // from its eigenvalues: M is symmetric positive definite), the
        // bound a backward-stable solve meets.
        let dense = m.cholesky().expect("M positive definite").solve(&f);
        let eigen = m.symmetric_eigenvalues();
        let condition = eigen.max() / eigen.min();
        let gap = (a - dense).amax();
        assert!(
            gap <= 64.0 * 30.0 * f64::EPSILON * condition * dense.amax(),
            "state {k}: q̈ {gap:e} from the dense solve's, cond(M) = {condition:e}"
        );
    }
}
