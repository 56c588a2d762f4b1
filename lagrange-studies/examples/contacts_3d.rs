//! Contact in 3D: bodies touching a table with isotropic Coulomb friction
//! in its plane (`slip: vector(..)`), each scene of `lagrange::models`
//! against its closed form, printed as tables; the die beside MuJoCo where
//! the Python peer is installed.
//!
//! `cargo run --release -p lagrange-studies --example contacts_3d`
//!
//! MuJoCo runs through `LAGRANGE_PEERS_PYTHON` (else `python3`), which must
//! import `mujoco` (`pip install mujoco`); without it that row says so and
//! the rest runs.
//!
//! Writes `docs/contacts/contacts_3d.svg`: the ball thrown with backspin
//! (its velocity along the throw, which turns back once it rolls) and the
//! die coming to rest (its height and its energy); and
//! `docs/contacts/tippe_top.svg`: two tippe tops' tilts and Jellett's
//! integrals over time (Leine and Glocker's, which turns over part way,
//! and the same top with its moments exchanged, which turns over fully);
//! and prints how far the top turns, by its moments.

use lagrange::contact::{Cause, ContactSettings, ContactTrajectory};
use lagrange::models::{BallOnTable, Die, PushedPuck, TippeTop, quaternion};
use lagrange::nalgebra::{UnitQuaternion, Vector3};
use plotters::prelude::*;
use std::error::Error;
use std::process::Command;

#[path = "support/peers_python.rs"]
mod peers_python;

#[path = "support/contact_run.rs"]
mod contact_run;

use contact_run::{run, run_with};

