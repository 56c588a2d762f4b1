//! What robotics code calls on a robot from URDF, beside the dynamics: the
//! placements of every link frame, the tool frame's Jacobian and velocity
//! (Pinocchio's `LOCAL_WORLD_ALIGNED`), the gravity torques and the
//! inertial-parameter regressor, against Pinocchio's values
//! (`tests/data/robots/reference_*.json`, `reference.py`); the Jacobian
//! against differences of the placement; `Y π` against RNEA; the same code
//! in `f32` and on SIMD lanes; the same on the Go2's floating base, in
//! Pinocchio's velocities `ν`.

use super::robots::{Go2, Panda, Tree, Ur5, from_pinocchio};
use lagrange::ensemble::AutoF64x4;
use lagrange::nalgebra::{DMatrix, Matrix3, SMatrix, SVector, SimdValue, Vector3};
use serde_json::Value;

/// What a robot is asked here.
trait Frames<const N: usize> {
    fn frames(&self) -> &'static [&'static str];
    fn placement(&self, q: &SVector<f64, N>, frame: usize) -> (Matrix3<f64>, Vector3<f64>);
    fn jacobian(&self, q: &SVector<f64, N>, frame: usize) -> SMatrix<f64, 6, N>;
    fn velocity(&self, q: &SVector<f64, N>, v: &SVector<f64, N>, frame: usize) -> SVector<f64, 6>;
    fn gravity(&self, q: &SVector<f64, N>) -> SVector<f64, N>;
    fn rnea(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        a: &SVector<f64, N>,
    ) -> SVector<f64, N>;
    fn regressor(
        &self,
        q: &SVector<f64, N>,
        v: &SVector<f64, N>,
        a: &SVector<f64, N>,
    ) -> DMatrix<f64>;
    fn parameters(&self) -> &'static [f64];
}

macro_rules! frames {
    ($t:ty, $n:literal) => {
        impl Frames<$n> for $t {
            fn frames(&self) -> &'static [&'static str] {
                &<$t>::FRAMES
            }
            fn placement(
                &self,
                q: &SVector<f64, $n>,
                frame: usize,
            ) -> (Matrix3<f64>, Vector3<f64>) {
                self.frame_placement(q, frame)
            }
            fn jacobian(&self, q: &SVector<f64, $n>, frame: usize) -> SMatrix<f64, 6, $n> {
                self.frame_jacobian(q, frame)
            }
            fn velocity(
                &self,
                q: &SVector<f64, $n>,
                v: &SVector<f64, $n>,
                frame: usize,
            ) -> SVector<f64, 6> {
                self.frame_velocity(q, v, frame)
            }
            fn gravity(&self, q: &SVector<f64, $n>) -> SVector<f64, $n> {
                self.gravity_torques(q)
            }
            fn rnea(
                &self,
                q: &SVector<f64, $n>,
                v: &SVector<f64, $n>,
                a: &SVector<f64, $n>,
            ) -> SVector<f64, $n> {
                self.inverse_dynamics(q, v, a)
            }
            fn regressor(
                &self,
                q: &SVector<f64, $n>,
                v: &SVector<f64, $n>,
                a: &SVector<f64, $n>,
            ) -> DMatrix<f64> {
                let y = <$t>::regressor(self, q, v, a);
                DMatrix::from_column_slice($n, 10 * $n, y.as_slice())
            }
            fn parameters(&self) -> &'static [f64] {
                &<$t>::PARAMETERS
            }
        }
    };
}
frames!(Ur5, 6);
frames!(Panda, 7);
frames!(Tree, 4);

fn vector<const N: usize>(v: &Value) -> SVector<f64, N> {
    SVector::from_iterator(v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
}

fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(a) => a.iter().flat_map(numbers).collect(),
        x => vec![x.as_f64().unwrap()],
    }
}

/// The largest error of `ours` against `theirs`, relative to `theirs`'
/// largest entry.
fn relative(ours: &[f64], theirs: &[f64]) -> f64 {
    assert_eq!(ours.len(), theirs.len());
    let scale = theirs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let err = ours
        .iter()
        .zip(theirs)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    err / scale
}

