//! A robot's inertial parameters as fields of its struct
//! (`#[lagrange(parameters(field = "link"))]`): at the file's values
//! (`new()`), the same bits as the robot with its constants folded; with
//! other values, every method moves with them as the regressor says (`Y π`
//! is RNEA's τ for the changed `π`), `M` with ABA and the kinetic energy,
//! the potential energy with the gravity torques; on a fixed base (the
//! tests' tree, its wrist with the weight welded to it) and on a floating
//! one (the trunk's own parameters).

use super::robots::{Tree, spread};
use lagrange::ensemble::AutoF64x4;
use lagrange::nalgebra::{
    Matrix3, Quaternion, SMatrix, SVector, SimdValue, UnitQuaternion, Vector3,
};
use lagrange::prelude::*;

lagrangian! {
    /// `tree.urdf` with its wrist's body (the weight welded to it included)
    /// and its arm's as fields.
    #[lagrange(urdf = "tests/data/robots/tree.urdf", regressor, parameters(wrist = "wrist", arm = "arm"))]
    pub struct TreeParameters {}
}

lagrangian! {
    /// A free trunk with an arm and a forearm, in constants.
    #[lagrange(regressor)]
    pub struct Swimmer {
        bodies:
            trunk: mass 3.0, com [0.02, 0, -0.01], inertia [[0.05, 0.001, 0], [0.001, 0.04, 0.002], [0, 0.002, 0.03]];
            arm: mass 0.7, com [0, 0, 0.15], inertia diag(0.004, 0.004, 0.0006);
            fore: mass 0.4, com [0.1, 0, 0], inertia diag(0.0002, 0.002, 0.002);
        joints:
            free: floating base -> trunk;
            shoulder: revolute trunk -> arm, at translate(0.1, 0, 0.05), axis [0, 1, 0];
            elbow: revolute arm -> fore, at translate(0, 0, 0.3) * rotate_x(0.3), axis [0, 0.6, 0.8];
    }
}

lagrangian! {
    /// [`Swimmer`] with the trunk's and the forearm's parameters as fields:
    /// its bodies and joints written again, since the tests compare the
    /// two robots.
    #[lagrange(regressor, parameters(trunk = "trunk", fore = "fore"))]
    pub struct SwimmerParameters {
        bodies:
            trunk: mass 3.0, com [0.02, 0, -0.01], inertia [[0.05, 0.001, 0], [0.001, 0.04, 0.002], [0, 0.002, 0.03]];
            arm: mass 0.7, com [0, 0, 0.15], inertia diag(0.004, 0.004, 0.0006);
            fore: mass 0.4, com [0.1, 0, 0], inertia diag(0.0002, 0.002, 0.002);
        joints:
            free: floating base -> trunk;
            shoulder: revolute trunk -> arm, at translate(0.1, 0, 0.05), axis [0, 1, 0];
            elbow: revolute arm -> fore, at translate(0, 0, 0.3) * rotate_x(0.3), axis [0, 0.6, 0.8];
    }
}

/// A rigid body's ten parameters in Pinocchio's order, about the frame's
/// origin: mass `m`, centre of mass `c`, inertia `ic` about `c`.
fn parameters(m: f64, c: Vector3<f64>, ic: Matrix3<f64>) -> [f64; 10] {
    let io = ic + m * (c.norm_squared() * Matrix3::identity() - c * c.transpose());
    let h = m * c;
    [
        m,
        h.x,
        h.y,
        h.z,
        io[(0, 0)],
        io[(0, 1)],
        io[(1, 1)],
        io[(0, 2)],
        io[(1, 2)],
        io[(2, 2)],
    ]
}

