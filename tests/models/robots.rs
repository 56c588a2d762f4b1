//! Robots from URDF (`#[lagrange(urdf = ..)]`): the recursions the macro
//! writes (RNEA, CRBA, ABA) against Pinocchio's at 100 random states of
//! each robot (`tests/data/robots/reference_*.json`, written once by
//! `tests/data/robots/reference.py`), and against the energy route: `M`
//! the Hessian of the kinetic energy, `f` the Euler–Lagrange equations of
//! `T − V`, both by differences of the energies the macro writes directly
//! (not by the recursions).
//!
//! Floating bases (the Go2, romeo_small) are compared in Pinocchio's
//! free-flyer coordinates: its configuration `(p, qx, qy, qz, qw, qⱼ)` is
//! ours `(p, qw, qx, qy, qz, qⱼ)` reordered, and its velocity (the base's
//! spatial velocity in the base frame, linear then angular, then the
//! joints') is the velocity `ν` our recursions take, so `M`, `nle`, `ν̇` and
//! `τ` compare entry by entry. The quaternion coordinates' own dynamics
//! (the `Lagrangian` in `q̇`, `|q| = 1` held by its constraint) are checked
//! through the map `ṗ = R v`, `q̇ = ½ q (0, ω)` and back
//! `ν̇ = (Rᵀ p̈ − ω × v, 2 Im(q̄ q̈), q̈ⱼ)`, written here with nalgebra's
//! quaternions.

use lagrange::nalgebra::{SMatrix, SVector};
use lagrange::prelude::*;
use lagrange::{Holonomic, Lagrangian};
use serde_json::Value;

lagrangian! {
    /// The UR5 of example-robot-data.
    #[lagrange(urdf = "tests/data/robots/ur5.urdf", regressor)]
    pub struct Ur5 {}
}

lagrangian! {
    /// The Panda of example-robot-data, its fingers locked closed.
    #[lagrange(urdf = "tests/data/robots/panda.urdf", regressor)]
    pub struct Panda {
        locked: panda_finger_joint1 = 0.0, panda_finger_joint2 = 0.0;
    }
}

lagrangian! {
    /// The xArm7 of example-robot-data.
    #[lagrange(urdf = "tests/data/robots/xarm7.urdf")]
    pub struct Xarm7 {}
}

lagrangian! {
    /// The Unitree Go2 of example-robot-data on a floating base.
    #[lagrange(urdf = "tests/data/robots/go2.urdf", floating, regressor)]
    pub struct Go2 {}
}

lagrangian! {
    /// The romeo_small humanoid of example-robot-data (31 joints) on a
    /// floating base.
    #[lagrange(urdf = "tests/data/robots/romeo_small.urdf", floating)]
    pub struct Romeo {}
}

lagrangian! {
    /// A tree of four joints on unaligned axes, one prismatic.
    #[lagrange(urdf = "tests/data/robots/tree.urdf", regressor)]
    pub struct Tree {}
}

// The same robots written as bodies and joints in the macro's input (no
// file), their numbers copied from the URDFs: each `<inertial>` a body's
// `mass`, `com`, `axes` (its `rpy`) and `inertia`, each `<origin>`
// `translate(xyz) * rotate_rpy(rpy)`. `base` is the world, so the files'
// `world` is `base` and the UR5's own `base` frame is `base_frame`.

lagrangian! {
    /// The UR5 written as bodies and joints, from the numbers of `ur5.urdf`.
    pub struct Ur5Written {
        bodies:
            base_link: mass 4.0, inertia diag(0.00443333156, 0.00443333156, 0.0072);
            shoulder_link: mass 3.7, inertia diag(0.010267495893, 0.010267495893, 0.00666);
            upper_arm_link: mass 8.393, com [0.0, 0.0, 0.28], inertia diag(0.22689067591, 0.22689067591, 0.0151074);
            forearm_link: mass 2.275, com [0.0, 0.0, 0.25], inertia diag(0.049443313556, 0.049443313556, 0.004095);
            wrist_1_link: mass 1.219, inertia diag(0.111172755531, 0.111172755531, 0.21942);
            wrist_2_link: mass 1.219, inertia diag(0.111172755531, 0.111172755531, 0.21942);
            wrist_3_link: mass 0.1879, inertia diag(0.0171364731454, 0.0171364731454, 0.033822);
            ee_link;
            base_frame;
            tool0;
        joints:
            shoulder_pan_joint: revolute base_link -> shoulder_link, at translate(0.0, 0.0, 0.089159), axis [0, 0, 1];
            shoulder_lift_joint: revolute shoulder_link -> upper_arm_link,
                at translate(0.0, 0.13585, 0.0) * rotate_rpy(0.0, 1.57079632679, 0.0), axis [0, 1, 0];
            elbow_joint: revolute upper_arm_link -> forearm_link, at translate(0.0, -0.1197, 0.425), axis [0, 1, 0];
            wrist_1_joint: revolute forearm_link -> wrist_1_link,
                at translate(0.0, 0.0, 0.39225) * rotate_rpy(0.0, 1.57079632679, 0.0), axis [0, 1, 0];
            wrist_2_joint: revolute wrist_1_link -> wrist_2_link, at translate(0.0, 0.093, 0.0), axis [0, 0, 1];
            wrist_3_joint: revolute wrist_2_link -> wrist_3_link, at translate(0.0, 0.0, 0.09465), axis [0, 1, 0];
            ee_fixed_joint: fixed wrist_3_link -> ee_link, at translate(0.0, 0.0823, 0.0) * rotate_rpy(0.0, 0.0, 1.57079632679);
            base_fixed_joint: fixed base_link -> base_frame, at rotate_rpy(0, 0, -3.14159265359);
            tool0_fixed_joint: fixed wrist_3_link -> tool0, at translate(0, 0.0823, 0) * rotate_rpy(-1.57079632679, 0, 0);
            world_joint: fixed base -> base_link;
    }
}