fn json(file: &str) -> Value {
    let path = format!("{}/tests/data/robots/{file}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

// The tolerance, as the dynamics' in `robots.rs`: both sides compose the
// same placements in f64 in different orders, each entry a sum of some
// tens of rounded products of O(1) numbers (metres, unit axes), so they
// differ by some hundred ulps of the largest entry; 1e-12 of it (4500
// ulps) holds with margin, where a wrong axis, offset, frame or sign shows
// at 1e-3 or more.
const TOLERANCE: f64 = 1e-12;

/// Every link frame's placement, the tool's Jacobian and velocity and the
/// gravity torques at the 20 states that carry them; the regressor at the
/// 5 that carry it. Returns the worst relative errors.
fn against_pinocchio<R: Frames<N>, const N: usize>(robot: &R, file: &str) -> [f64; 5] {
    let json = json(file);
    let mut links: Vec<&str> = json["links"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j.as_str().unwrap())
        .collect();
    let mut ours = robot.frames().to_vec();
    links.sort_unstable();
    ours.sort_unstable();
    // Pinocchio lists the frames of fixed joints in its own order; the
    // placements below are compared by name.
    assert_eq!(
        links, ours,
        "the frames are the URDF's links, Pinocchio's BODY frames"
    );
    let tool = robot
        .frames()
        .iter()
        .position(|f| *f == json["tool"].as_str().unwrap())
        .unwrap();
    let mut worst = [0.0f64; 5];
    let (mut placed, mut regressed) = (0, 0);
    for s in json["states"].as_array().unwrap() {
        let (q, v, a) = (
            vector::<N>(&s["q"]),
            vector::<N>(&s["v"]),
            vector::<N>(&s["a"]),
        );
        if let Some(placements) = s.get("placements") {
            placed += 1;
            for (k, name) in robot.frames().iter().enumerate() {
                let (r, p) = robot.placement(&q, k);
                let ours: Vec<f64> = r.transpose().iter().chain(p.iter()).copied().collect();
                worst[0] = worst[0].max(relative(&ours, &numbers(&placements[*name])));
            }
            // Row-major, as the JSON.
            let j = robot.jacobian(&q, tool).transpose();
            worst[1] = worst[1].max(relative(j.as_slice(), &numbers(&s["jacobian"])));
            let w = robot.velocity(&q, &v, tool);
            worst[2] = worst[2].max(relative(w.as_slice(), &numbers(&s["frame_velocity"])));
            let g = robot.gravity(&q);
            worst[3] = worst[3].max(relative(g.as_slice(), &numbers(&s["gravity"])));
        }
        if let Some(y) = s.get("regressor") {
            regressed += 1;
            let ours = robot.regressor(&q, &v, &a).transpose(); // row-major
            worst[4] = worst[4].max(relative(ours.as_slice(), &numbers(y)));
        }
    }
    assert_eq!((placed, regressed), (20, 5));
    println!(
        "{file}: placements {:.1e}, jacobian {:.1e}, velocity {:.1e}, gravity {:.1e}, regressor {:.1e}",
        worst[0], worst[1], worst[2], worst[3], worst[4]
    );
    for (what, e) in [
        "link placements",
        "tool Jacobian",
        "tool velocity",
        "gravity torques",
        "regressor",
    ]
    .iter()
    .zip(worst)
    {
        assert!(
            e < TOLERANCE,
            "{file}: {what} off Pinocchio's by {e:e} of its largest entry"
        );
    }
    worst
}

#[test]
fn ur5_frames_and_regressor_match_pinocchio() {
    against_pinocchio(&Ur5::new(), "reference_ur5.json");
}

#[test]
fn panda_frames_and_regressor_match_pinocchio() {
    against_pinocchio(&Panda::new(), "reference_panda.json");
}

#[test]
fn tree_frames_and_regressor_match_pinocchio() {
    against_pinocchio(&Tree::new(), "reference_tree.json");
}

/// `Y π = τ` at all 100 stored states, `π` the file's parameters: the
/// regressor is RNEA's linear map, not only at Pinocchio's 5 states.
fn regressor_times_parameters_is_rnea<R: Frames<N>, const N: usize>(robot: &R, file: &str) {
    let json = json(file);
    let pi = DMatrix::from_column_slice(10 * N, 1, robot.parameters());
    let mut worst = 0.0f64;
    for s in json["states"].as_array().unwrap() {
        let (q, v, a) = (
            vector::<N>(&s["q"]),
            vector::<N>(&s["v"]),
            vector::<N>(&s["a"]),
        );
        let tau = robot.rnea(&q, &v, &a);
        let y_pi = robot.regressor(&q, &v, &a) * &pi;
        worst = worst.max(relative(y_pi.as_slice(), tau.as_slice()));
    }
    println!("{file}: |Y π − τ| {worst:.1e} of τ's largest");
    // The same products summed in another order (per parameter, then
    // through the joints): TOLERANCE as above.
    assert!(worst < TOLERANCE, "{file}: Y π off RNEA by {worst:e}");
}

#[test]
fn regressor_times_parameters_is_inverse_dynamics() {
    regressor_times_parameters_is_rnea(&Ur5::new(), "reference_ur5.json");
    regressor_times_parameters_is_rnea(&Panda::new(), "reference_panda.json");
    regressor_times_parameters_is_rnea(&Tree::new(), "reference_tree.json");
}

/// The Jacobian against central differences of the placement: column `j`
/// is `(∂p/∂q_j, vee(∂R/∂q_j Rᵀ))`, for every frame of the robot.
fn jacobian_is_the_placements_derivative<R: Frames<N>, const N: usize>(
    robot: &R,
    q: SVector<f64, N>,
) {
    // Step 1e-5: truncation O(h²) ~ 1e-10 (second derivatives O(1)),
    // rounding ~1e-16 / 1e-5 = 1e-11; compared at 1e-8.
    let h = 1e-5;
    for frame in 0..robot.frames().len() {
        let j = robot.jacobian(&q, frame);
        let (r, _) = robot.placement(&q, frame);
        for c in 0..N {
            let dq = SVector::<f64, N>::from_fn(|i, _| if i == c { h } else { 0.0 });
            let (rp, pp) = robot.placement(&(q + dq), frame);
            let (rm, pm) = robot.placement(&(q - dq), frame);
            let dp = (pp - pm) / (2.0 * h);
            let w = (rp - rm) / (2.0 * h) * r.transpose();
            let omega = Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]);
            let diff = (dp - j.fixed_view::<3, 1>(0, c)).amax()
                + (omega - j.fixed_view::<3, 1>(3, c)).amax();
            assert!(
                diff < 1e-8,
                "frame {} column {c}: Jacobian {} against differences {dp} {omega}",
                robot.frames()[frame],
                j.column(c)
            );
        }
    }
}

