//! Contacts and friction (`contacts:`), each scene against its closed
//! form, printed as tables; the block that must stay put on an incline
//! beside MuJoCo where the Python peer is installed.
//!
//! `cargo run --release -p lagrange-studies --example contacts`
//!
//! MuJoCo runs through `LAGRANGE_PEERS_PYTHON` (else `python3`), which must
//! import `mujoco` (`python3 -m venv ../peers-venv && ../peers-venv/bin/pip
//! install mujoco`); without it that column says so and the rest runs.
//!
//! Writes `docs/contacts/contacts.svg`: the block on a belt sticking and
//! slipping (its position and friction force), and the ball coming to
//! rest (its height and the floor's force).

use lagrange::contact::{self, Cause, Mode};
use lagrange::models::{
    BallOnFloor, BlockOnBelt, BlockOnIncline, BobOnString, Ladder, ParticleOnSphere, SlidingBall,
    TorsionBearing, TumblingBox,
};
use plotters::prelude::*;
use std::error::Error;
use std::process::Command;

#[allow(dead_code)]
#[path = "support/contact_run.rs"]
mod contact_run;

use contact_run::run;

fn main() -> Result<(), Box<dyn Error>> {
    println!(
        "scene                                   closed form              lagrange                 error"
    );
    let row = |scene: &str, exact: f64, ours: f64| {
        println!(
            "{scene:<39} {exact:<24.16} {ours:<24.16} {:.1e}",
            (ours - exact).abs()
        );
    };

    let sphere = ParticleOnSphere::new(1.0, 9.81, 1.0);
    let leaves = run(&sphere, sphere.at_rest(0.4), 2.0, 20)?;
    let release = leaves
        .switches()
        .iter()
        .find(|s| s.cause == Cause::Release)
        .unwrap();
    row(
        "sphere (θ₀ = 0.4): cos θ at release",
        ParticleOnSphere::release_angle(0.4).cos(),
        (release.q[0].atan2(release.q[1])).cos(),
    );

    let ladder = Ladder::new(5.0, 3.0, 9.81);
    let slides = run(&ladder, ladder.at_rest(1.0), 3.0, 30)?;
    let release = slides
        .switches()
        .iter()
        .find(|s| s.cause == Cause::Release)
        .unwrap();
    row(
        "ladder (θ₀ = 1): top height / start",
        2.0 / 3.0,
        release.q[2].sin() / 1f64.sin(),
    );

    let bob = BobOnString::new(0.5, 9.81, 1.2);
    let v0 = (3.5f64 * 9.81 * 1.2).sqrt();
    let whirled = run(&bob, bob.whirled(v0), 3.0, 30)?;
    let slack = whirled
        .switches()
        .iter()
        .find(|s| s.cause == Cause::Release)
        .unwrap();
    row(
        "string (v₀² = 3.5 g l): slack angle",
        bob.slack_angle(v0),
        slack.q[0].atan2(-slack.q[1]),
    );
    let taut = whirled
        .switches()
        .iter()
        .find(|s| s.cause == Cause::Impact)
        .unwrap();
    println!(
        "{:<39} snaps taut at t = {:.6} s, the impact takes {:.6} J",
        "", taut.t, taut.energy_lost
    );

    let ball = BallOnFloor::new(1.0, 9.81, 0.5);
    let bounces = run(&ball, ([0.0, 1.0], [0.0, 0.0]), 2.0, 400)?;
    let rest = bounces.switches().last().unwrap();
    row("ball (e = 1/2): time of rest", ball.rest_time(1.0), rest.t);
    let impacts = bounces
        .switches()
        .iter()
        .filter(|s| s.cause == Cause::Impact)
        .count();
    println!(
        "{:<39} after {impacts} bounces, then N = {:.15} N",
        "",
        bounces.forces().last().unwrap().normal[0]
    );

    let rolling = SlidingBall::new(0.3, 0.05, 9.81, 0.2);
    let thrown = run(&rolling, rolling.thrown(3.0), 2.0, 20)?;
    let rolls = thrown
        .switches()
        .iter()
        .find(|s| s.cause == Cause::SlideStopped)
        .unwrap();
    row(
        "sliding ball (v₀ = 3): starts rolling at",
        rolling.rolling_time(3.0),
        rolls.t,
    );
    row(
        "                       at the speed",
        SlidingBall::rolling_speed(3.0),
        rolls.qdot[0],
    );

    let belt = BlockOnBelt::new(1.0, 9.81, 40.0, 0.3, 0.6, 0.4);
    let cycle = belt.cycle();
    let stick_slip = run(&belt, ([0.0, 0.0], [0.3, 0.0]), 6.0, 1200)?;
    let switches: Vec<_> = stick_slip
        .switches()
        .iter()
        .filter(|s| s.cause != Cause::Start)
        .collect();
    row("belt: first slip at", cycle.slips_at / 0.3, switches[0].t);
    row(
        "      sticks again at",
        cycle.slips_at / 0.3 + cycle.slip_duration,
        switches[1].t,
    );
    row(
        "      slips again at",
        cycle.slips_at / 0.3 + cycle.slip_duration + cycle.stick_duration,
        switches[2].t,
    );

    // Friction in a joint, against a given load: the torsion pendulum's
    // turning points lose 2 μ_k F r / κ each, and it sticks where static
    // friction holds the spring.
    let bearing = TorsionBearing::new(0.5, 2.0, 1.0, 0.1, 0.4, 0.3);
    let swings = bearing.swings(0.205);
    let damped = run(&bearing, ([0.205], [0.0]), 14.0, 140)?;
    let turns: Vec<_> = damped
        .switches()
        .iter()
        .filter(|s| s.cause == Cause::SlideStopped)
        .collect();
    let last = swings.last().expect("it slips");
    let stuck = turns.last().expect("it sticks");
    row(
        "bearing: sticks at (time)",
        last.start + core::f64::consts::FRAC_PI_2,
        stuck.t,
    );
    row("         sticks at (angle)", last.to, stuck.q[0]);

    // The box: no penetration, energy only lost.
    let tumbling = TumblingBox::new(2.0, 0.6, 0.3, 9.81, 0.4, 0.5);
    let start = ([0.0, 0.5, 0.3], [0.8, 0.0, 4.0]);
    let dropped = run(&tumbling, start, 3.0, 3000)?;
    let (mut deepest, mut rise) = (0.0f64, 0.0f64);
    let mut previous = tumbling.energy(0.0, &start.0.into(), &start.1.into());
    for sample in dropped.trajectory().iter() {
        deepest = deepest.min(tumbling.gaps(sample.t, &sample.q).min());
        let e = tumbling.energy(sample.t, &sample.q, &sample.qdot);
        rise = rise.max(e - previous);
        previous = e;
    }
    let struck = dropped
        .switches()
        .iter()
        .filter(|s| s.cause == Cause::Impact)
        .count();
    println!(
        "\ntumbling box: {} switches ({struck} corner impacts), deepest corner {deepest:.1e} m, \
         largest energy rise between samples {rise:.1e} J (of {:.2} J)",
        dropped.switches().len(),
        tumbling.energy(0.0, &start.0.into(), &start.1.into())
    );

    incline()?;

    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/contacts/contacts.svg");
    std::fs::create_dir_all(path.parent().unwrap())?;
    draw(&path, &stick_slip, &bounces)?;
    println!("\nwrote {}", path.display());
    Ok(())
}

