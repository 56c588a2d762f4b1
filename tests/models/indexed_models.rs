//! The indexed DSL (`const`, `theta[N]`, `m[N]`, `let x[i in a..b]`,
//! `sum(j in a..=b, ...)`, index arithmetic), compile-time `constants:`,
//! forces along `let` positions, repeated sections: each checked against a
//! closed form derived by hand, at random states.
//!
//! Tolerance: the generated code and the closed forms evaluate the same
//! smooth functions in different orders of operations, so they differ by a
//! few ulps per operation; with O(N²) terms of size O(1) a relative 1e-10
//! leaves a margin of more than 1e3 over that rounding.

use lagrange::models::Chain;
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use rand::{Rng, SeedableRng, rngs::StdRng};

const TOL: f64 = 1e-10;

lagrangian! {
    /// The chain: N point masses on massless rods, with a wind force
    /// at the tip and a damper on the first joint.
    pub struct WindyChain {
        const N = 5;
        coordinates: theta[N];
        parameters: m[N], l[N];
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
        forces: x[N-1] = wind*sin(t), theta[0] = -c*dot(theta[0]);
        parameters: wind, c;
    }
}

/// The links of `lagrange::models::Chain`, the chain without forces.
const N: usize = Chain::<f64>::DOF;
const G: f64 = 9.81;

fn random_chain(rng: &mut StdRng) -> ([f64; N], [f64; N]) {
    let m = std::array::from_fn(|_| rng.gen_range(0.5..2.0));
    let l = std::array::from_fn(|_| rng.gen_range(0.5..2.0));
    (m, l)
}

/// Mass carried at and below link `k`: Σ_{k' ≥ k} m_k'.
fn tail(m: &[f64; N], k: usize) -> f64 {
    m[k..].iter().sum()
}

/// Closed forms for the chain (angles from the downward vertical):
/// M_ij = l_i l_j cos(θ_i − θ_j) μ_max(i,j),
/// f_i  = −Σ_j l_i l_j sin(θ_i − θ_j) θ̇_j² μ_max(i,j) − g l_i sin θ_i μ_i,
/// with μ_k the mass at and below link k.
fn closed_form(
    m: &[f64; N],
    l: &[f64; N],
    q: &SVector<f64, N>,
    v: &SVector<f64, N>,
) -> (Vec<Vec<f64>>, Vec<f64>) {
    let mut mass = vec![vec![0.0; N]; N];
    let mut f = vec![0.0; N];
    for i in 0..N {
        for j in 0..N {
            let mu = tail(m, i.max(j));
            mass[i][j] = l[i] * l[j] * (q[i] - q[j]).cos() * mu;
            f[i] -= l[i] * l[j] * (q[i] - q[j]).sin() * v[j] * v[j] * mu;
        }
        f[i] -= G * l[i] * q[i].sin() * tail(m, i);
    }
    (mass, f)
}

fn random_state(rng: &mut StdRng) -> (SVector<f64, N>, SVector<f64, N>) {
    (
        SVector::from_fn(|_, _| rng.gen_range(-3.0..3.0)),
        SVector::from_fn(|_, _| rng.gen_range(-2.0..2.0)),
    )
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= TOL * scale.max(1.0)
}

#[test]
fn indexed_chain_matches_the_closed_form() {
    let mut rng = StdRng::seed_from_u64(5);
    for _ in 0..200 {
        let (m, l) = random_chain(&mut rng);
        let chain = Chain::new(m, l);
        let (q, v) = random_state(&mut rng);
        let (mass, f) = chain.mass_matrix_and_forcing(0.0, &q, &v);
        let (mass_ref, f_ref) = closed_form(&m, &l, &q, &v);
        let scale = f_ref.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        for i in 0..N {
            assert!(
                close(f[i], f_ref[i], scale),
                "f[{i}]: {} vs {}",
                f[i],
                f_ref[i]
            );
            for j in 0..N {
                assert!(
                    close(mass[(i, j)], mass_ref[i][j], 1.0),
                    "M[{i},{j}]: {} vs {}",
                    mass[(i, j)],
                    mass_ref[i][j]
                );
            }
        }
    }
}

#[test]
fn the_chain_hanging_straight_down_is_finite_and_at_rest() {
    // All angles equal: every sin(θ_i − θ_j) vanishes. A removable 0/0 in
    // the simplified forcing (once seen: (a − b)²/(b − a)) would give NaN.
    let chain = Chain::new([1.0; N], [1.0; N]);
    for angle in [0.0, 0.3] {
        let q = SVector::<f64, N>::from_element(angle);
        let (mass, f) = chain.mass_matrix_and_forcing(0.0, &q, &SVector::zeros());
        assert!(mass.iter().chain(f.iter()).all(|x| x.is_finite()));
        let (_, f_ref) = closed_form(&[1.0; N], &[1.0; N], &q, &SVector::zeros());
        for i in 0..N {
            assert!(close(f[i], f_ref[i], 10.0), "f[{i}] = {}", f[i]);
        }
    }
}

#[test]
fn names_fields_and_compile_time_constants() {
    assert_eq!(
        Chain::<f64>::COORDINATES,
        ["theta[0]", "theta[1]", "theta[2]", "theta[3]", "theta[4]"]
    );
    // `g` is a constant, folded: no field, no constructor argument.
    assert_eq!(Chain::<f64>::PARAMETERS, ["m", "l"]);
    assert_eq!(WindyChain::<f64>::PARAMETERS, ["m", "l", "wind", "c"]);
    let chain = WindyChain::new([1.0; N], [2.0; N], 0.5, 0.1);
    assert_eq!(chain.l, [2.0; N]);
    assert!(Chain::<f64>::EQUATIONS.contains("9.81"));
    assert!(!Chain::<f64>::EQUATIONS.contains(" g"));
    // A NaN in an array parameter is caught like a scalar one.
    let bad = Chain::new([1.0, 1.0, f64::NAN, 1.0, 1.0], [1.0; N]);
    assert!(!Lagrangian::parameters_are_finite(&bad));
    assert!(Lagrangian::parameters_are_finite(&chain));
}

