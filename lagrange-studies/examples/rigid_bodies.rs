//! Rigid bodies in unit quaternions and bodies that roll: the models of
//! issue 24's first part, each against its closed form, printed as tables.
//!
//! `cargo run --release -p lagrange-studies --example rigid_bodies`
//!
//! - the Dzhanibekov effect: a torque-free body spun near its intermediate
//!   axis (`FreeBody`), its flips located as events against Euler's
//!   closed form `n · 2K(k)/λ`;
//! - a heavy top swinging through the pole (`HeavyTop`), its invariants,
//!   and what the Euler-angle model does there;
//! - the Chaplygin sleigh (`ChaplyginSleigh`) against its tanh/sech;
//! - a rolling disk (`RollingDisk`): the largest lean after a nudge from
//!   upright rolling, either side of the critical speed `v² = g r / 3`, and
//!   its linearization about upright rolling against the closed form;
//! - a ball rolling in a unit quaternion (`RollingBall`) started from its
//!   body rates by `constraints::state_from_body_rates`, against the
//!   hand-made start and the closed-form roll.
//!
//! Writes `docs/rigid_bodies/rigid_bodies.svg`: the tumbling body's rates
//! over four flips, and the paths of the sleigh and of the disk's contact
//! point.

#[path = "../../tests/support/elliptic.rs"]
#[allow(dead_code)]
mod elliptic;

use lagrange::analysis::linearize_steady_motion;
use lagrange::constraints::state_from_body_rates;
use lagrange::models::{
    ChaplyginSleigh, EulerTop, FreeBody, HeavyTop, RollingBall, RollingDisk, quaternion,
};
use lagrange::nalgebra::{SVector, UnitQuaternion, Vector2, Vector3};
use lagrange::prelude::*;
use plotters::prelude::*;
use std::error::Error;
use std::time::Instant;

/// A time and the body rates there.
type Rates = (f64, Vector3<f64>);

fn main() -> Result<(), Box<dyn Error>> {
    let rates = dzhanibekov()?;
    heavy_top()?;
    let sleigh_path = sleigh()?;
    let disk_path = disk()?;
    rolling_ball()?;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../docs/rigid_bodies/rigid_bodies.svg");
    std::fs::create_dir_all(path.parent().unwrap())?;
    draw(&path, &rates, &sleigh_path, &disk_path)?;
    println!("\nwrote {}", path.display());
    Ok(())
}