lagrangian! {
    /// `tree.urdf` written as bodies and joints: unaligned axes, a
    /// prismatic joint, a mass on a fixed joint, a massless tool frame.
    pub struct TreeWritten {
        bodies:
            hub: mass 2.5, com [0.02, -0.01, 0.11], axes rotate_rpy(0.1, -0.2, 0.3),
                 inertia [[0.031, 0.002, -0.001], [0.002, 0.027, 0.003], [-0.001, 0.003, 0.019]];
            slider: mass 1.2, com [0.1, 0.02, 0.0], inertia [[0.004, 0, 0.0005], [0, 0.011, 0], [0.0005, 0, 0.012]];
            wrist: mass 0.6, com [0, 0, 0.07], inertia [[0.002, 0.0001, 0], [0.0001, 0.0021, 0], [0, 0, 0.0009]];
            weight: mass 0.3, inertia diag(0.0003, 0.0003, 0.0003);
            tool;
            arm: mass 0.9, com [0, 0.12, 0], axes rotate_rpy(0, 0.3, 0), inertia diag(0.006, 0.001, 0.0055);
        joints:
            a_yaw: revolute base -> hub, at translate(0.05, 0, 0.2) * rotate_rpy(0, 0, 0.4), axis [0.1, 0.2, 0.97];
            b_slide: prismatic hub -> slider, at translate(0, 0.03, 0.25) * rotate_rpy(0.3, 0.5, -0.2), axis [0.8, 0, 0.6];
            c_wrist: revolute slider -> wrist, at translate(0.2, 0, 0) * rotate_x(PI / 2), axis [0, 1, 0];
            weight_mount: fixed wrist -> weight, at translate(0.03, -0.02, 0.12) * rotate_rpy(0.2, 0, 0);
            tool_frame: fixed weight -> tool, at translate(0, 0, 0.05);
            d_arm: revolute hub -> arm, at translate(0.04, 0, 0.15) * rotate_rpy(-0.4, 0.1, 1.1), axis [0.6, -0.48, 0.64];
    }
}