#[test]
fn named_parameters_at_the_files_values_give_the_constant_robots_bits() {
    let (file, named) = (Tree::<f64>::new(), TreeParameters::<f64>::new());
    // `new()` writes the file's parameters: the body's slice of PARAMETERS.
    assert_eq!(named.wrist[..], Tree::<f64>::PARAMETERS[20..30]);
    assert_eq!(named.arm[..], Tree::<f64>::PARAMETERS[30..40]);
    // An identified π (an nalgebra vector) goes in by assignment.
    let mut twin = named;
    twin.arm = SVector::<f64, 10>::from(named.arm).into();
    assert_eq!(twin, named);
    // The parameters read at run time instead of folded at compile time:
    // the same operations on the same numbers (a product by a constant
    // zero or one is exact either way), hence the same bits.
    for [q, v, a] in spread::<4>(11, 40) {
        assert_eq!(file.mass_matrix(0.0, &q), named.mass_matrix(0.0, &q));
        assert_eq!(
            file.nonlinear_effects(&q, &v),
            named.nonlinear_effects(&q, &v)
        );
        assert_eq!(
            file.inverse_dynamics(&q, &v, &a),
            named.inverse_dynamics(&q, &v, &a)
        );
        assert_eq!(
            file.forward_dynamics(&q, &v, &a),
            named.forward_dynamics(&q, &v, &a)
        );
        assert_eq!(
            file.kinetic_energy(0.0, &q, &v),
            named.kinetic_energy(0.0, &q, &v)
        );
        assert_eq!(
            file.potential_energy(0.0, &q),
            named.potential_energy(0.0, &q)
        );
    }
    // The fields are the scalar's: in f32, `M` to f32's rounding (6e-8 a
    // operation, a few hundred operations: 1e-5 of its largest entry).
    let q = SVector::<f64, 4>::new(0.3, 0.05, -1.2, 0.8);
    let m32 = TreeParameters::<f32>::new().mass_matrix(0.0, &q.cast::<f32>());
    let m64 = file.mass_matrix(0.0, &q);
    assert!((m32.cast::<f64>() - m64).amax() < 1e-5 * m64.amax());
    // And on SIMD lanes, four states at once, each lane its own state's
    // (the lanes' sine and cosine may round a few ulps off the scalar's:
    // 1e-14 of the torques).
    let mut wide = TreeParameters::<AutoF64x4>::new();
    wide.wrist[0] = AutoF64x4::splat(1.4);
    let mut heavy = named;
    heavy.wrist[0] = 1.4;
    let states = spread::<4>(15, 4);
    let lanes = |k: usize| {
        SVector::<AutoF64x4, 4>::from_fn(|i, _| {
            AutoF64x4::from([0, 1, 2, 3].map(|s| states[s][k][i]))
        })
    };
    let tau = wide.inverse_dynamics(&lanes(0), &lanes(1), &lanes(2));
    for (s, [q, v, a]) in states.iter().enumerate() {
        let one = heavy.inverse_dynamics(q, v, a);
        close(
            "τ on a lane",
            &tau.map(|x| x.extract(s)),
            &one,
            one.amax(),
            1e-14,
        );
    }
    let (file, named) = (Swimmer::<f64>::new(), SwimmerParameters::<f64>::new());
    assert_eq!(named.trunk[..], Swimmer::<f64>::PARAMETERS[0..10]);
    assert_eq!(named.fore[..], Swimmer::<f64>::PARAMETERS[20..30]);
    for (q, v, a) in floating_states(12, 40) {
        assert_eq!(
            file.velocity_mass_matrix(&q),
            named.velocity_mass_matrix(&q)
        );
        assert_eq!(
            file.inverse_dynamics(&q, &v, &a),
            named.inverse_dynamics(&q, &v, &a)
        );
        assert_eq!(
            file.forward_dynamics(&q, &v, &a),
            named.forward_dynamics(&q, &v, &a)
        );
        let qdot = file.rates(&q, &v);
        assert_eq!(
            file.kinetic_energy(0.0, &q, &qdot),
            named.kinetic_energy(0.0, &q, &qdot)
        );
        assert_eq!(
            file.potential_energy(0.0, &q),
            named.potential_energy(0.0, &q)
        );
    }
}