fn main() -> Result<(), Box<dyn Error>> {
    println!(
        "scene                                        closed form              lagrange                 error"
    );
    let row = |scene: &str, exact: f64, ours: f64| {
        println!(
            "{scene:<44} {exact:<24.16} {ours:<24.16} {:.1e}",
            (ours - exact).abs()
        );
    };

    // A puck pushed at 5.6° (the middle of a side of the 32-gon that
    // stands for the disc in the decisions): it holds while the push is
    // inside the disc of friction and breaks away where it leaves it.
    let (m, g, mu) = (1.0, 9.81, 0.5);
    let puck = PushedPuck::new(
        m,
        g,
        mu,
        core::f64::consts::PI / 32.0,
        0.9 * mu * m * g,
        0.5,
    );
    let end = puck.breakaway() + 2.0;
    let pushed = run(&puck, ([0.0; 3], [0.0; 3]), end, 100)?;
    let breakaway = pushed
        .switches()
        .iter()
        .find(|s| s.cause == Cause::StickLimit)
        .ok_or("the puck never broke away")?;
    row(
        "puck pushed at 5.6°: breaks away at",
        puck.breakaway(),
        breakaway.t,
    );
    let last = pushed.trajectory().last().unwrap();
    row(
        "                     slid by the end",
        puck.slid(end),
        last.q[0].hypot(last.q[1]),
    );

    // A uniform ball thrown along x with backspin about −y: it slides,
    // then rolls at (5 v₀ − 2 r ω₀)/7, back towards the thrower where
    // 2 r ω₀ > 5 v₀.
    let ball = BallOnTable::new(0.2, 0.1, 9.81, 0.3, 0.0);
    let mut backspun = None;
    for spin in [20.0, 100.0] {
        let (v0, w0) = (Vector3::new(3.0, 0.0, 0.0), Vector3::new(0.0, -spin, 0.0));
        let t_roll = ball.rolling_time(&v0, &w0);
        let thrown = run(&ball, ball.thrown(&v0, &w0), 2.0 * t_roll, 200)?;
        let rolls = thrown
            .switches()
            .iter()
            .find(|s| s.cause == Cause::SlideStopped)
            .ok_or("the ball never rolled")?;
        row(
            &format!("ball, v₀ = 3, backspin {spin}: rolls at"),
            t_roll,
            rolls.t,
        );
        row(
            "                               at the speed",
            ball.rolling_velocity(&v0, &w0)[0],
            thrown.trajectory().last().unwrap().qdot[0],
        );
        if spin == 100.0 {
            backspun = Some((thrown, t_roll));
        }
    }
    let (backspun, t_roll) = backspun.unwrap();

    // A die thrown spinning from 10 cm: it bounces, tumbles and rests.
    let die = Die::new(0.01, 0.016, 9.81, 0.3, 0.4);
    let turned = UnitQuaternion::from_euler_angles(0.5, 0.3, 0.2);
    let (q, qdot) = quaternion::state(&turned, &Vector3::new(8.0, -5.0, 12.0));
    let start = (
        [0.0, 0.0, 0.1, q[0], q[1], q[2], q[3]],
        [0.5, 0.2, 0.0, qdot[0], qdot[1], qdot[2], qdot[3]],
    );
    // At 1e-13: resting on a face, its stuck accelerations are rounding,
    // and what it creeps in steps of seconds is the method's error
    // (1.4e-12 m in 10 s at 1e-12, 7.9e-13 at 1e-13, 2.4e-13 at 1e-14).
    let thrown = run_with(&die, start, 12.0, 4800, 1e-13, ContactSettings::default())?;
    let die_row = die_measures(&die, &thrown, &start);
    let impacts = thrown
        .switches()
        .iter()
        .filter(|s| s.cause == Cause::Impact)
        .count();
    println!(
        "\ndie thrown spinning (side 16 mm, 10 g, e = 0.3, μ = 0.4), 12 s: {impacts} impacts, {} \
         switches, {} steps; at rest its normal forces hold m g to {:.1e}",
        thrown.switches().len(),
        thrown.trajectory().stats().steps_accepted,
        (thrown.forces().last().unwrap().normal.sum() - 0.01 * 9.81).abs() / (0.01 * 9.81)
    );
    println!(
        "{:<48} {:<13} {:<13} {:<13} {:<13}",
        "", "creep [m]", "deepest [m]", "sunk at rest", "energy rise"
    );
    println!(
        "{:<48} {:<13.1e} {:<13.1e} {:<13.1e} {:.1e}",
        "lagrange (Dop853 at 1e-13)", die_row.0, die_row.1, die_row.2, die_row.3
    );
    mujoco_die(&q)?;

    // The tippe top, spun about the vertical, turns over while it slides:
    // Leine and Glocker's part way (its slip stops at 155°), the same top
    // with its moments exchanged fully. Its slip comes to rest turning with
    // the precession, where Coulomb's law is stiff: `direction_speed` 1e-4
    // m/s (at the default 1e-6 the run takes its 100,000 steps at the
    // stop).
    let settings = ContactSettings {
        direction_speed: 1e-4,
        ..ContactSettings::default()
    };
    let mut tops = Vec::new();
    for (name, top) in [
        ("Leine and Glocker's", TippeTop::leine_glocker(0.1)),
        ("oblate", TippeTop::oblate(0.1)),
    ] {
        let spun = top.spun(0.1, 180.0);
        let turning = run_with(&top, spun, 5.0, 1000, 1e-13, settings)?;
        let j0 = top.jellett(&spun.0.into(), &spun.1.into());
        let e0 = top.energy(0.0, &spun.0.into(), &spun.1.into());
        let (mut jellett, mut rise, mut previous) = (0.0f64, 0.0f64, e0);
        let mut horizontal = None;
        for sample in turning.trajectory().iter() {
            jellett = jellett.max((top.jellett(&sample.q, &sample.qdot) - j0).abs() / j0.abs());
            let energy = top.energy(sample.t, &sample.q, &sample.qdot);
            rise = rise.max(energy - previous);
            previous = energy;
            if horizontal.is_none() && top.tilt(&sample.q) > core::f64::consts::FRAC_PI_2 {
                horizontal = Some(sample.t);
            }
        }
        let rolls = turning
            .switches()
            .iter()
            .find(|s| s.cause == Cause::SlideStopped)
            .ok_or("the tippe top never stopped slipping")?;
        println!(
            "\ntippe top ({name}, C/A = {:.3}, μ = 0.1), tilted 0.1 rad, 180 rad/s about the \
             vertical, 5 s with Dop853 at 1e-13: through the horizontal by {:.3} s (samples every 5 ms), its slip stops \
             at {:.4} s at a tilt of {:.4} rad ({:.1}°), then it rolls; Jellett's integral kept \
             to {jellett:.1e} relative, the energy's largest rise between samples {:.1e} of the \
             start's; {} steps",
            top.i3 / top.i1,
            horizontal.ok_or("the tippe top never turned over")?,
            rolls.t,
            top.tilt(&rolls.q),
            top.tilt(&rolls.q).to_degrees(),
            rise / e0,
            turning.trajectory().stats().steps_accepted
        );
        tops.push((name, top, turning, j0));
    }
    // How far the top turns before its slip stops, by its moments: the
    // moment along the axis varied, that across it 8e-7 kg m² (7e-7 for
    // the oblate top's 8/7), spun alike.
    println!("\nC/A      tilt where the slip stops [rad]");
    for (i1, i3) in [
        (8e-7, 6.6e-7),
        (8e-7, 7e-7),
        (8e-7, 7.8e-7),
        (8e-7, 8e-7),
        (8e-7, 8.4e-7),
        (8e-7, 8.8e-7),
        (7e-7, 8e-7),
    ] {
        let top = TippeTop::new(6e-3, 0.015, 0.003, i1, i3, 9.81, 0.1);
        let turning = run_with(&top, top.spun(0.1, 180.0), 6.0, 10, 1e-12, settings)?;
        let stop = turning
            .switches()
            .iter()
            .find(|s| s.cause == Cause::SlideStopped)
            .map_or(f64::NAN, |s| top.tilt(&s.q));
        println!("{:<8.3} {stop:.4}", i3 / i1);
    }

    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/contacts/contacts_3d.svg");
    std::fs::create_dir_all(path.parent().unwrap())?;
    draw(&path, (&backspun, t_roll), (&die, &thrown))?;
    println!("\nwrote {}", path.display());
    let path = path.with_file_name("tippe_top.svg");
    draw_top(&path, &tops)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// The tippe tops' tilts, and their Jellett's integrals' relative changes.
fn draw_top(
    path: &std::path::Path,
    tops: &[(&str, TippeTop<f64>, ContactTrajectory<f64, 7, 1>, f64)],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (1200, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(600);
    let mut chart = ChartBuilder::on(&left)
        .caption("tippe tops: the tilt of the axis", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..5.0, 0.0..core::f64::consts::PI)?;
    chart
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc("tilt [rad]")
        .draw()?;
    let colours = [BLUE, GREEN];
    for ((name, top, run, _), colour) in tops.iter().zip(colours) {
        chart
            .draw_series(LineSeries::new(
                run.trajectory().iter().map(|s| (s.t, top.tilt(&s.q))),
                colour.stroke_width(2),
            ))?
            .label(format!("{name}, C/A = {:.3}", top.i3 / top.i1))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], colour));
    }
    chart.draw_series(LineSeries::new(
        [
            (0.0, core::f64::consts::FRAC_PI_2),
            (5.0, core::f64::consts::FRAC_PI_2),
        ],
        BLACK.mix(0.4).stroke_width(1),
    ))?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    let mut chart = ChartBuilder::on(&right)
        .caption(
            "Jellett's integral L_G · (P − G): relative change",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..5.0, -1e-10..1e-10)?;
    chart
        .configure_mesh()
        .x_desc("t [s]")
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()?;
    for ((_, top, run, j0), colour) in tops.iter().zip(colours) {
        chart.draw_series(LineSeries::new(
            run.trajectory()
                .iter()
                .map(|s| (s.t, (top.jellett(&s.q, &s.qdot) - j0) / j0)),
            colour.stroke_width(2),
        ))?;
    }
    root.present()?;
    Ok(())
}