lagrangian! {
    /// The Go2 written as bodies and joints on a floating base, from the
    /// numbers of `go2.urdf` (its `base` link is `trunk`).
    pub struct Go2Written {
        bodies:
            trunk: mass 6.921, com [0.021112, 0, -0.005366], inertia [[0.02448, 0.00012166, 0.0014849], [0.00012166, 0.098077, -3.12E-05], [0.0014849, -3.12E-05, 0.107]];
            FL_hip: mass 0.678, com [-0.0054, 0.00194, -0.000105], inertia [[0.00048, -3.01E-06, 1.11E-06], [-3.01E-06, 0.000884, -1.42E-06], [1.11E-06, -1.42E-06, 0.000596]];
            FL_hip_rotor: mass 0.089, inertia diag(0.000111842, 0.000059647, 0.000059647);
            FL_thigh: mass 1.152, com [-0.00374, -0.0223, -0.0327], inertia [[0.00584, 8.72E-05, -0.000289], [8.72E-05, 0.0058, 0.000808], [-0.000289, 0.000808, 0.00103]];
            FL_thigh_rotor: mass 0.089, inertia diag(0.000059647, 0.000111842, 0.000059647);
            FL_calf: mass 0.154, com [0.00548, -0.000975, -0.115], inertia [[0.00108, 3.4E-07, 1.72E-05], [3.4E-07, 0.0011, 8.28E-06], [1.72E-05, 8.28E-06, 3.29E-05]];
            FL_calf_rotor: mass 0.089, inertia diag(0.000059647, 0.000111842, 0.000059647);
            FL_foot: mass 0.04, inertia diag(9.6e-06, 9.6e-06, 9.6e-06);
            FR_hip: mass 0.678, com [-0.0054, -0.00194, -0.000105], inertia [[0.00048, 3.01E-06, 1.11E-06], [3.01E-06, 0.000884, 1.42E-06], [1.11E-06, 1.42E-06, 0.000596]];
            FR_hip_rotor: mass 0.089, inertia diag(0.000111842, 0.000059647, 0.000059647);
            FR_thigh: mass 1.152, com [-0.00374, 0.0223, -0.0327], inertia [[0.00584, -8.72E-05, -0.000289], [-8.72E-05, 0.0058, -0.000808], [-0.000289, -0.000808, 0.00103]];
            FR_thigh_rotor: mass 0.089, inertia diag(0.000059647, 0.000111842, 0.000059647);
            FR_calf: mass 0.154, com [0.00548, 0.000975, -0.115], inertia [[0.00108, -3.4E-07, 1.72E-05], [-3.4E-07, 0.0011, -8.28E-06], [1.72E-05, -8.28E-06, 3.29E-05]];
            FR_calf_rotor: mass 0.089, inertia diag(0.000059647, 0.000111842, 0.000059647);
            FR_foot: mass 0.04, inertia diag(9.6e-06, 9.6e-06, 9.6e-06);
            RL_hip: mass 0.678, com [0.0054, 0.00194, -0.000105], inertia [[0.00048, 3.01E-06, -1.11E-06], [3.01E-06, 0.000884, -1.42E-06], [-1.11E-06, -1.42E-06, 0.000596]];
            RL_hip_rotor: mass 0.089, inertia diag(0.000111842, 0.000059647, 0.000059647);
            RL_thigh: mass 1.152, com [-0.00374, -0.0223, -0.0327], inertia [[0.00584, 8.72E-05, -0.000289], [8.72E-05, 0.0058, 0.000808], [-0.000289, 0.000808, 0.00103]];
            RL_thigh_rotor: mass 0.089, inertia diag(0.000059647, 0.000111842, 0.000059647);
            RL_calf: mass 0.154, com [0.00548, -0.000975, -0.115], inertia [[0.00108, 3.4E-07, 1.72E-05], [3.4E-07, 0.0011, 8.28E-06], [1.72E-05, 8.28E-06, 3.29E-05]];
            RL_calf_rotor: mass 0.089, inertia diag(0.000059647, 0.000111842, 0.000059647);
            RL_foot: mass 0.04, inertia diag(9.6e-06, 9.6e-06, 9.6e-06);
            RR_hip: mass 0.678, com [0.0054, -0.00194, -0.000105], inertia [[0.00048, -3.01E-06, -1.11E-06], [-3.01E-06, 0.000884, 1.42E-06], [-1.11E-06, 1.42E-06, 0.000596]];
            RR_hip_rotor: mass 0.089, inertia diag(0.000111842, 0.000059647, 0.000059647);
            RR_thigh: mass 1.152, com [-0.00374, 0.0223, -0.0327], inertia [[0.00584, -8.72E-05, -0.000289], [-8.72E-05, 0.0058, -0.000808], [-0.000289, -0.000808, 0.00103]];
            RR_thigh_rotor: mass 0.089, inertia diag(0.000059647, 0.000111842, 0.000059647);
            RR_calf: mass 0.154, com [0.00548, 0.000975, -0.115], inertia [[0.00108, -3.4E-07, 1.72E-05], [-3.4E-07, 0.0011, -8.28E-06], [1.72E-05, -8.28E-06, 3.29E-05]];
            RR_calf_rotor: mass 0.089, inertia diag(0.000059647, 0.000111842, 0.000059647);
            RR_foot: mass 0.04, inertia diag(9.6e-06, 9.6e-06, 9.6e-06);
            imu;
            radar;
        joints:
            free: floating base -> trunk;
            FL_hip_joint: revolute trunk -> FL_hip, at translate(0.1934, 0.0465, 0), axis [1, 0, 0];
            FL_hip_rotor_joint: fixed trunk -> FL_hip_rotor, at translate(0.11215, 0.04675, 0);
            FL_thigh_joint: revolute FL_hip -> FL_thigh, at translate(0, 0.0955, 0), axis [0, 1, 0];
            FL_thigh_rotor_joint: fixed FL_hip -> FL_thigh_rotor, at translate(0, -0.00015, 0);
            FL_calf_joint: revolute FL_thigh -> FL_calf, at translate(0, 0, -0.213), axis [0, 1, 0];
            FL_calf_rotor_joint: fixed FL_thigh -> FL_calf_rotor, at translate(0, -0.03235, 0);
            FL_foot_joint: fixed FL_calf -> FL_foot, at translate(0, 0, -0.213);
            FR_hip_joint: revolute trunk -> FR_hip, at translate(0.1934, -0.0465, 0), axis [1, 0, 0];
            FR_hip_rotor_joint: fixed trunk -> FR_hip_rotor, at translate(0.11215, -0.04675, 0);
            FR_thigh_joint: revolute FR_hip -> FR_thigh, at translate(0, -0.0955, 0), axis [0, 1, 0];
            FR_thigh_rotor_joint: fixed FR_hip -> FR_thigh_rotor, at translate(0, 0.00015, 0);
            FR_calf_joint: revolute FR_thigh -> FR_calf, at translate(0, 0, -0.213), axis [0, 1, 0];
            FR_calf_rotor_joint: fixed FR_thigh -> FR_calf_rotor, at translate(0, 0.03235, 0);
            FR_foot_joint: fixed FR_calf -> FR_foot, at translate(0, 0, -0.213);
            RL_hip_joint: revolute trunk -> RL_hip, at translate(-0.1934, 0.0465, 0), axis [1, 0, 0];
            RL_hip_rotor_joint: fixed trunk -> RL_hip_rotor, at translate(-0.11215, 0.04675, 0);
            RL_thigh_joint: revolute RL_hip -> RL_thigh, at translate(0, 0.0955, 0), axis [0, 1, 0];
            RL_thigh_rotor_joint: fixed RL_hip -> RL_thigh_rotor, at translate(0, -0.00015, 0);
            RL_calf_joint: revolute RL_thigh -> RL_calf, at translate(0, 0, -0.213), axis [0, 1, 0];
            RL_calf_rotor_joint: fixed RL_thigh -> RL_calf_rotor, at translate(0, -0.03235, 0);
            RL_foot_joint: fixed RL_calf -> RL_foot, at translate(0, 0, -0.213);
            RR_hip_joint: revolute trunk -> RR_hip, at translate(-0.1934, -0.0465, 0), axis [1, 0, 0];
            RR_hip_rotor_joint: fixed trunk -> RR_hip_rotor, at translate(-0.11215, -0.04675, 0);
            RR_thigh_joint: revolute RR_hip -> RR_thigh, at translate(0, -0.0955, 0), axis [0, 1, 0];
            RR_thigh_rotor_joint: fixed RR_hip -> RR_thigh_rotor, at translate(0, 0.00015, 0);
            RR_calf_joint: revolute RR_thigh -> RR_calf, at translate(0, 0, -0.213), axis [0, 1, 0];
            RR_calf_rotor_joint: fixed RR_thigh -> RR_calf_rotor, at translate(0, 0.03235, 0);
            RR_foot_joint: fixed RR_calf -> RR_foot, at translate(0, 0, -0.213);
            imu_joint: fixed trunk -> imu, at translate(-0.02557, 0, 0.04232);
            radar_joint: fixed trunk -> radar, at translate(0.28945, 0, -0.046825) * rotate_rpy(0, 2.8782, 0);
    }
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
    fn solve(&self, m: &SMatrix<f64, N, N>, b: &SVector<f64, N>) -> Option<SVector<f64, N>>;
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
            fn solve(
                &self,
                m: &SMatrix<f64, $n, $n>,
                b: &SVector<f64, $n>,
            ) -> Option<SVector<f64, $n>> {
                self.solve_mass_matrix(m, b)
            }
        }
    };
}
robot!(Ur5, 6);
robot!(Panda, 7);
robot!(Tree, 4);
robot!(Xarm7, 7);
robot!(Ur5Written, 6);
robot!(TreeWritten, 4);

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
fn xarm7_matches_pinocchio() {
    check(&Xarm7::new(), "reference_xarm7.json");
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

/// What a robot on a floating base is asked: `NQ` coordinates, `NV`
/// velocities.
trait FloatingRobot<const NQ: usize, const NV: usize>:
    Holonomic<NQ, 1, Scalar = f64> + Lagrangian<NQ, Scalar = f64>
{
    const JOINTS: &'static [&'static str];
    fn m(&self, q: &SVector<f64, NQ>) -> SMatrix<f64, NV, NV>;
    fn nle(&self, q: &SVector<f64, NQ>, v: &SVector<f64, NV>) -> SVector<f64, NV>;
    fn aba(
        &self,
        q: &SVector<f64, NQ>,
        v: &SVector<f64, NV>,
        tau: &SVector<f64, NV>,
    ) -> SVector<f64, NV>;
    fn rnea(
        &self,
        q: &SVector<f64, NQ>,
        v: &SVector<f64, NV>,
        a: &SVector<f64, NV>,
    ) -> SVector<f64, NV>;
    fn rates(&self, q: &SVector<f64, NQ>, v: &SVector<f64, NV>) -> SVector<f64, NQ>;
    fn solve(&self, m: &SMatrix<f64, NV, NV>, b: &SVector<f64, NV>) -> Option<SVector<f64, NV>>;
}

