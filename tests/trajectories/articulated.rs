//! Models whose masses hang on a tree of increments: `lagrangian!` finds
//! the form and the runtime solves `M q̈ = f` by the articulated-body
//! recursion, in `O(N)` without `M` (`lagrange::linalg::articulated`).
//! Here: that it solves the same system as the dense solve, that runs
//! through it follow the dense runs, and that where it cannot answer (a
//! massless link) the dense solve's typed error comes out unchanged.

use lagrange::Lagrangian;
use lagrange::models::Tree;
use lagrange::nalgebra::{SMatrix, SVector};
use lagrange::prelude::*;

lagrangian! {
    /// The chain of ten links in absolute angles, masses and lengths as
    /// parameters.
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

fn chain(last_mass: f64) -> Chain10<f64> {
    Chain10::new(
        std::array::from_fn(|i| {
            if i == 9 {
                last_mass
            } else {
                1.0 + 0.1 * i as f64
            }
        }),
        std::array::from_fn(|i| 1.0 - 0.04 * i as f64),
    )
}

/// The same model, its accelerations from `M` and `f`: the dense solve.
#[derive(Clone)]
struct Dense<L>(L);

impl<L: Lagrangian<N>, const N: usize> Lagrangian<N> for Dense<L> {
    type Scalar = L::Scalar;
    const COORDINATES: [&'static str; N] = L::COORDINATES;
    fn mass_matrix(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> SMatrix<L::Scalar, N, N> {
        self.0.mass_matrix(t, q)
    }
    fn forcing(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        v: &SVector<L::Scalar, N>,
    ) -> SVector<L::Scalar, N> {
        self.0.forcing(t, q, v)
    }
    fn mass_matrix_and_forcing(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        v: &SVector<L::Scalar, N>,
    ) -> (SMatrix<L::Scalar, N, N>, SVector<L::Scalar, N>) {
        self.0.mass_matrix_and_forcing(t, q, v)
    }
    fn kinetic_energy(
        &self,
        t: L::Scalar,
        q: &SVector<L::Scalar, N>,
        v: &SVector<L::Scalar, N>,
    ) -> L::Scalar {
        self.0.kinetic_energy(t, q, v)
    }
    fn potential_energy(&self, t: L::Scalar, q: &SVector<L::Scalar, N>) -> L::Scalar {
        self.0.potential_energy(t, q)
    }
}

/// A state spread over the circle and over `±3` rad/s, `k` its seed.
fn state<const N: usize>(k: usize) -> (SVector<f64, N>, SVector<f64, N>) {
    let q = SVector::from_fn(|i, _| 3.0 * ((7 * i + 13 * k) as f64 * 0.37).sin());
    let v = SVector::from_fn(|i, _| 3.0 * ((5 * i + 11 * k) as f64 * 0.61).cos());
    (q, v)
}

fn solves_m_qddot_equals_f<L: Lagrangian<N, Scalar = f64>, const N: usize>(model: &L) {
    assert!(L::SOLVES_ACCELERATIONS, "the form was not found");
    for k in 0..200 {
        let (q, v) = state::<N>(k);
        let a = model
            .accelerations(0.0, &q, &v)
            .expect("the recursion answers")
            .expect("a regular M");
        let (m, f) = model.mass_matrix_and_forcing(0.0, &q, &v);
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
    solves_m_qddot_equals_f(&chain(1.9));
    solves_m_qddot_equals_f(&Tree::unit());
}

#[test]
fn runs_through_the_recursion_follow_the_dense_runs() {
    // RK4 at h = 1e-3 for 1 s from a start at rest: the two runs differ by
    // the rounding of each q̈ (relative 1e-15, the test above), carried over
    // 1000 steps and grown by the motion; measured at 3e-14 (chain) and
    // 1.1e-13 (tree).
    // 1e-10 leaves room for a platform's rounding while catching any error
    // of the recursion's (a wrong term moves the state by 1e-3 or more).
    fn compare<L: Lagrangian<N, Scalar = f64> + Clone, const N: usize>(model: &L) {
        let q0 = SVector::<f64, N>::from_fn(|i, _| if i == 0 { 1.0 } else { 0.3 });
        let run = |fast: bool| {
            let times = [1.0];
            let end = if fast {
                Rk4::new(1e-3).integrate(model, 0.0, q0, SVector::zeros(), &times)
            } else {
                Rk4::new(1e-3).integrate(&Dense(model.clone()), 0.0, q0, SVector::zeros(), &times)
            };
            let last = end.expect("the run").last().expect("one sample");
            (last.q, last.qdot)
        };
        let ((qa, va), (qd, vd)) = (run(true), run(false));
        let gap = (qa - qd).amax().max((va - vd).amax());
        assert!(
            gap < 1e-10,
            "the recursion's run is {gap:e} from the dense one"
        );
    }
    compare(&chain(1.9));
    compare(&Tree::unit());
}

#[test]
fn a_massless_tip_gets_the_dense_solves_error() {
    // The last link's mass zero: its joint's articulated inertia vanishes,
    // the recursion declines, and the dense solve reports the singular `M`
    // at the same t, in the same state, as it did before the recursion.
    let model = chain(0.0);
    let (q, v) = state::<10>(3);
    assert_eq!(model.accelerations(0.0, &q, &v), None);
    let times = [1.0];
    let ours = Rk4::new(1e-3).integrate(&model, 0.0, q, v, &times);
    let dense = Rk4::new(1e-3).integrate(&Dense(model), 0.0, q, v, &times);
    let (ours, dense) = (ours.expect_err("singular"), dense.expect_err("singular"));
    assert!(
        matches!(ours.error, IntegrationError::SingularMassMatrix { .. }),
        "{}",
        ours.error
    );
    assert_eq!(ours.error.to_string(), dense.error.to_string());
}