/// The swimmer's states: its position, a unit quaternion, its two joints'
/// angles; its velocities `ν` and accelerations `ν̇` (8 each).
fn floating_states(
    seed: u64,
    count: usize,
) -> Vec<(SVector<f64, 9>, SVector<f64, 8>, SVector<f64, 8>)> {
    spread::<9>(seed, count)
        .into_iter()
        .map(|[x, v, a]| {
            let mut q = x;
            let quat = x.fixed_rows::<4>(3).normalize();
            q.fixed_rows_mut::<4>(3).copy_from(&quat);
            (
                q,
                v.fixed_rows::<8>(0).into_owned(),
                a.fixed_rows::<8>(0).into_owned(),
            )
        })
        .collect()
}

/// `a` within `bound` of `b`, entry by entry, relative to `scale`.
fn close<const R: usize, const C: usize>(
    what: &str,
    a: &SMatrix<f64, R, C>,
    b: &SMatrix<f64, R, C>,
    scale: f64,
    bound: f64,
) {
    let e = (a - b).amax() / scale;
    assert!(
        e < bound,
        "{what}: {e:.2e} of {scale:.3e}, bound {bound:.0e}"
    );
}

/// `|Y| |π|`, entry by entry: the scale of the rounding of `Y π`.
fn rounding_scale<const N: usize, const P: usize>(
    y: &SMatrix<f64, N, P>,
    pi: &SVector<f64, P>,
) -> f64 {
    (y.abs() * pi.abs()).amax()
}

/// The named robot's `τ` against the regressor's `Y π` for its changed
/// `π`, and `M q̈ + nle` against `τ` (ABA, CRBA and RNEA read the same
/// parameters), `q̈` ABA's answer to `τ`.
fn consistent<const N: usize, const P: usize>(
    tau: &SVector<f64, N>,
    y: &SMatrix<f64, N, P>,
    pi: &SVector<f64, P>,
    m: &SMatrix<f64, N, N>,
    nle: &SVector<f64, N>,
    qdd: &SVector<f64, N>,
) {
    // Y π sums P products: its rounding is some ε of |Y| |π| (2e-16 each,
    // 40 of them, 1e-14); 1e-13 of that scale.
    close(
        "τ against Y π",
        tau,
        &(y * pi),
        rounding_scale(y, pi),
        1e-13,
    );
    // M q̈ + nle = τ to the rounding of ABA's recursion (a few hundred
    // operations, each ε of the terms' scale |M| |q̈| + |nle| + |τ|):
    // 1e-12 of it.
    let scale = (m.abs() * qdd.abs()).amax() + nle.amax() + tau.amax();
    close("M q̈ + nle against τ", &(m * qdd + nle), tau, scale, 1e-12);
}