macro_rules! floating_robot {
    ($t:ty, $nq:literal, $nv:literal) => {
        impl FloatingRobot<$nq, $nv> for $t {
            const JOINTS: &'static [&'static str] = {
                let (_, joints) = <$t>::COORDINATES.split_at(7);
                joints
            };
            fn m(&self, q: &SVector<f64, $nq>) -> SMatrix<f64, $nv, $nv> {
                self.velocity_mass_matrix(q)
            }
            fn nle(&self, q: &SVector<f64, $nq>, v: &SVector<f64, $nv>) -> SVector<f64, $nv> {
                self.nonlinear_effects(q, v)
            }
            fn aba(
                &self,
                q: &SVector<f64, $nq>,
                v: &SVector<f64, $nv>,
                tau: &SVector<f64, $nv>,
            ) -> SVector<f64, $nv> {
                self.forward_dynamics(q, v, tau)
            }
            fn rnea(
                &self,
                q: &SVector<f64, $nq>,
                v: &SVector<f64, $nv>,
                a: &SVector<f64, $nv>,
            ) -> SVector<f64, $nv> {
                self.inverse_dynamics(q, v, a)
            }
            fn rates(&self, q: &SVector<f64, $nq>, v: &SVector<f64, $nv>) -> SVector<f64, $nq> {
                <$t>::rates(self, q, v)
            }
            fn solve(
                &self,
                m: &SMatrix<f64, $nv, $nv>,
                b: &SVector<f64, $nv>,
            ) -> Option<SVector<f64, $nv>> {
                self.solve_velocity_mass_matrix(m, b)
            }
        }
    };
}
floating_robot!(Go2, 19, 18);
floating_robot!(Romeo, 38, 37);
floating_robot!(Go2Written, 19, 18);