/// The die's creep from 2 s on, 10 s at rest (the largest displacement of a corner
/// along the table), its deepest corner below the table, how deep it sits
/// at the end, and the largest rise of its energy between samples
/// relative to the start's.
fn die_measures(
    die: &Die<f64>,
    run: &ContactTrajectory<f64, 7, 8>,
    start: &([f64; 7], [f64; 7]),
) -> (f64, f64, f64, f64) {
    let e0 = die.energy(0.0, &start.0.into(), &start.1.into());
    let (mut deepest, mut rise, mut previous) = (0.0f64, 0.0f64, e0);
    let mut creep = 0.0f64;
    let mut first = None;
    for sample in run.trajectory().iter() {
        deepest = deepest.min(die.gaps(sample.t, &sample.q).min());
        let energy = die.energy(sample.t, &sample.q, &sample.qdot);
        rise = rise.max(energy - previous);
        previous = energy;
        if sample.t >= 2.0 {
            let corners = die.corners(&sample.q);
            let first = first.get_or_insert(corners);
            for (now, then) in corners.iter().zip(first.iter()) {
                creep = creep.max((now.xy() - then.xy()).norm());
            }
        }
    }
    let last = run.trajectory().last().unwrap();
    let sunk = -die.gaps(last.t, &last.q).min();
    (creep, -deepest, sunk.max(0.0), rise / e0)
}