#[test]
fn changed_parameters_move_every_method_as_the_regressor_says() {
    let file = Tree::<f64>::new();
    let mut named = TreeParameters::<f64>::new();
    // A heavier wrist (its weight swapped for a 0.8 kg tool off its axis)
    // and a lighter arm, both rigid bodies (positive inertias about their
    // centres of mass that keep the triangle inequality).
    let tool = Matrix3::new(
        0.003, 0.0002, 0.0, 0.0002, 0.0025, -0.0001, 0.0, -0.0001, 0.0012,
    );
    named.wrist = parameters(1.4, Vector3::new(0.01, -0.02, 0.09), tool);
    named.arm = parameters(
        0.5,
        Vector3::new(0.0, 0.1, 0.01),
        Matrix3::from_diagonal(&Vector3::new(0.004, 0.0008, 0.0035)),
    );
    let mut pi = SVector::<f64, 40>::from_column_slice(&Tree::<f64>::PARAMETERS);
    pi.fixed_rows_mut::<10>(20).copy_from_slice(&named.wrist);
    pi.fixed_rows_mut::<10>(30).copy_from_slice(&named.arm);
    let mut moved = 0.0_f64;
    for [q, v, a] in spread::<4>(13, 40) {
        let tau = named.inverse_dynamics(&q, &v, &a);
        let m = named.mass_matrix(0.0, &q);
        let qdd = named.forward_dynamics(&q, &v, &tau);
        let nle = named.nonlinear_effects(&q, &v);
        consistent(&tau, &file.regressor(&q, &v, &a), &pi, &m, &nle, &qdd);
        moved = moved.max((tau - file.inverse_dynamics(&q, &v, &a)).amax() / tau.amax());
        // T = ½ q̇ᵀ M q̇, to rounding (1e-14 of T's terms).
        let t = named.kinetic_energy(0.0, &q, &v);
        let vmv = 0.5 * v.dot(&(m * v));
        let terms = 0.5 * v.abs().dot(&(m.abs() * v.abs()));
        assert!(
            (t - vmv).abs() < 1e-13 * terms,
            "T {t} against ½ vᵀ M v {vmv}"
        );
        // The gravity torques are ∂V/∂q: central differences at h = 1e-5,
        // truncation h² |∂³V| ~ 1e-10 of the torques, rounding ε |V| / h
        // ~ 1e-11 of them; compared to 1e-8 of the largest.
        let g = named.gravity_torques(&q);
        let h = 1e-5;
        let dv = SVector::<f64, 4>::from_fn(|i, _| {
            let mut e = SVector::<f64, 4>::zeros();
            e[i] = h;
            (named.potential_energy(0.0, &(q + e)) - named.potential_energy(0.0, &(q - e)))
                / (2.0 * h)
        });
        close("g against ∂V/∂q", &g, &dv, g.amax(), 1e-8);
    }
    // They moved the dynamics, by far more than any bound above.
    assert!(moved > 0.05, "τ moved by {moved:.2e} of itself");

    let file = Swimmer::<f64>::new();
    let mut named = SwimmerParameters::<f64>::new();
    named.trunk = parameters(
        4.2,
        Vector3::new(0.0, 0.03, 0.02),
        Matrix3::from_diagonal(&Vector3::new(0.06, 0.05, 0.03)),
    );
    named.fore = parameters(
        0.9,
        Vector3::new(0.12, 0.01, 0.0),
        Matrix3::from_diagonal(&Vector3::new(0.0003, 0.003, 0.0029)),
    );
    let mut pi = SVector::<f64, 30>::from_column_slice(&Swimmer::<f64>::PARAMETERS);
    pi.fixed_rows_mut::<10>(0).copy_from_slice(&named.trunk);
    pi.fixed_rows_mut::<10>(20).copy_from_slice(&named.fore);
    let mut moved = 0.0_f64;
    for (q, v, a) in floating_states(14, 40) {
        let tau = named.inverse_dynamics(&q, &v, &a);
        let m = named.velocity_mass_matrix(&q);
        let acc = named.forward_dynamics(&q, &v, &tau);
        let nle = named.nonlinear_effects(&q, &v);
        consistent(&tau, &file.regressor(&q, &v, &a), &pi, &m, &nle, &acc);
        moved = moved.max((tau - file.inverse_dynamics(&q, &v, &a)).amax() / tau.amax());
        // The base's force at rest is its weight, the trunk's and the
        // forearm's new masses in it, along the world's up in the base's
        // axes (to rounding).
        let g = named.gravity_torques(&q);
        let total = 4.2 + 0.7 + 0.9;
        let rot = UnitQuaternion::from_quaternion(Quaternion::new(q[3], q[4], q[5], q[6]));
        let weight = rot.inverse() * Vector3::new(0.0, 0.0, 9.81 * total);
        close(
            "the base's weight",
            &g.fixed_rows::<3>(0).into_owned(),
            &weight,
            weight.amax(),
            1e-14,
        );
    }
    assert!(moved > 0.05, "τ moved by {moved:.2e} of itself");
}