/// Pinocchio's free-flyer configuration in our order: the quaternion's
/// `(x, y, z, w)` to `(w, x, y, z)`.
pub(super) fn from_pinocchio<const NQ: usize>(q: &SVector<f64, NQ>) -> SVector<f64, NQ> {
    let mut ours = *q;
    ours[3] = q[6];
    ours[4] = q[3];
    ours[5] = q[4];
    ours[6] = q[5];
    ours
}

/// `ν̇` of the coordinates' accelerations `q̈` at `(q, ν)`: `Rᵀ p̈ − ω × v`,
/// `2 Im(q̄ q̈)`, the joints' `q̈`.
fn velocity_accelerations<const NQ: usize, const NV: usize>(
    q: &SVector<f64, NQ>,
    v: &SVector<f64, NV>,
    qdd: &SVector<f64, NQ>,
) -> SVector<f64, NV> {
    use lagrange::nalgebra::{Quaternion, UnitQuaternion, Vector3};
    let quat = Quaternion::new(q[3], q[4], q[5], q[6]);
    let rot = UnitQuaternion::from_quaternion(quat);
    let (lin, w) = (
        Vector3::new(v[0], v[1], v[2]),
        Vector3::new(v[3], v[4], v[5]),
    );
    let pdd = Vector3::new(qdd[0], qdd[1], qdd[2]);
    let a_lin = rot.inverse() * pdd - w.cross(&lin);
    let a_ang = (quat.conjugate() * Quaternion::new(qdd[3], qdd[4], qdd[5], qdd[6])).imag() * 2.0;
    SVector::from_fn(|i, _| match i {
        0..3 => a_lin[i],
        3..6 => a_ang[i - 3],
        _ => qdd[i + 1],
    })
}