/// The block that must stay put on an incline (μ = 1, tilted by 20° and
/// 30°): how far it moves in 10 s and how deep it sinks, here and in
/// MuJoCo.
fn incline() -> Result<(), Box<dyn Error>> {
    println!("\nblock on an incline, mu = 1, 10 s                     creep [m]   penetration [m]");
    for degrees in [20.0f64, 30.0] {
        let block = BlockOnIncline::new(1.0, 9.81, degrees.to_radians(), 1.0, 1.0);
        let stays = run(&block, ([0.0, 0.0], [0.0, 0.0]), 10.0, 100)?;
        let last = stays.trajectory().last().unwrap();
        let sink = stays
            .trajectory()
            .iter()
            .map(|s| -s.q[1])
            .fold(0.0f64, f64::max);
        assert_eq!(stays.modes().last().unwrap()[0], Mode::Stuck);
        let label = format!("lagrange, {degrees}°");
        println!("{label:<53} {:<11.1e} {sink:.1e}", last.q[0]);
    }
    let python = std::env::var("LAGRANGE_PEERS_PYTHON").unwrap_or_else(|_| "python3".into());
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/contacts/incline_mujoco.py");
    match Command::new(&python).arg(&script).output() {
        Ok(out) if out.status.success() => {
            for line in String::from_utf8_lossy(&out.stdout).lines() {
                let f: Vec<&str> = line.split(';').collect();
                if let [label, degrees, creep, sink] = f[..] {
                    let label = format!("{label}, {degrees}°");
                    println!("{label:<53} {creep:<11} {sink}");
                }
            }
        }
        _ => println!(
            "MuJoCo: skipped: `{python}` cannot run {} (set LAGRANGE_PEERS_PYTHON to a Python with `mujoco`)",
            script.display()
        ),
    }
    Ok(())
}

fn draw(
    path: &std::path::Path,
    belt: &contact::ContactTrajectory<f64, 2, 1>,
    ball: &contact::ContactTrajectory<f64, 2, 1>,
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (1200, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(600);
    let mut chart = ChartBuilder::on(&left)
        .caption("block on a belt: stick and slip", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..6.0, -0.5..7.0)?;
    chart.configure_mesh().x_desc("t [s]").draw()?;
    let times = belt.trajectory().times();
    chart
        .draw_series(LineSeries::new(
            times
                .iter()
                .zip(belt.trajectory().positions())
                .map(|(t, q)| (*t, 20.0 * q[0])),
            BLUE.stroke_width(2),
        ))?
        .label("x [5 cm]")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    chart
        .draw_series(LineSeries::new(
            times
                .iter()
                .zip(belt.forces())
                .map(|(t, f)| (*t, f.friction[0])),
            RED.stroke_width(2),
        ))?
        .label("friction [N]")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED.stroke_width(2)));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;

    let mut chart = ChartBuilder::on(&right)
        .caption(
            "ball, e = 1/2: bounces that end in rest",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..2.0, 0.0..10.5)?;
    chart.configure_mesh().x_desc("t [s]").draw()?;
    let times = ball.trajectory().times();
    chart
        .draw_series(LineSeries::new(
            times
                .iter()
                .zip(ball.trajectory().positions())
                .map(|(t, q)| (*t, 10.0 * q[1])),
            BLUE.stroke_width(2),
        ))?
        .label("z [10 cm]")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    chart
        .draw_series(LineSeries::new(
            times
                .iter()
                .zip(ball.forces())
                .map(|(t, f)| (*t, f.normal[0])),
            RED.stroke_width(2),
        ))?
        .label("N [N]")
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