#[test]
fn a_force_along_a_let_position_does_virtual_work() {
    // Q_i = wind sin t · ∂x_{N−1}/∂θ_i − c θ̇_0 δ_i0, and
    // ∂x_{N−1}/∂θ_i = l_i cos θ_i for every link.
    let mut rng = StdRng::seed_from_u64(6);
    for _ in 0..200 {
        let (m, l) = random_chain(&mut rng);
        let (wind, c) = (rng.gen_range(-2.0..2.0), rng.gen_range(0.0..1.0));
        let t: f64 = rng.gen_range(0.0..10.0);
        let windy = WindyChain::new(m, l, wind, c);
        let calm = Chain::new(m, l);
        let (q, v) = random_state(&mut rng);
        let forces = windy.nonconservative_forces(t, &q, &v);
        let f_windy = windy.forcing(t, &q, &v);
        let f_calm = calm.forcing(t, &q, &v);
        for i in 0..N {
            let expected = wind * t.sin() * l[i] * q[i].cos() - if i == 0 { c * v[0] } else { 0.0 };
            assert!(close(forces[i], expected, 1.0), "Q[{i}]");
            // ... and it is exactly what the forcing gains.
            let scale = f_calm[i].abs() + expected.abs();
            assert!(close(f_windy[i] - f_calm[i], expected, scale), "f[{i}]");
        }
    }
}

#[test]
fn a_model_without_forces_is_conservative_and_emits_no_force_code() {
    let chain = Chain::new([1.0; N], [1.0; N]);
    let q = SVector::from_element(0.4);
    let zero = Lagrangian::nonconservative_forces(&chain, 0.0, &q, &q);
    assert_eq!(zero, Some(SVector::zeros()));
}

lagrangian! {
    /// A ring of N carts joined by springs of rest length d: index
    /// arithmetic (`i-1`, `N-1`) and a sum starting at 1.
    pub struct SpringTrain {
        const N = 4;
        coordinates: x[N];
        parameters: m, k, d;
        kinetic: sum(i in 0..N, m/2*dot(x[i])^2);
        potential: sum(i in 1..N, k/2*(x[i] - x[i-1] - d)^2) + k/2*(x[0] + N*d - x[N-1] - d)^2;
    }
}

#[test]
fn index_arithmetic_and_ranges() {
    let mut rng = StdRng::seed_from_u64(7);
    let (m, k, d) = (1.5, 3.0, 0.25);
    let train = SpringTrain::new(m, k, d);
    for _ in 0..100 {
        let x = SVector::<f64, 4>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
        let f = train.forcing(0.0, &x, &SVector::zeros());
        let mass = train.mass_matrix(0.0, &x);
        for i in 0..4 {
            // Ring: the neighbour of 0 below is 3 shifted by one lap, 4d.
            let prev = if i == 0 { x[3] - 4.0 * d } else { x[i - 1] };
            let next = if i == 3 { x[0] + 4.0 * d } else { x[i + 1] };
            let expected = k * (next - x[i] - d) - k * (x[i] - prev - d);
            assert!(close(f[i], expected, 1.0), "f[{i}]: {} vs {expected}", f[i]);
            assert_eq!(mass[(i, i)], m);
        }
    }
}

lagrangian! {
    /// A particle in a plane, its kinetic and potential energies each
    /// written in two sections: repeated sections add up.
    pub struct SplitSections {
        coordinates: x;
        parameters: m, kx;
        kinetic: m/2*dot(x)^2;
        potential: kx/2*x^2;
        coordinates: y;
        kinetic: m/2*dot(y)^2;
        potential: ky/2*y^2;
        parameters: ky;
    }
}

#[test]
fn repeated_sections_add_up() {
    let model = SplitSections::new(2.0, 3.0, 5.0);
    let q = lagrange::nalgebra::Vector2::new(0.5, -0.25);
    let v = lagrange::nalgebra::Vector2::new(1.0, 2.0);
    assert_eq!(
        model.mass_matrix(0.0, &q),
        lagrange::nalgebra::Matrix2::new(2.0, 0.0, 0.0, 2.0)
    );
    let f = model.forcing(0.0, &q, &v);
    assert_eq!((f[0], f[1]), (-1.5, 1.25));
    assert_eq!(model.kinetic_energy(0.0, &q, &v), 5.0);
}

#[test]
fn an_f32_chain_integrates() {
    let chain = Chain::<f32>::new([1.0; N], [0.5; N]);
    let q0 = SVector::<f32, N>::from_element(1.0);
    let e0 = chain.energy(0.0, &q0, &SVector::zeros());
    let times: Vec<f32> = (0..=60).map(|k| k as f32 / 60.0).collect();
    let traj = Rk4::new(1.0 / 240.0)
        .integrate(&chain, 0.0, q0, SVector::zeros(), &times)
        .expect("a smooth, short run");
    let last = traj.last().unwrap();
    let e1 = chain.energy(last.t, &last.q, &last.qdot);
    // RK4 at h = 1/240 over 1 s on a chain with periods ~0.3 s: the
    // truncation error is ~1e-5 of E, f32 rounding ~1e-6 per step summed.
    assert!(((e1 - e0) / e0).abs() < 1e-3, "drift {}", (e1 - e0) / e0);
}