/// The floating base's checks at every recorded state: the worst relative
/// errors of M, nle, ABA's ν̇ and RNEA's τ in Pinocchio's velocities; and
/// of the quaternion coordinates' dynamics: `T(q, q̇)` against
/// `½ νᵀ M ν`, and `q̈` of the saddle-point system (`M_q`, `f_q`, `G`, `γ`)
/// mapped to `ν̇` against Pinocchio's unforced `M⁻¹ (−nle)`.
fn floating_against_pinocchio<R: FloatingRobot<NQ, NV>, const NQ: usize, const NV: usize>(
    robot: &R,
    file: &str,
) -> [f64; 6] {
    let path = format!("{}/tests/data/robots/{file}", env!("CARGO_MANIFEST_DIR"));
    let json: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let joints: Vec<&str> = json["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j.as_str().unwrap())
        .collect();
    // Pinocchio orders a link's children by their joints' names (urdfdom's
    // map), ours by the file: the same joints, romeo's neck and arms in
    // another order. `pin[k]`: Pinocchio's index of our joint `k`.
    let mut sorted = joints.clone();
    sorted.sort_unstable();
    let mut ours = R::JOINTS.to_vec();
    ours.sort_unstable();
    assert_eq!(sorted, ours, "the joints are Pinocchio's");
    let pin: Vec<usize> = R::JOINTS
        .iter()
        .map(|j| joints.iter().position(|p| p == j).unwrap())
        .collect();
    // Pinocchio's index of our entry `i` of a configuration (the base's 7
    // first) or a velocity (the base's 6 first).
    let at_q = |i: usize| if i < 7 { i } else { 7 + pin[i - 7] };
    let at_v = |i: usize| if i < 6 { i } else { 6 + pin[i - 6] };
    let velocity = |x: &Value| {
        let x = vector::<NV>(x);
        SVector::<f64, NV>::from_fn(|i, _| x[at_v(i)])
    };
    let states = json["states"].as_array().unwrap();
    assert_eq!(states.len(), 100);
    let mut worst = [0.0f64; 6];
    for s in states {
        let q_pin = vector::<NQ>(&s["q"]);
        let q = from_pinocchio(&SVector::<f64, NQ>::from_fn(|i, _| q_pin[at_q(i)]));
        let (v, a, tau) = (velocity(&s["v"]), velocity(&s["a"]), velocity(&s["tau"]));
        // The upper triangle, row by row.
        let upper = vector_of(&s["mass_matrix_upper"]);
        let mut m_pin = SMatrix::<f64, NV, NV>::zeros();
        let mut k = 0;
        for i in 0..NV {
            for j in i..NV {
                m_pin[(i, j)] = upper[k];
                m_pin[(j, i)] = upper[k];
                k += 1;
            }
        }
        let m_ref = SMatrix::<f64, NV, NV>::from_fn(|i, j| m_pin[(at_v(i), at_v(j))]);
        let nle_ref = velocity(&s["nonlinear_effects"]);
        // The quaternion coordinates: rates of Pinocchio's velocity, the
        // saddle-point system [[M, Gᵀ], [G, 0]] solved whole (LU).
        let qdot = robot.rates(&q, &v);
        let kinetic = robot.kinetic_energy(0.0, &q, &qdot);
        let kinetic_ref = 0.5 * v.dot(&(m_ref * v));
        let (mq, fq) = robot.mass_matrix_and_forcing(0.0, &q, &qdot);
        let g = robot.constraint_jacobian(0.0, &q);
        let gamma = robot.constraint_bias(0.0, &q, &qdot);
        let mut kkt = lagrange::nalgebra::DMatrix::<f64>::zeros(NQ + 1, NQ + 1);
        let mut rhs = lagrange::nalgebra::DVector::<f64>::zeros(NQ + 1);
        for i in 0..NQ {
            for j in 0..NQ {
                kkt[(i, j)] = mq[(i, j)];
            }
            kkt[(i, NQ)] = g[i];
            kkt[(NQ, i)] = g[i];
            rhs[i] = fq[i];
        }
        rhs[NQ] = -gamma[0];
        let x = kkt.lu().solve(&rhs).unwrap();
        let qdd = SVector::<f64, NQ>::from_fn(|i, _| x[i]);
        let unforced_ref = m_ref.cholesky().unwrap().solve(&(-nle_ref));
        let errors = [
            relative(robot.m(&q).as_slice(), m_ref.as_slice()),
            relative(robot.nle(&q, &v).as_slice(), nle_ref.as_slice()),
            relative(
                robot.aba(&q, &v, &tau).as_slice(),
                velocity(&s["aba"]).as_slice(),
            ),
            relative(
                robot.rnea(&q, &v, &a).as_slice(),
                velocity(&s["rnea"]).as_slice(),
            ),
            (kinetic - kinetic_ref).abs() / kinetic_ref,
            relative(
                velocity_accelerations(&q, &v, &qdd).as_slice(),
                unforced_ref.as_slice(),
            ),
        ];
        for (w, e) in worst.iter_mut().zip(errors) {
            *w = w.max(e);
        }
    }
    worst
}

fn vector_of(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

// M, nle, ν̇ and τ: TOLERANCE, for the reasons given there (the base's 6 × 6
// solve in ABA is one more Cholesky of a well-conditioned block). The
// quaternion coordinates' q̈ comes from a second route (our M_q and f_q,
// the saddle-point system by LU, M's condition entering twice) against
// Pinocchio's M⁻¹(−nle) solved here: 1e-9 of its largest entry, still a
// millionth of what a wrong sign or factor in the map shows.
const MAP_TOLERANCE: f64 = 1e-9;

fn check_floating<R: FloatingRobot<NQ, NV>, const NQ: usize, const NV: usize>(
    robot: &R,
    file: &str,
) {
    let worst = floating_against_pinocchio(robot, file);
    println!(
        "{file}: M {:.1e}, nle {:.1e}, aba {:.1e}, rnea {:.1e}; in q̇: T {:.1e}, q̈ {:.1e}",
        worst[0], worst[1], worst[2], worst[3], worst[4], worst[5]
    );
    for (k, (what, e)) in [
        "M",
        "nonlinear effects",
        "ABA's ν̇",
        "RNEA's τ",
        "T in the quaternion's rates",
        "q̈ of the quaternion coordinates",
    ]
    .iter()
    .zip(worst)
    .enumerate()
    {
        let tolerance = if k < 5 { TOLERANCE } else { MAP_TOLERANCE };
        assert!(
            e < tolerance,
            "{file}: {what} off Pinocchio's by {e:e} of its largest entry"
        );
    }
}

#[test]
fn go2_on_a_floating_base_matches_pinocchio() {
    check_floating(&Go2::new(), "reference_go2.json");
}

#[test]
fn romeo_humanoid_on_a_floating_base_matches_pinocchio() {
    check_floating(&Romeo::new(), "reference_romeo.json");
}

/// A run of the Go2 falling free, tumbling, its legs swinging: the energy
/// `T + V` kept and `|q| = 1` held, through the runtime's constrained
/// right-hand side (the quaternion's norm a `Holonomic` constraint, as a
/// free body's is).
#[test]
fn go2_falls_keeping_its_energy_and_unit_quaternion() {
    use lagrange::nalgebra::{Quaternion, UnitQuaternion};
    let go2 = Go2::new();
    let turn = UnitQuaternion::from_euler_angles(0.3, -0.5, 1.1);
    let quat: &Quaternion<f64> = turn.as_ref();
    let mut q = SVector::<f64, 19>::zeros();
    q[2] = 0.5;
    (q[3], q[4], q[5], q[6]) = (quat.w, quat.i, quat.j, quat.k);
    for k in 7..19 {
        q[k] = 0.4 * ((k * 5) % 7) as f64 / 7.0 - 0.2;
    }
    let v = SVector::<f64, 18>::from_fn(|i, _| 0.8 * ((i * 3) % 5) as f64 / 5.0 - 0.4);
    let qdot = go2.rates(&q, &v);
    let energy = |q: &SVector<f64, 19>, qd: &SVector<f64, 19>| {
        go2.kinetic_energy(0.0, q, qd) + go2.potential_energy(0.0, q)
    };
    let e0 = energy(&q, &qdot);
    let run = Dop853::new()
        .rtol(1e-10)
        .atol(1e-10)
        .integrate(&go2, 0.0, q, qdot, &[0.3])
        .unwrap();
    let end = run.last().unwrap();
    // The tolerance 1e-10 per step over some hundred steps: the energy to
    // 1e-7 of the robot's energy scale (its weight times a metre, ~150 J).
    let scale = 15.0 * 9.81;
    assert!(
        (energy(&end.q, &end.qdot) - e0).abs() < 1e-7 * scale,
        "energy {} against {e0}",
        energy(&end.q, &end.qdot)
    );
    let norm = end.q.fixed_rows::<4>(3).norm();
    assert!((norm - 1.0).abs() < 1e-12, "|q| = {norm}");
    // It fell: gravity acts on the base's height.
    assert!(end.q[2] < 0.5 - 0.3 * 0.3, "height {}", end.q[2]);
}

/// States spread over the joints' ranges: angles and displacements in
/// `[-2, 2]`, rates and accelerations in `[-3, 3]` (SplitMix64, seeded).
pub(super) fn spread<const N: usize>(seed: u64, count: usize) -> Vec<[SVector<f64, N>; 3]> {
    let mut state = seed;
    let mut next = move || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..count)
        .map(|_| {
            let q = SVector::from_fn(|_, _| 2.0 * next());
            let v = SVector::from_fn(|_, _| 3.0 * next());
            let a = SVector::from_fn(|_, _| 3.0 * next());
            [q, v, a]
        })
        .collect()
}

/// Two robots whose trees are the same give the same bits: the robot
/// written in the language is read into the URDF route's links and
/// joints, and from there the code is that route's.
fn same_bits<A: Robot<N>, B: Robot<N>, const N: usize>(written: &A, file: &B) {
    assert_eq!(A::NAMES, B::NAMES);
    for [q, v, a] in spread::<N>(7, 50) {
        assert_eq!(written.m(&q), file.m(&q));
        assert_eq!(written.nle(&q, &v), file.nle(&q, &v));
        assert_eq!(written.aba(&q, &v, &a), file.aba(&q, &v, &a));
        assert_eq!(written.rnea(&q, &v, &a), file.rnea(&q, &v, &a));
    }
}

#[test]
fn ur5_written_as_bodies_and_joints_is_its_urdf_bit_for_bit() {
    same_bits(&Ur5Written::new(), &Ur5::new());
    check(&Ur5Written::new(), "reference_ur5.json");
    // Its frames come with it: the tool frame's placement and Jacobian.
    let (written, file) = (Ur5Written::<f64>::new(), Ur5::<f64>::new());
    let (a, b) = (
        Ur5Written::<f64>::frame_index("tool0").unwrap(),
        Ur5::<f64>::frame_index("tool0").unwrap(),
    );
    for [q, _, _] in spread::<6>(8, 10) {
        assert_eq!(written.frame_placement(&q, a), file.frame_placement(&q, b));
        assert_eq!(written.frame_jacobian(&q, a), file.frame_jacobian(&q, b));
    }
}

#[test]
fn tree_written_as_bodies_and_joints_is_its_urdf_bit_for_bit() {
    same_bits(&TreeWritten::new(), &Tree::new());
    check(&TreeWritten::new(), "reference_tree.json");
}

/// The Go2 written on a floating base: the recursions in `ν` and the
/// `Lagrangian` in the quaternion's rates, bit for bit the URDF's.
#[test]
fn go2_written_as_bodies_and_joints_is_its_urdf_bit_for_bit() {
    let (written, file) = (Go2Written::new(), Go2::new());
    assert_eq!(Go2Written::<f64>::COORDINATES, Go2::<f64>::COORDINATES);
    for (k, [p, v, a]) in spread::<18>(9, 30).into_iter().enumerate() {
        let mut q = SVector::<f64, 19>::zeros();
        q.fixed_rows_mut::<3>(0).copy_from(&p.fixed_rows::<3>(0));
        let quat =
            SVector::<f64, 4>::new(1.0, 0.3 * p[3], -0.2 * p[4], 0.1 * p[5] + 0.01 * k as f64)
                .normalize();
        q.fixed_rows_mut::<4>(3).copy_from(&quat);
        q.fixed_rows_mut::<12>(7).copy_from(&p.fixed_rows::<12>(6));
        assert_eq!(written.m(&q), file.m(&q));
        assert_eq!(written.nle(&q, &v), file.nle(&q, &v));
        assert_eq!(written.aba(&q, &v, &a), file.aba(&q, &v, &a));
        assert_eq!(written.rnea(&q, &v, &a), file.rnea(&q, &v, &a));
        let qdot = file.rates(&q, &v);
        assert_eq!(written.mass_matrix(0.0, &q), file.mass_matrix(0.0, &q));
        assert_eq!(
            Lagrangian::forcing(&written, 0.0, &q, &qdot),
            Lagrangian::forcing(&file, 0.0, &q, &qdot)
        );
    }
    check_floating(&written, "reference_go2.json");
}

/// The emitted sparse solve's `x = M⁻¹ (τ − nle)` against the dense
/// Cholesky solve of the same `M` and against ABA's `q̈(q, q̇, τ)`, at
/// spread states; returns the worst error over the bound below.
///
/// The bound: each of the three is backward stable, so its forward error
/// is at most `c N ε κ(M) |x|` (`κ` the 2-norm condition number, `c` a
/// small constant from the sums' lengths, `N` terms each); ABA also forms
/// its bias forces in another order than RNEA's `nle`, an error
/// `~ N ε |τ − nle|` in the right-hand side, which `M⁻¹` amplifies by at
/// most `κ(M) |x| / |τ − nle|`: the same form. `10 N ε κ(M) |x|_∞` in the
/// max norm (`√N` from the 2-norm absorbed in the 10) holds both.
fn solve_against_dense_and_aba<const N: usize>(
    states: impl Iterator<Item = (SMatrix<f64, N, N>, SVector<f64, N>, SVector<f64, N>)>,
    solve: impl Fn(&SMatrix<f64, N, N>, &SVector<f64, N>) -> Option<SVector<f64, N>>,
    name: &str,
) -> f64 {
    let mut worst = 0.0f64;
    for (m, b, aba) in states {
        let x = solve(&m, &b).unwrap_or_else(|| panic!("{name}: the solve refused a regular M"));
        let dense = m.cholesky().expect("M is positive definite").solve(&b);
        let eigen = lagrange::nalgebra::DMatrix::from_column_slice(N, N, m.as_slice())
            .symmetric_eigenvalues();
        let kappa = eigen.max() / eigen.min();
        let bound = 10.0 * N as f64 * f64::EPSILON * kappa * dense.amax();
        for reference in [dense, aba] {
            worst = worst.max((x - reference).amax() / bound);
        }
    }
    worst
}

/// The generated `solve_mass_matrix` (Featherstone's sparse `Lᵀ D L`
/// unrolled over the tree) against the dense solve and ABA on every
/// fixed-base robot; `None`, never a NaN, where `M` is not positive
/// definite or has a NaN.
#[test]
fn emitted_solve_matches_the_dense_solve_and_aba() {
    fn fixed<R: Robot<N>, const N: usize>(robot: &R, name: &str) {
        let states = spread::<N>(11, 40).into_iter().map(|[q, v, tau]| {
            let m = robot.m(&q);
            (m, tau - robot.nle(&q, &v), robot.aba(&q, &v, &tau))
        });
        let worst = solve_against_dense_and_aba(states, |m, b| robot.solve(m, b), name);
        println!("{name}: worst error {worst:.1e} of the bound");
        assert!(worst <= 1.0, "{name}: {worst} of the bound");
        // Refusals: a pivot negative, a NaN entry the solve reads.
        let [q, _, b] = spread::<N>(12, 1)[0];
        let mut m = robot.m(&q);
        m[(0, 0)] = -m[(0, 0)];
        assert_eq!(robot.solve(&m, &b), None, "{name}: indefinite");
        let mut m = robot.m(&q);
        m[(N - 1, 0)] = f64::NAN;
        assert_eq!(robot.solve(&m, &b), None, "{name}: NaN");
    }
    fixed(&Ur5::new(), "ur5");
    fixed(&Panda::new(), "panda");
    fixed(&Xarm7::new(), "xarm7");
    fixed(&Tree::new(), "tree");
}

/// The same on the floating bases, in the velocities `ν`: the Go2 and
/// romeo_small (37 velocities).
#[test]
fn emitted_velocity_solve_matches_the_dense_solve_and_aba() {
    fn floating<R: FloatingRobot<NQ, NV>, const NQ: usize, const NV: usize>(robot: &R, name: &str) {
        let states = spread::<NV>(13, 40).into_iter().map(|[p, v, tau]| {
            let mut q = SVector::<f64, NQ>::zeros();
            q.fixed_rows_mut::<3>(0).copy_from(&p.fixed_rows::<3>(0));
            let quat = SVector::<f64, 4>::new(1.0, p[3], p[4], p[5]).normalize();
            q.fixed_rows_mut::<4>(3).copy_from(&quat);
            for k in 6..NV {
                q[k + 1] = p[k];
            }
            let m = robot.m(&q);
            (m, tau - robot.nle(&q, &v), robot.aba(&q, &v, &tau))
        });
        let worst = solve_against_dense_and_aba(states, |m, b| robot.solve(m, b), name);
        println!("{name}: worst error {worst:.1e} of the bound");
        assert!(worst <= 1.0, "{name}: {worst} of the bound");
        let mut q = SVector::<f64, NQ>::zeros();
        q[3] = 1.0;
        let m = robot.m(&q);
        let b = SVector::<f64, NV>::from_fn(|i, _| (i as f64).sin());
        let mut bad = m;
        bad[(NV - 1, NV - 1)] = -bad[(NV - 1, NV - 1)];
        assert_eq!(robot.solve(&bad, &b), None, "{name}: indefinite");
        let mut bad = m;
        bad[(2, 2)] = f64::INFINITY;
        assert_eq!(robot.solve(&bad, &b), None, "{name}: infinite");
    }
    floating(&Go2::new(), "go2");
    floating(&Romeo::new(), "romeo");
}