/// The flips of a body with moments (1, 2, 3) started at rates (1.7, 0, 1)
/// (`M² − 2 E I2 = 0.11`, near the intermediate axis' separatrix).
fn dzhanibekov() -> Result<Vec<Rates>, Box<dyn Error>> {
    let (i1, i2, i3) = (1.0f64, 2.0f64, 3.0f64);
    let omega0 = Vector3::<f64>::new(1.7, 0.0, 1.0);
    let two_e = i1 * omega0[0].powi(2) + i2 * omega0[1].powi(2) + i3 * omega0[2].powi(2);
    let m2 = (i1 * omega0[0]).powi(2) + (i2 * omega0[1]).powi(2) + (i3 * omega0[2]).powi(2);
    let (upper, lower) = (two_e * i3 - m2, m2 - two_e * i1);
    let k2 = (i2 - i1) * upper / ((i3 - i2) * lower);
    let lambda = ((i3 - i2) * lower / (i1 * i2 * i3)).sqrt();
    let kk = elliptic::jacobi(0.0, k2.sqrt(), (1.0 - k2).sqrt()).k_complete;
    let half = 2.0 * kk / lambda;

    let body = FreeBody::new(i1, i2, i3);
    let rotation = UnitQuaternion::from_euler_angles(0.3, -0.7, 1.1);
    let (q0, v0) = quaternion::state(&rotation, &omega0);
    let flip = Event::new("flip", |_t, q: &SVector<f64, 4>, qdot: &SVector<f64, 4>| {
        quaternion::body_rates(q, qdot)[1]
    });
    let times: Vec<f64> = (1..=400).map(|k| 4.0 * half * k as f64 / 400.0).collect();
    let started = Instant::now();
    let run = Dop853::new()
        .rtol(1e-14)
        .atol(1e-14)
        .integrate(&body, 0.0, q0, v0, &times)?;
    let long = Dop853::new()
        .rtol(1e-14)
        .atol(1e-14)
        .integrate_with_events(
            &body,
            0.0,
            q0,
            v0,
            &[10.5 * half],
            &Events::new().with(flip),
        )?;
    let elapsed = started.elapsed();
    println!("The Dzhanibekov effect: a free body in unit quaternions, moments (1, 2, 3),");
    println!(
        "started at body rates (1.7, 0, 1): k = {:.6}, 2K/λ = {half:.12} s\n",
        k2.sqrt()
    );
    println!("| flip | t (located) | n · 2K/λ | relative error |");
    println!("|---:|---:|---:|---:|");
    for (n, e) in long.events().iter().enumerate() {
        let expected = (n + 1) as f64 * half;
        println!(
            "| {} | {:.12} | {:.12} | {:.1e} |",
            n + 1,
            e.t,
            expected,
            (e.t - expected) / expected
        );
    }
    let end = long.last().unwrap();
    let l0 = body.angular_momentum(&q0, &v0);
    println!(
        "\nafter ten flips: |q| − 1 = {:.1e}, angular momentum in space off by {:.1e} relative; \
         both runs {:.1} ms (Dop853, rtol = atol = 1e-14)",
        end.q.norm() - 1.0,
        (body.angular_momentum(&end.q, &end.qdot) - l0).norm() / l0.norm(),
        elapsed.as_secs_f64() * 1e3
    );

    // The same ten flips by the variational integrator at fixed steps:
    // symplectic, the angular momentum in space a symmetry's momentum.
    println!(
        "\nThe same by the variational integrator (fixed step h, RATTLE on |q| = 1), ten flips:\n"
    );
    println!(
        "| h [s] | steps | angular momentum in space, largest drift | energy, largest error | largest flip time error [s] | ms |"
    );
    println!("|---:|---:|---:|---:|---:|---:|");
    for h in [0.02, 0.01, 0.005] {
        let flip = Event::new("flip", |_t, q: &SVector<f64, 4>, qdot: &SVector<f64, 4>| {
            quaternion::body_rates(q, qdot)[1]
        });
        let samples: Vec<f64> = (1..=105).map(|k| 0.1 * half * k as f64).collect();
        let started = Instant::now();
        let fixed = Variational::new(h).integrate_with_events(
            &body,
            0.0,
            q0,
            v0,
            &samples,
            &Events::new().with(flip),
        )?;
        let elapsed = started.elapsed();
        let e0 = body.kinetic_energy(0.0, &q0, &v0);
        let (mut dl, mut de) = (0.0f64, 0.0f64);
        for s in fixed.iter() {
            dl = dl.max((body.angular_momentum(&s.q, &s.qdot) - l0).norm() / l0.norm());
            de = de.max((body.kinetic_energy(0.0, &s.q, &s.qdot) - e0).abs() / e0);
        }
        let flips = fixed
            .events()
            .iter()
            .enumerate()
            .map(|(n, e)| (e.t - (n + 1) as f64 * half).abs())
            .fold(0.0, f64::max);
        println!(
            "| {h} | {} | {dl:.1e} | {de:.1e} | {flips:.2e} | {:.1} |",
            fixed.stats().steps_accepted,
            elapsed.as_secs_f64() * 1e3
        );
    }
    Ok(run
        .iter()
        .map(|s| (s.t, quaternion::body_rates(&s.q, &s.qdot)))
        .collect())
}

/// The top (a = 1, c = 0.5, m = 1, g = 9.81, l = 0.2) from a tilt of
/// 0.5 rad with `L_z = L_3`: its axis swings through the vertical.
fn heavy_top() -> Result<(), Box<dyn Error>> {
    let (a, c, m, g, l) = (1.0, 0.5, 1.0, 9.81, 0.2);
    let (theta0, omega3) = (0.5f64, 5.0);
    let phid = c * omega3 * (1.0 - theta0.cos()) / (a * theta0.sin().powi(2));
    let rates = SVector::<f64, 3>::new(phid, -2.0, omega3 - phid * theta0.cos());
    let angles = SVector::<f64, 3>::new(0.0, theta0, 0.0);
    let rotation = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), theta0);
    let body = Vector3::new(
        rates[1], // θ̇ about the body's x at ψ = 0
        phid * theta0.sin(),
        omega3,
    );
    let (q0, v0) = quaternion::state(&rotation, &body);
    let top = HeavyTop::new(a, c, m, g, l);
    let times: Vec<f64> = (1..=1000).map(|k| 0.01 * k as f64).collect();
    let run = Dop853::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&top, 0.0, q0, v0, &times)?;
    let start = top.invariants(&q0, &v0);
    let mut worst = [0.0f64; 3];
    let mut highest = 0.0f64;
    for s in &run {
        let now = top.invariants(&s.q, &s.qdot);
        for k in 0..3 {
            worst[k] = worst[k].max((now[k] - start[k]).abs() / start[k].abs());
        }
        highest = highest.max(HeavyTop::axis(&s.q)[2]);
    }
    println!("\nA heavy top through the pole (L_z = L_3), 10 s, Dop853 at 1e-12:");
    println!(
        "  quaternions: the axis within {:.1e} of the vertical; energy, L_z, L_3 kept to {:.1e}, {:.1e}, {:.1e}",
        1.0 - highest,
        worst[0],
        worst[1],
        worst[2]
    );
    let euler = Dop853::new().rtol(1e-12).atol(1e-12).integrate(
        &EulerTop::new(a, c, m, g, l),
        0.0,
        angles,
        rates,
        &times,
    );
    match euler {
        Ok(_) => println!("  Euler angles: ran through (unexpected)"),
        Err(failure) => println!("  Euler angles: {}", failure.error),
    }
    Ok(())
}

