//! Robots from URDF (`#[lagrange(urdf = ..)]`): the recursions the macro
//! writes (RNEA, CRBA, ABA) against Pinocchio's at 100 random states of
//! each robot (`tests/data/robots/reference_*.json`, written once by
//! `tests/data/robots/reference.py`), and against the energy route: `M`
//! the Hessian of the kinetic energy, `f` the Euler–Lagrange equations of
//! `T − V`, both by differences of the energies the macro writes directly
//! (not by the recursions).

use lagrange::Lagrangian;
use lagrange::nalgebra::{SMatrix, SVector};
use lagrange::prelude::*;
use serde_json::Value;

lagrangian! {
    /// The UR5 of example-robot-data.
    #[lagrange(urdf = "tests/data/robots/ur5.urdf")]
    pub struct Ur5 {}
}

lagrangian! {
    /// The Panda of example-robot-data, its fingers locked closed.
    #[lagrange(urdf = "tests/data/robots/panda.urdf")]
    pub struct Panda {
        locked: panda_finger_joint1 = 0.0, panda_finger_joint2 = 0.0;
    }
}

lagrangian! {
    /// A tree of four joints on unaligned axes, one prismatic.
    #[lagrange(urdf = "tests/data/robots/tree.urdf")]
    pub struct Tree {}
}