#[test]
fn jacobians_are_the_placements_derivatives() {
    jacobian_is_the_placements_derivative(
        &Panda::new(),
        SVector::<f64, 7>::from_fn(|i, _| 0.4 * i as f64 - 1.1),
    );
    // The prismatic joint's column is its axis, with no angular part.
    jacobian_is_the_placements_derivative(
        &Tree::new(),
        SVector::<f64, 4>::new(0.7, 0.12, -2.1, 1.3),
    );
}

/// The same generated code in `f32` and on four `f64` lanes: each lane is
/// its scalar run.
#[test]
fn frames_and_regressor_run_in_f32_and_on_lanes() {
    let q = SVector::<f64, 7>::from_fn(|i, _| 0.3 * i as f64 - 0.8);
    let v = SVector::<f64, 7>::from_fn(|i, _| 0.5 - 0.2 * i as f64);
    let a = SVector::<f64, 7>::from_fn(|i, _| 1.0 - 0.3 * i as f64);
    let tool = Panda::<f64>::frame_index("panda_hand_tcp").unwrap();
    let panda = Panda::new();
    let j = panda.frame_jacobian(&q, tool);
    let y = Panda::regressor(&panda, &q, &v, &a);
    let single = Panda::<f32>::new();
    let j32 = single.frame_jacobian(&q.cast(), tool).cast::<f64>();
    let y32 = Panda::regressor(&single, &q.cast(), &v.cast(), &a.cast()).cast::<f64>();
    // f32 rounding (6e-8) over some tens to hundreds of operations: 1e-5.
    assert!((j32 - j).amax() < 1e-5 * j.amax());
    assert!((y32 - y).amax() < 1e-5 * y.amax());
    // Lanes: four states, lane k of the result against the scalar call.
    let shift = |k: usize| SVector::<f64, 7>::from_fn(|i, _| 0.1 * (k * i) as f64);
    let lanes = |x: &SVector<f64, 7>| {
        SVector::<AutoF64x4, 7>::from_fn(|i, _| {
            AutoF64x4::from([0, 1, 2, 3].map(|k| x[i] + shift(k)[i]))
        })
    };
    let wide = Panda::<AutoF64x4>::new();
    let jl = wide.frame_jacobian(&lanes(&q), tool);
    let yl = Panda::regressor(&wide, &lanes(&q), &lanes(&v), &lanes(&a));
    for k in 0..4 {
        let (qk, vk, ak) = (q + shift(k), v + shift(k), a + shift(k));
        let jk = jl.map(|x| x.extract(k));
        let yk = yl.map(|x| x.extract(k));
        let (js, ys) = (
            panda.frame_jacobian(&qk, tool),
            Panda::regressor(&panda, &qk, &vk, &ak),
        );
        // The same operations lane by lane; the lanes' sine and cosine may
        // round differently from the scalar's (a few ulps): 1e-14.
        assert!((jk - js).amax() < 1e-14 * js.amax(), "lane {k}: {jk} {js}");
        assert!((yk - ys).amax() < 1e-14 * ys.amax(), "lane {k}");
    }
}