/// The sleigh (m = 2, i = 0.3, a = 0.4) from speed 0.5 m/s turning at
/// 1.5 rad/s.
fn sleigh() -> Result<Vec<(f64, f64)>, Box<dyn Error>> {
    let sleigh = ChaplyginSleigh::new(2.0, 0.3, 0.4);
    let (q0, v0) = sleigh.state(0.5, 1.5);
    let times: Vec<f64> = (1..=200).map(|k| 0.05 * k as f64).collect();
    let run = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(&sleigh, 0.0, q0, v0, &times)?;
    println!("\nThe Chaplygin sleigh against v = V tanh(λt + c), ω = ω0 cosh c / cosh(λt + c):\n");
    println!("| t [s] | v | closed form | ω [rad/s] | closed form |");
    println!("|---:|---:|---:|---:|---:|");
    for s in run
        .iter()
        .filter(|s| (s.t * 20.0).round() as usize % 40 == 0)
    {
        let (v, w) = sleigh.closed_form(0.5, 1.5, s.t);
        println!(
            "| {:.0} | {:.12} | {:.12} | {:.3e} | {:.3e} |",
            s.t,
            ChaplyginSleigh::speed(&s.q, &s.qdot),
            v,
            s.qdot[2],
            w
        );
    }
    Ok(run.iter().map(|s| (s.q[0], s.q[1])).collect())
}

/// The disk (m = 1.5, r = 0.3): a steady circle, and upright rolling
/// nudged either side of the critical speed.
fn disk() -> Result<Vec<(f64, f64)>, Box<dyn Error>> {
    let (m, r, g) = (1.5, 0.3, 9.81);
    let disk = RollingDisk::new(m, r, g);
    let precession = disk.steady_precession(0.5, -6.0);
    let (q0, v0) = disk.state(0.5, 0.0, precession, -6.0);
    let times: Vec<f64> = (1..=400).map(|k| 0.025 * k as f64).collect();
    let circle = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(&disk, 0.0, q0, v0, &times)?;
    let lean = circle
        .iter()
        .map(|s| (s.q[3] - 0.5).abs())
        .fold(0.0, f64::max);
    println!(
        "\nA rolling disk leaning 0.5 rad at spin −6 rad/s, heading rate {precession:.9} rad/s \
         (the steady relation): over 10 s the lean stays within {lean:.1e} rad"
    );
    println!("\nUpright rolling nudged by a lean rate of 1e-3 rad/s (critical v² = g r / 3):\n");
    println!("| v² / (g r / 3) | largest lean over 20 s [rad] |");
    println!("|---:|---:|");
    let critical = g * r / 3.0;
    for ratio in [0.5, 0.8, 0.9, 0.95, 1.05, 1.1, 1.2, 2.0] {
        let v = (ratio * critical).sqrt();
        let (q0, v0) = disk.state(0.0, 1e-3, 0.0, -v / r);
        let times: Vec<f64> = (1..=400).map(|k| 0.05 * k as f64).collect();
        let run = Dop853::new()
            .rtol(1e-10)
            .atol(1e-12)
            .integrate(&disk, 0.0, q0, v0, &times);
        let trajectory = match run {
            Ok(t) => t,
            Err(failure) => failure.trajectory,
        };
        let largest = trajectory.iter().map(|s| s.q[3].abs()).fold(0.0, f64::max);
        println!("| {ratio} | {largest:.2e} |");
    }
    println!("\nThe same, linearized about upright rolling (analysis::linearize_steady_motion,");
    println!("kept: lean, lean rate, heading rate) against the closed form");
    println!(
        "A = [[0, 1, 0], [4g/5r, 0, -6w/5], [0, 2w, 0]], growth rate sqrt((4g - 12 w^2 r) / 5r):\n"
    );
    println!("| v² / (g r / 3) | max |A − closed form| | largest Re s | closed form |");
    println!("|---:|---:|---:|---:|");
    for ratio in [0.5, 0.99, 1.01, 2.0] {
        let omega0 = -(ratio * critical).sqrt() / r;
        let (q, qdot) = disk.state(0.0, 0.0, 0.0, omega0);
        let lin = linearize_steady_motion(&disk, 0.0, &q, &qdot, &["theta"], &["theta", "psi"])?;
        let exact = [
            [0.0, 1.0, 0.0],
            [4.0 * g / (5.0 * r), 0.0, -6.0 * omega0 / 5.0],
            [0.0, 2.0 * omega0, 0.0],
        ];
        let off = (0..9)
            .map(|k| (lin.state_matrix[(k / 3, k % 3)] - exact[k / 3][k % 3]).abs())
            .fold(0.0, f64::max);
        let growth = lin
            .eigenvalues()
            .iter()
            .map(|s| s.re)
            .fold(f64::MIN, f64::max);
        let s2 = (4.0 * g - 12.0 * omega0 * omega0 * r) / (5.0 * r);
        println!(
            "| {ratio} | {off:.1e} | {growth:.6} | {:.6} |",
            s2.max(0.0).sqrt()
        );
    }
    Ok(circle.iter().map(|s| (s.q[0], s.q[1])).collect())
}