/// The same throw in MuJoCo, at its defaults and with its anti-slip
/// settings, its rows printed beside the project's.
fn mujoco_die(q: &lagrange::nalgebra::Vector4<f64>) -> Result<(), Box<dyn Error>> {
    let script =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/contacts/die_mujoco.py");
    let python = match peers_python::importing("mujoco, numpy") {
        Ok(python) => python,
        Err(why) => {
            println!("MuJoCo: skipped: {why}");
            return Ok(());
        }
    };
    let out = Command::new(&python)
        .arg(&script)
        .args([q[0], q[1], q[2], q[3]].map(|x| format!("{x:.17e}")))
        .output()?;
    if !out.status.success() {
        println!(
            "MuJoCo: failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        );
        return Ok(());
    }
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        if let [label, creep, deepest, sunk, rise, _energy] =
            line.split(';').collect::<Vec<_>>()[..]
        {
            println!("{label:<48} {creep:<13} {deepest:<13} {sunk:<13} {rise}");
        }
    }
    Ok(())
}

fn draw(
    path: &std::path::Path,
    (ball, t_roll): (&ContactTrajectory<f64, 7, 1>, f64),
    (die, thrown): (&Die<f64>, &ContactTrajectory<f64, 7, 8>),
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (1200, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(600);
    let mut chart = ChartBuilder::on(&left)
        .caption(
            "ball thrown at 3 m/s with backspin 100 rad/s",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..2.0 * t_roll, -2.0..3.5)?;
    chart.configure_mesh().x_desc("t [s]").draw()?;
    let times = ball.trajectory().times();
    chart
        .draw_series(LineSeries::new(
            times
                .iter()
                .zip(ball.trajectory().velocities())
                .map(|(t, v)| (*t, v[0])),
            BLUE.stroke_width(2),
        ))?
        .label("velocity along the throw [m/s]")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    chart
        .draw_series(LineSeries::new(
            [(t_roll, -2.0), (t_roll, 3.5)],
            GREEN.stroke_width(1),
        ))?
        .label("rolls from 2|s₀|/(7 μ g)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], GREEN));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;

    let mut chart = ChartBuilder::on(&right)
        .caption("die thrown spinning from 10 cm", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..0.5, 0.0..12.0)?;
    chart.configure_mesh().x_desc("t [s]").draw()?;
    let samples: Vec<_> = thrown.trajectory().iter().filter(|s| s.t <= 0.5).collect();
    chart
        .draw_series(LineSeries::new(
            samples.iter().map(|s| (s.t, 100.0 * s.q[2])),
            BLUE.stroke_width(2),
        ))?
        .label("centre's height [cm]")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    chart
        .draw_series(LineSeries::new(
            samples
                .iter()
                .map(|s| (s.t, 1e3 * die.energy(s.t, &s.q, &s.qdot))),
            RED.stroke_width(2),
        ))?
        .label("energy [mJ]")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