/// The Go2 on its floating base, in Pinocchio's velocities `ν`: every link
/// frame's placement, the front left foot's Jacobian (6 × 18, the base's
/// six columns first) and velocity and the gravity forces at the 20 states
/// that carry them, the regressor (18 × 130, the base's body first) at the
/// 5 that carry it, against Pinocchio; `Y π` against RNEA at all 100.
#[test]
fn go2_frames_and_regressor_on_a_floating_base_match_pinocchio() {
    let json = json("reference_go2.json");
    let go2 = Go2::new();
    let joints: Vec<&str> = json["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j.as_str().unwrap())
        .collect();
    // Pinocchio's index of our joint `k` (it orders a link's children by
    // their joints' names), of our entry `i` of a configuration (the
    // base's 7 first) and of a velocity (the base's 6 first).
    let pin: Vec<usize> = Go2::<f64>::COORDINATES[7..]
        .iter()
        .map(|j| joints.iter().position(|p| p == j).unwrap())
        .collect();
    let at_q = |i: usize| if i < 7 { i } else { 7 + pin[i - 7] };
    let at_v = |i: usize| if i < 6 { i } else { 6 + pin[i - 6] };
    let velocity = |x: &Value| {
        let x = vector::<18>(x);
        SVector::<f64, 18>::from_fn(|i, _| x[at_v(i)])
    };
    let mut links: Vec<&str> = json["links"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j.as_str().unwrap())
        .collect();
    let mut ours = Go2::<f64>::FRAMES.to_vec();
    links.sort_unstable();
    ours.sort_unstable();
    assert_eq!(links, ours, "the frames are Pinocchio's BODY frames");
    let tool = Go2::<f64>::frame_index(json["tool"].as_str().unwrap()).unwrap();
    let pi = SVector::<f64, 130>::from_column_slice(&Go2::<f64>::PARAMETERS);
    let mut worst = [0.0f64; 6];
    let (mut placed, mut regressed) = (0, 0);
    for s in json["states"].as_array().unwrap() {
        let q_pin = vector::<19>(&s["q"]);
        let q = from_pinocchio(&SVector::<f64, 19>::from_fn(|i, _| q_pin[at_q(i)]));
        let (v, a) = (velocity(&s["v"]), velocity(&s["a"]));
        let y = go2.regressor(&q, &v, &a);
        let tau = go2.inverse_dynamics(&q, &v, &a);
        worst[5] = worst[5].max(relative((y * pi).as_slice(), tau.as_slice()));
        if let Some(placements) = s.get("placements") {
            placed += 1;
            for (k, name) in Go2::<f64>::FRAMES.iter().enumerate() {
                let (r, p) = go2.frame_placement(&q, k);
                let ours: Vec<f64> = r.transpose().iter().chain(p.iter()).copied().collect();
                worst[0] = worst[0].max(relative(&ours, &numbers(&placements[*name])));
            }
            let theirs = numbers(&s["jacobian"]); // row-major, Pinocchio's columns
            let theirs = SMatrix::<f64, 6, 18>::from_fn(|r, c| theirs[18 * r + at_v(c)]);
            let j = go2.frame_jacobian(&q, tool);
            worst[1] = worst[1].max(relative(j.as_slice(), theirs.as_slice()));
            let w = go2.frame_velocity(&q, &v, tool);
            worst[2] = worst[2].max(relative(w.as_slice(), &numbers(&s["frame_velocity"])));
            let g = go2.gravity_torques(&q);
            worst[3] = worst[3].max(relative(g.as_slice(), velocity(&s["gravity"]).as_slice()));
        }
        if let Some(theirs) = s.get("regressor") {
            regressed += 1;
            let theirs = numbers(theirs); // 18 rows of 130, Pinocchio's order
            // Our column of body `b` (0 the base's), parameter `p`.
            let col = |c: usize| match c / 10 {
                0 => c,
                b => 10 * (1 + pin[b - 1]) + c % 10,
            };
            let theirs = SMatrix::<f64, 18, 130>::from_fn(|r, c| theirs[130 * at_v(r) + col(c)]);
            worst[4] = worst[4].max(relative(y.as_slice(), theirs.as_slice()));
        }
    }
    assert_eq!((placed, regressed), (20, 5));
    println!(
        "go2: placements {:.1e}, jacobian {:.1e}, velocity {:.1e}, gravity {:.1e}, regressor {:.1e}, Y π {:.1e}",
        worst[0], worst[1], worst[2], worst[3], worst[4], worst[5]
    );
    for (what, e) in [
        "link placements",
        "foot Jacobian",
        "foot velocity",
        "gravity forces",
        "regressor",
        "Y π against RNEA",
    ]
    .iter()
    .zip(worst)
    {
        // TOLERANCE, as on the fixed bases: the base's rotation is one more
        // product of O(1) numbers before the same walk.
        assert!(
            e < TOLERANCE,
            "go2: {what} off by {e:e} of the largest entry"
        );
    }
}

/// The Go2's frame velocities `J ν` against central differences of the
/// frames' placements along the coordinates' rates `q̇` of `ν`, every
/// frame, the base's columns included; and the same code in `f32`.
#[test]
fn go2_frame_velocities_are_the_placements_rates() {
    use lagrange::nalgebra::{Quaternion, UnitQuaternion};
    let go2 = Go2::new();
    let turn = UnitQuaternion::from_euler_angles(0.4, -0.7, 2.0);
    let quat: &Quaternion<f64> = turn.as_ref();
    let mut q = SVector::<f64, 19>::from_fn(|i, _| 0.3 * i as f64 - 2.1);
    (q[3], q[4], q[5], q[6]) = (quat.w, quat.i, quat.j, quat.k);
    let v = SVector::<f64, 18>::from_fn(|i, _| 0.9 - 0.17 * i as f64);
    let qdot = go2.rates(&q, &v);
    // Step 1e-5: truncation O(h²) ~ 1e-10, rounding 1e-16 / 1e-5 = 1e-11
    // (the quaternion leaves the sphere by O(h²), symmetrically); 1e-8.
    let h = 1e-5;
    for frame in 0..Go2::<f64>::FRAMES.len() {
        let w = go2.frame_velocity(&q, &v, frame);
        let (r, _) = go2.frame_placement(&q, frame);
        let (rp, pp) = go2.frame_placement(&(q + qdot * h), frame);
        let (rm, pm) = go2.frame_placement(&(q - qdot * h), frame);
        let dp = (pp - pm) / (2.0 * h);
        let dr = (rp - rm) / (2.0 * h) * r.transpose();
        let omega = Vector3::new(dr[(2, 1)], dr[(0, 2)], dr[(1, 0)]);
        let diff = (dp - w.fixed_rows::<3>(0)).amax() + (omega - w.fixed_rows::<3>(3)).amax();
        assert!(
            diff < 1e-8,
            "frame {}: velocity {w} against differences {dp} {omega}",
            Go2::<f64>::FRAMES[frame]
        );
    }
    let a = SVector::<f64, 18>::from_fn(|i, _| 1.0 - 0.3 * i as f64);
    let tool = Go2::<f64>::frame_index("FL_foot").unwrap();
    let (j, y) = (go2.frame_jacobian(&q, tool), go2.regressor(&q, &v, &a));
    let single = Go2::<f32>::new();
    let j32 = single.frame_jacobian(&q.cast(), tool).cast::<f64>();
    let y32 = single
        .regressor(&q.cast(), &v.cast(), &a.cast())
        .cast::<f64>();
    // f32 rounding (6e-8) over some tens to hundreds of operations: 1e-5.
    assert!((j32 - j).amax() < 1e-5 * j.amax());
    assert!((y32 - y).amax() < 1e-5 * y.amax());
}