/// A ball rolling in a unit quaternion, started from its orientation and
/// body rates by the library (the centre's velocity from the rolling
/// constraints): against the hand-made start of `RollingBall::state`, and
/// its roll over 2 s against the closed form.
fn rolling_ball() -> Result<(), Box<dyn Error>> {
    let ball = RollingBall::new(1.0, 0.1);
    let rotation = UnitQuaternion::from_euler_angles(0.3, -0.7, 1.1);
    let (velocity, spin) = (Vector2::new(0.3, -0.2), 1.5);
    let body = rotation.inverse() * ball.angular_velocity(&velocity, spin);
    let (q0, v0) = state_from_body_rates(
        &ball,
        0.0,
        &[("x", 0.0), ("y", 0.0)],
        &[],
        ["w", "a", "b", "c"],
        &rotation,
        &body,
    )?;
    let (q_hand, v_hand) = ball.state(&rotation, &velocity, spin);
    let run = Dop853::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&ball, 0.0, q0, v0, &[2.0])?;
    let end = run.last().expect("a sample");
    let exact = ball.rotation_at(&rotation, &velocity, spin, 2.0);
    println!("\n## A rolling ball started from its body rates\n");
    println!(
        "| start against the hand-made one (q, q̇) | constraints' velocity residuals | rotation after 2 s against the closed form |"
    );
    println!("|---:|---:|---:|");
    println!(
        "| {:.1e}, {:.1e} | {:.1e} | {:.1e} rad |",
        (q0 - q_hand).amax(),
        (v0 - v_hand).amax(),
        ball.constraint_velocities(0.0, &q0, &v0).amax(),
        RollingBall::rotation(&end.q).angle_to(&exact)
    );
    Ok(())
}

fn draw(
    path: &std::path::Path,
    rates: &[Rates],
    sleigh: &[(f64, f64)],
    disk: &[(f64, f64)],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (1200, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(640);
    let end = rates.last().map_or(1.0, |r| r.0);
    let mut chart = ChartBuilder::on(&left)
        .caption(
            "a free body flipping about its intermediate axis (body rates)",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(0.0..end, -2.0..2.0)?;
    chart
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc("rad/s")
        .draw()?;
    for (k, color) in [BLUE, RED, GREEN].into_iter().enumerate() {
        chart
            .draw_series(LineSeries::new(
                rates.iter().map(|(t, w)| (*t, w[k])),
                color.stroke_width(2),
            ))?
            .label(format!("omega{}", k + 1))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;

    let bounds = sleigh.iter().chain(disk).fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    let pad = 0.1 * (bounds.1 - bounds.0).max(bounds.3 - bounds.2);
    let mut paths = ChartBuilder::on(&right)
        .caption("paths on the plane (10 s)", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(
            bounds.0 - pad..bounds.1 + pad,
            bounds.2 - pad..bounds.3 + pad,
        )?;
    paths
        .configure_mesh()
        .x_desc("x [m]")
        .y_desc("y [m]")
        .draw()?;
    for (points, name, color) in [
        (sleigh, "Chaplygin sleigh (mass centre)", BLUE),
        (disk, "rolling disk (contact point)", RED),
    ] {
        paths
            .draw_series(LineSeries::new(
                points.iter().copied(),
                color.stroke_width(2),
            ))?
            .label(name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    paths
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