/// What a robot is asked, at one state.
trait Robot<const N: usize> {
    const NAMES: [&'static str; N];
    fn m(&self, q: &SVector<f64, N>) -> SMatrix<f64, N, N>;
    fn nle(&self, q: &SVector<f64, N>, v: &SVector<f64, N>) -> SVector<f64, N>;
    fn aba(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        tau: &SVector<f64, N>,
    ) -> SVector<f64, N>;
    fn rnea(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        a: &SVector<f64, N>,
    ) -> SVector<f64, N>;
}

macro_rules! robot {
    ($t:ty, $n:literal) => {
        impl Robot<$n> for $t {
            const NAMES: [&'static str; $n] = <$t>::COORDINATES;
            fn m(&self, q: &SVector<f64, $n>) -> SMatrix<f64, $n, $n> {
                self.mass_matrix(0.0, q)
            }
            fn nle(&self, q: &SVector<f64, $n>, v: &SVector<f64, $n>) -> SVector<f64, $n> {
                self.nonlinear_effects(q, v)
            }
            fn aba(
                &self,
                q: &SVector<f64, $n>,
                v: &SVector<f64, $n>,
                tau: &SVector<f64, $n>,
            ) -> SVector<f64, $n> {
                self.forward_dynamics(q, v, tau)
            }
            fn rnea(
                &self,
                q: &SVector<f64, $n>,
                v: &SVector<f64, $n>,
                a: &SVector<f64, $n>,
            ) -> SVector<f64, $n> {
                self.inverse_dynamics(q, v, a)
            }
        }
    };
}
robot!(Ur5, 6);
robot!(Panda, 7);
robot!(Tree, 4);

fn vector<const N: usize>(v: &Value) -> SVector<f64, N> {
    SVector::from_iterator(v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
}

/// The largest error of `ours` against `theirs`, relative to `theirs`'
/// largest entry.
fn relative(ours: &[f64], theirs: &[f64]) -> f64 {
    let scale = theirs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let err = ours
        .iter()
        .zip(theirs)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    err / scale
}

/// Compares a robot with Pinocchio at every recorded state; returns the
/// worst relative error of M, nle, ABA's q̈ and RNEA's τ.
fn against_pinocchio<R: Robot<N>, const N: usize>(robot: &R, file: &str) -> [f64; 4] {
    let path = format!("{}/tests/data/robots/{file}", env!("CARGO_MANIFEST_DIR"));
    let json: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let joints: Vec<&str> = json["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j.as_str().unwrap())
        .collect();
    assert_eq!(
        joints,
        R::NAMES,
        "the coordinates are Pinocchio's joints, in its order"
    );
    let states = json["states"].as_array().unwrap();
    assert_eq!(states.len(), 100);
    let mut worst = [0.0f64; 4];
    for s in states {
        let (q, v, a, tau) = (
            vector::<N>(&s["q"]),
            vector::<N>(&s["v"]),
            vector::<N>(&s["a"]),
            vector::<N>(&s["tau"]),
        );
        let m_ref: Vec<f64> = s["mass_matrix"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|row| vector::<N>(row).data.0[0])
            .collect();
        let m = robot.m(&q).transpose(); // row-major, as the JSON
        let errors = [
            relative(m.as_slice(), &m_ref),
            relative(
                robot.nle(&q, &v).as_slice(),
                vector::<N>(&s["nonlinear_effects"]).as_slice(),
            ),
            relative(
                robot.aba(&q, &v, &tau).as_slice(),
                vector::<N>(&s["aba"]).as_slice(),
            ),
            relative(
                robot.rnea(&q, &v, &a).as_slice(),
                vector::<N>(&s["rnea"]).as_slice(),
            ),
        ];
        for (w, e) in worst.iter_mut().zip(errors) {
            *w = w.max(e);
        }
    }
    worst
}

// The tolerance: both sides run the same recursions in f64, in different
// orders of operations (Pinocchio over 6-vectors and placements, ours
// unrolled with the constants folded), and the URDF's rotations are read
// alike; each entry is a sum of some hundred rounded products, so their
// difference is a few hundred ulps of the largest entry at most: 1e-12 of
// it (4500 ulps) holds with margin, where any mistake in a joint, an axis,
// an inertia or a sign shows at 1e-3 or more. ABA's q̈ carries M's
// condition number on top (at most ~1e3 on these arms at these states),
// still within it: the figures printed are the measured ones.
const TOLERANCE: f64 = 1e-12;

fn check<R: Robot<N>, const N: usize>(robot: &R, file: &str) {
    let worst = against_pinocchio(robot, file);
    println!(
        "{file}: M {:.1e}, nle {:.1e}, aba {:.1e}, rnea {:.1e}",
        worst[0], worst[1], worst[2], worst[3]
    );
    for (what, e) in ["M", "nonlinear effects", "ABA's q̈", "RNEA's τ"]
        .iter()
        .zip(worst)
    {
        assert!(
            e < TOLERANCE,
            "{file}: {what} off Pinocchio's by {e:e} of its largest entry"
        );
    }
}

#[test]
fn ur5_matches_pinocchio() {
    check(&Ur5::new(), "reference_ur5.json");
}

#[test]
fn panda_with_fingers_locked_matches_pinocchio() {
    check(&Panda::new(), "reference_panda.json");
}

#[test]
fn tree_of_unaligned_axes_with_a_prismatic_joint_matches_pinocchio() {
    check(&Tree::new(), "reference_tree.json");
}

/// The energy route on the tree: `M = ∂²T/∂q̇²` and
/// `f = ∂(T − V)/∂q − (∂²T/∂q̇∂q) q̇` by central differences of the
/// kinetic and potential energies (written directly, body by body, not by
/// the recursions).
#[test]
fn tree_recursions_match_its_energies_euler_lagrange() {
    let tree = Tree::new();
    let q = SVector::<f64, 4>::new(0.7, -0.12, 2.1, -1.3);
    let v = SVector::<f64, 4>::new(-0.9, 0.4, 1.7, 0.6);
    let e = |i: usize| SVector::<f64, 4>::from_fn(|k, _| if k == i { 1.0 } else { 0.0 });
    let t = |q: &SVector<f64, 4>, v: &SVector<f64, 4>| tree.kinetic_energy(0.0, q, v);
    let lagrangian = |q: &SVector<f64, 4>| t(q, &v) - tree.potential_energy(0.0, q);
    // T is quadratic in q̇: its second difference is exact up to rounding.
    let h = 1e-3;
    let m = tree.mass_matrix(0.0, &q);
    let f = Lagrangian::forcing(&tree, 0.0, &q, &v);
    let scale_m = m.amax();
    for i in 0..4 {
        for j in 0..4 {
            let (ei, ej) = (e(i) * h, e(j) * h);
            let d2 = (t(&q, &(ei + ej)) - t(&q, &(ei - ej)) - t(&q, &(ej - ei))
                + t(&q, &(-ei - ej)))
                / (4.0 * h * h);
            // Rounding of T (~1e-16 × T ≈ 1e-16) over 4h²: 1e-10 of M.
            assert!(
                (d2 - m[(i, j)]).abs() < 1e-8 * scale_m,
                "M[{i},{j}] {} against ∂²T {d2}",
                m[(i, j)]
            );
        }
    }
    // f by differences in q: step 1e-5, truncation O(h²) ~ 1e-10 relative,
    // rounding ~1e-16/1e-5 = 1e-11 relative; compared to 1e-7 of f's largest.
    let h = 1e-5;
    let mut f_el = SVector::<f64, 4>::zeros();
    for i in 0..4 {
        let dl = (lagrangian(&(q + e(i) * h)) - lagrangian(&(q - e(i) * h))) / (2.0 * h);
        // (∂²T/∂q̇_i∂q) q̇ = d/dε ∂T/∂q̇_i (q + ε q̇): ∂T/∂q̇_i = (M q̇)_i.
        let p = |q: &SVector<f64, 4>| (tree.mass_matrix(0.0, q) * v)[i];
        let dp = (p(&(q + v * h)) - p(&(q - v * h))) / (2.0 * h);
        f_el[i] = dl - dp;
    }
    assert!(
        (f - f_el).amax() < 1e-7 * f.amax(),
        "f {f} against Euler–Lagrange {f_el}"
    );
}

/// The contract: the runtime's `q̈` (the model's `accelerations`, ABA at
/// τ = 0) is `M⁻¹ f`; and in `f32` the same code runs.
#[test]
fn panda_accelerations_solve_m_qdd_f_and_run_in_f32() {
    let panda = Panda::new();
    const { assert!(<Panda as Lagrangian<7>>::SOLVES_ACCELERATIONS) };
    let q = SVector::<f64, 7>::from_fn(|i, _| 0.3 * i as f64 - 0.8);
    let v = SVector::<f64, 7>::from_fn(|i, _| 0.5 - 0.2 * i as f64);
    let qdd = Lagrangian::accelerations(&panda, 0.0, &q, &v)
        .unwrap()
        .unwrap();
    let (m, f) = panda.mass_matrix_and_forcing(0.0, &q, &v);
    let solved = m.cholesky().unwrap().solve(&f);
    // Two routes in f64 through M's condition (~1e3 here): 1e-11 of q̈.
    assert!((qdd - solved).amax() < 1e-11 * solved.amax());
    let single = Panda::<f32>::new()
        .mass_matrix(0.0, &q.cast::<f32>())
        .cast::<f64>();
    // f32 rounding (6e-8) over a few hundred operations: 1e-5 of M.
    assert!((single - m).amax() < 1e-5 * m.amax());
}
