//! A robot from its URDF under control: the Panda (fingers locked) holding
//! a pose against gravity and tracking a joint trajectory by computed
//! torque, `τ = M(q) (q̈_d + K_d ė + K_p e) + h(q, q̇)` — the generated
//! inverse dynamics in the loop, one call per right-hand side — while it
//! carries a payload its model does not know; then the payload's mass,
//! first moment and inertia identified from noisy joint torques by least
//! squares through the generated regressor `Y(q, q̇, q̈)`, and the same
//! controller run again with the identified payload added to its model.
//!
//! The Panda's last body's inertial parameters are a field of its struct
//! (`#[lagrange(parameters(link7 = "panda_link7"))]`): the robot simulated
//! is the Panda with the payload's ten parameters added there, its `M`
//! and forcing the generated ones; the model a controller uses is the
//! Panda without it, then with the identified parameters added the same
//! way. The runtime's Dopri5 integrates the plant.
//!
//! `cargo run --release -p lagrange-studies --example robot_control`
//!
//! Writes `docs/robot_control/robot_control.svg`: the joint error while
//! holding and while tracking, without and with the identified payload;
//! and the tool frame's path.

use lagrange::nalgebra::{DMatrix, DVector, SMatrix, SVector};
use lagrange::prelude::*;
use plotters::prelude::*;
use std::error::Error;

lagrangian! {
    /// The Panda of example-robot-data, its fingers locked closed.
    /// Its last body's inertial parameters are a field, `link7`: a payload
    /// on it is added there.
    #[lagrange(urdf = "../tests/data/robots/panda.urdf", regressor, parameters(link7 = "panda_link7"))]
    pub struct Panda {
        locked: panda_finger_joint1 = 0.0, panda_finger_joint2 = 0.0;
    }
}

type V = SVector<f64, 7>;
type Pi = SVector<f64, 10>;
/// A run's sample: `(t, q, q̇)`.
type Sample = (f64, V, V);

/// The last body's parameters in the regressor's columns.
const LAST: usize = 60;
/// The torque sensors' noise, N m (one standard deviation).
const NOISE: f64 = 0.05;
/// Computed torque's error dynamics `ë + K_d ė + K_p e = 0`: ω = 10 rad/s,
/// critically damped.
const KP: f64 = 100.0;
const KD: f64 = 20.0;

/// A 1.2 kg box (8 × 6 × 10 cm) on `panda_link7`, its centre 0.16 m out
/// along the link's z and off its axis: the ten parameters `π` in the
/// link's frame (mass, first moment, inertia about the frame's origin).
fn payload() -> Pi {
    let m = 1.2;
    let c = [0.02, -0.015, 0.16];
    let (a, b, h) = (0.08, 0.06, 0.10);
    let ic = [
        m / 12.0 * (b * b + h * h),
        m / 12.0 * (a * a + h * h),
        m / 12.0 * (a * a + b * b),
    ];
    let cc: f64 = c.iter().map(|x| x * x).sum();
    // I_o = I_c + m (|c|² 1 − c cᵀ), in (xx, xy, yy, xz, yz, zz).
    let i = |r: usize, s: usize| {
        let d = if r == s { ic[r] + m * cc } else { 0.0 };
        d - m * c[r] * c[s]
    };
    Pi::from_column_slice(&[
        m,
        m * c[0],
        m * c[1],
        m * c[2],
        i(0, 0),
        i(0, 1),
        i(1, 1),
        i(0, 2),
        i(1, 2),
        i(2, 2),
    ])
}

/// The payload's columns of the regressor: its torques are `Y_p π_p`.
fn payload_columns(panda: &Panda, q: &V, qdot: &V, qddot: &V) -> SMatrix<f64, 7, 10> {
    Panda::regressor(panda, q, qdot, qddot)
        .fixed_columns::<10>(LAST)
        .into_owned()
}

/// The Panda with a payload on `panda_link7`: its ten parameters added
/// to the body's (parameters are linear: the sum is the rigid body of both).
fn with_payload(payload: &Pi) -> Panda {
    let mut panda = Panda::new();
    for (p, x) in panda.link7.iter_mut().zip(payload.iter()) {
        *p += x;
    }
    panda
}

/// Computed torque towards `(q_d, q̇_d, q̈_d)` with `model`'s inverse
/// dynamics (RNEA, its payload among its parameters).
fn computed_torque(model: &Panda, q: &V, qdot: &V, (qd, qd_dot, qd_ddot): (V, V, V)) -> V {
    let command = qd_ddot + (qd_dot - qdot) * KD + (qd - q) * KP;
    model.inverse_dynamics(q, qdot, &command)
}

/// The robot simulated: the Panda with the true payload, driven by
/// `control(t, q, q̇)`.
struct Plant<F> {
    truth: Panda,
    control: F,
}

impl<F: Fn(f64, &V, &V) -> V> Lagrangian<7> for Plant<F> {
    type Scalar = f64;
    const COORDINATES: [&'static str; 7] = Panda::<f64>::COORDINATES;
    fn mass_matrix(&self, t: f64, q: &V) -> SMatrix<f64, 7, 7> {
        self.truth.mass_matrix(t, q)
    }
    fn forcing(&self, t: f64, q: &V, qdot: &V) -> V {
        // M q̈ = τ − nle.
        (self.control)(t, q, qdot) - self.truth.nonlinear_effects(q, qdot)
    }
    fn kinetic_energy(&self, t: f64, q: &V, qdot: &V) -> f64 {
        self.truth.kinetic_energy(t, q, qdot)
    }
    fn potential_energy(&self, t: f64, q: &V) -> f64 {
        self.truth.potential_energy(t, q)
    }
}

/// The pose held: the Panda's "ready" configuration.
fn ready() -> V {
    V::from_column_slice(&[0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785])
}

/// The trajectory: a sum of sines about `ready` on every joint, different
/// frequencies (0.2 to 0.7 Hz), amplitudes 0.25 to 0.5 rad: rich enough to
/// excite the payload's ten parameters. `(q_d, q̇_d, q̈_d)` at `t`.
fn trajectory(t: f64) -> (V, V, V) {
    let mut out = (ready(), V::zeros(), V::zeros());
    for j in 0..7 {
        for (k, f) in [0.2 + 0.07 * j as f64, 0.45 + 0.04 * j as f64]
            .into_iter()
            .enumerate()
        {
            let (a, w) = (
                0.25 / (1.0 + k as f64) + 0.02 * j as f64,
                2.0 * std::f64::consts::PI * f,
            );
            out.0[j] += a * (w * t).sin();
            out.1[j] += a * w * (w * t).cos();
            out.2[j] -= a * w * w * (w * t).sin();
        }
    }
    out
}

/// SplitMix64 and Box–Muller: Gaussian noise from a seed.
fn noise(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
    let mut uniform = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    move || {
        let (u, v) = (uniform().max(f64::MIN_POSITIVE), uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}

/// A run of the plant under `control` from `(q0, 0)`, sampled at 100 Hz
/// for `seconds`: the samples `(t, q, q̇)`.
fn simulate(
    truth: Panda,
    control: impl Fn(f64, &V, &V) -> V,
    q0: V,
    qdot0: V,
    seconds: f64,
) -> Result<Vec<Sample>, Box<dyn Error>> {
    let plant = Plant { truth, control };
    let times: Vec<f64> = (0..=(seconds * 100.0).round() as usize)
        .map(|i| 0.01 * i as f64)
        .collect();
    let run = Dopri5::new()
        .rtol(1e-10)
        .atol(1e-10)
        .integrate(&plant, 0.0, q0, qdot0, &times)
        .map_err(|f| f.error.to_string())?;
    Ok(run.iter().map(|s| (s.t, s.q, s.qdot)).collect())
}

fn degrees(e: f64) -> f64 {
    e.to_degrees()
}

fn main() -> Result<(), Box<dyn Error>> {
    let truth = with_payload(&payload());
    let nominal = Panda::new();
    let tcp = Panda::<f64>::frame_index("panda_hand_tcp").ok_or("no panda_hand_tcp")?;
    println!(
        "Panda from its URDF: {} joints, {} frames, {} inertial parameters; payload {:.2} kg on panda_link7 (unknown to the model)",
        Panda::<f64>::DOF,
        Panda::<f64>::FRAMES.len(),
        Panda::<f64>::PARAMETERS.len(),
        payload()[0]
    );

    // 1. Holding `ready` from 0.1 rad off on every joint, by computed
    // torque with zero desired motion, the nominal model.
    let hold_target = (ready(), V::zeros(), V::zeros());
    let q0 = ready() + V::from_element(0.1);
    let hold = |model: Panda| {
        simulate(
            truth,
            move |_t, q: &V, qdot: &V| computed_torque(&model, q, qdot, hold_target),
            q0,
            V::zeros(),
            3.0,
        )
    };
    let hold_nominal = hold(nominal)?;
    let error = |q: &V, qd: &V| (q - qd).amax();
    let (_, q_end, _) = hold_nominal.last().ok_or("no samples")?;
    println!(
        "hold, nominal model: joint error {:.3}° at t = 3 s (the payload's weight, uncompensated: K_p⁻¹ M̂⁻¹ g_payload)",
        degrees(error(q_end, &ready()))
    );

    // 2. Identification: the nominal controller tracks the trajectory for
    // 10 s; at 100 Hz the joint torques are recorded with Gaussian noise
    // (q, q̇, q̈ exact: the plant's own); the payload's ten parameters
    // solve τ_measured − τ_nominal(q, q̇, q̈) = Y_p(q, q̇, q̈) π_p by least
    // squares.
    let control = move |t: f64, q: &V, qdot: &V| computed_torque(&nominal, q, qdot, trajectory(t));
    let (qd0, qd_dot0, _) = trajectory(0.0);
    let recording = simulate(truth, control, qd0, qd_dot0, 10.0)?;
    let plant = Plant { truth, control };
    let mut gauss = noise(7);
    let rows = 7 * recording.len();
    let mut a = DMatrix::<f64>::zeros(rows, 10);
    let mut b = DVector::<f64>::zeros(rows);
    for (k, (t, q, qdot)) in recording.iter().enumerate() {
        let qddot = plant
            .mass_matrix(*t, q)
            .cholesky()
            .ok_or("M not positive definite")?
            .solve(&plant.forcing(*t, q, qdot));
        let measured = control(*t, q, qdot) + V::from_fn(|_, _| NOISE * gauss());
        let y = payload_columns(&nominal, q, qdot, &qddot);
        let r = measured - nominal.inverse_dynamics(q, qdot, &qddot);
        a.view_mut((7 * k, 0), (7, 10)).copy_from(&y);
        b.rows_mut(7 * k, 7).copy_from(&r);
    }
    let normal = a.transpose() * &a;
    let chol = normal
        .clone()
        .cholesky()
        .ok_or("the payload is not identifiable on this trajectory")?;
    let estimate = chol.solve(&(a.transpose() * &b));
    let residual = &b - &a * &estimate;
    let sigma = (residual.norm_squared() / (rows - 10) as f64).sqrt();
    let covariance = chol.inverse() * sigma * sigma;
    println!(
        "identification: {} samples × 7 torques, noise {NOISE} N m (σ̂ = {sigma:.4} N m from the residuals)",
        recording.len()
    );
    println!("| parameter | true | identified | error | standard error | error / s.e. |");
    println!("|---|---:|---:|---:|---:|---:|");
    let names = [
        "m [kg]",
        "m cx [kg m]",
        "m cy",
        "m cz",
        "Ixx [kg m²]",
        "Ixy",
        "Iyy",
        "Ixz",
        "Iyz",
        "Izz",
    ];
    let mut worst: f64 = 0.0;
    for (i, name) in names.iter().enumerate() {
        let (t, e, se) = (payload()[i], estimate[i], covariance[(i, i)].sqrt());
        worst = worst.max(((e - t) / se).abs());
        println!(
            "| {name} | {t:.5} | {e:.5} | {:+.1e} | {se:.1e} | {:+.2} |",
            e - t,
            (e - t) / se
        );
    }
    println!(
        "largest |error| / standard error: {worst:.2} (each ratio standard normal under Gaussian noise: beyond 3 with probability 0.27 %)"
    );
    // Into the model: the payload's ten added to the last body's field.
    let identified = with_payload(&Pi::from_iterator(estimate.iter().copied()));

    // 3. Holding and tracking again, with the identified payload in the
    // model; tracking from on the trajectory, 10 s.
    let hold_identified = hold(identified)?;
    let (_, q_end, _) = hold_identified.last().ok_or("no samples")?;
    println!(
        "hold, identified payload: joint error {:.2e}° at t = 3 s",
        degrees(error(q_end, &ready()))
    );
    let track = |model: Panda| {
        simulate(
            truth,
            move |t, q: &V, qdot: &V| computed_torque(&model, q, qdot, trajectory(t)),
            qd0,
            qd_dot0,
            10.0,
        )
    };
    let track_identified = track(identified)?;
    let tracking_error = |run: &[Sample]| -> Vec<(f64, f64)> {
        run.iter()
            .map(|(t, q, _)| (*t, degrees(error(q, &trajectory(*t).0))))
            .collect()
    };
    let (e_nominal, e_identified) = (
        tracking_error(&recording),
        tracking_error(&track_identified),
    );
    let peak = |e: &[(f64, f64)]| e.iter().map(|p| p.1).fold(0.0, f64::max);
    println!(
        "tracking 10 s by computed torque (ω = 10 rad/s): largest joint error {:.3}° with the nominal model, {:.2e}° with the identified payload",
        peak(&e_nominal),
        peak(&e_identified)
    );
    let path: Vec<(f64, f64)> = track_identified
        .iter()
        .map(|(_, q, _)| {
            let (_, p) = nominal.frame_placement(q, tcp);
            (p.x, p.z)
        })
        .collect();
    let hold_error = |run: &[Sample]| -> Vec<(f64, f64)> {
        run.iter()
            .map(|(t, q, _)| (*t, degrees(error(q, &ready()))))
            .collect()
    };

    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../docs/robot_control/robot_control.svg");
    std::fs::create_dir_all(file.parent().ok_or("no parent")?)?;
    draw(
        &file,
        [
            (&hold_error(&hold_nominal), &hold_error(&hold_identified)),
            (&e_nominal, &e_identified),
        ],
        &path,
    )?;
    println!("Wrote {}", file.display());
    Ok(())
}

type Series<'a> = (&'a Vec<(f64, f64)>, &'a Vec<(f64, f64)>);

fn draw(
    path: &std::path::Path,
    errors: [Series; 2],
    tcp: &[(f64, f64)],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (1000, 620)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Panda from its URDF, computed torque with a 1.2 kg payload: nominal model and identified payload",
        ("sans-serif", 18),
    )?;
    let (left, right) = root.split_horizontally(680);
    let (top, bottom) = left.split_vertically(300);
    for ((area, title), (nominal, identified)) in [
        (&top, "holding the ready pose"),
        (&bottom, "tracking the trajectory"),
    ]
    .into_iter()
    .zip(errors)
    {
        let end = nominal.last().map_or(1.0, |p| p.0);
        let floor = 1e-6;
        let mut chart = ChartBuilder::on(area)
            .caption(title, ("sans-serif", 15))
            .margin(8)
            .x_label_area_size(32)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..end, (floor..20.0).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc("largest joint error [deg]")
            .draw()?;
        for (points, color, label) in [
            (nominal, RED, "nominal model"),
            (identified, BLUE, "identified payload"),
        ] {
            chart
                .draw_series(LineSeries::new(
                    points.iter().map(|&(t, e)| (t, e.max(floor))),
                    color.stroke_width(2),
                ))?
                .label(label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
    }
    let (lo_x, hi_x) = tcp
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let (lo_z, hi_z) = tcp
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
    let pad = 0.05;
    let mut chart = ChartBuilder::on(&right)
        .caption("tool frame (panda_hand_tcp), tracking", ("sans-serif", 15))
        .margin(8)
        .x_label_area_size(32)
        .y_label_area_size(50)
        .build_cartesian_2d((lo_x - pad)..(hi_x + pad), (lo_z - pad)..(hi_z + pad))?;
    chart
        .configure_mesh()
        .x_desc("x [m]")
        .y_desc("z [m]")
        .draw()?;
    chart.draw_series(LineSeries::new(tcp.iter().copied(), BLUE.stroke_width(1)))?;
    root.present()?;
    Ok(())
}
