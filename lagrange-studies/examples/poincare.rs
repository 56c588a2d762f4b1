//! A Poincaré section of the double pendulum: the state at each upward
//! pass of the upper rod through the vertical, `θ₁ = 0` rising, located by
//! an event that only records, for a dozen orbits of one energy.
//!
//! `cargo run --release -p lagrange-studies --example poincare`
//!
//! Writes `docs/poincare/poincare.svg`: `(θ₂, θ̇₂)` at every crossing.
//! Regular orbits draw closed curves (their invariant tori cut by the
//! section), chaotic ones fill a region.

use lagrange::models::DoublePendulum;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;
use plotters::prelude::*;
use std::error::Error;

/// How long each orbit is followed.
const END: f64 = 500.0;
/// The energy of every orbit, in joules: 9.4 J above the rest state
/// (`−3 g` for unit masses and rods), where regular orbits and a chaotic
/// one live side by side.
const ENERGY: f64 = -20.0;

fn main() -> Result<(), Box<dyn Error>> {
    let pendulum = DoublePendulum::unit();
    let g = pendulum.g;
    let method = Dop853::new().rtol(1e-11).atol(1e-11).max_steps(10_000_000);
    println!("Double pendulum (unit masses and rods), E = {ENERGY} J, {END} s per orbit,");
    println!("Dop853 at 1e-11; crossings of theta1 = 0 upwards (an event that records):\n");
    println!("theta2(0)  crossings  max |E - E0| at the crossings  section evals per step");
    let mut orbits = Vec::new();
    for k in 0..12 {
        // Start on the section itself, θ₁ = 0, at rest in θ₂: T = θ̇₁²
        // there, so θ̇₁ = √(E − V) sets the energy.
        let theta2 = -1.1 + 0.2 * k as f64;
        let potential = -2.0 * g - g * theta2.cos();
        let q0 = Vector2::new(0.0, theta2);
        let v0 = Vector2::new((ENERGY - potential).sqrt(), 0.0);
        let section = Event::new("theta1 = 0", |_, q: &Vector2<f64>, _: &_| q[0]).rising();
        let events = Events::new().with(section);
        let run = method.integrate_with_events(&pendulum, 0.0, q0, v0, &[END], &events)?;
        let e0 = pendulum.energy(0.0, &q0, &v0);
        let points: Vec<(f64, f64)> = run
            .events()
            .iter()
            .map(|c| (wrap(c.q[1]), c.qdot[1]))
            .collect();
        let drift = run
            .events()
            .iter()
            .map(|c| (pendulum.energy(c.t, &c.q, &c.qdot) - e0).abs())
            .fold(0.0, f64::max);
        let stats = run.stats();
        println!(
            "{theta2:>9.2}  {:>9}  {drift:>29.1e}  {:>22.1}",
            points.len(),
            stats.event_evals as f64 / stats.steps_accepted as f64
        );
        orbits.push(points);
    }
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/poincare/poincare.svg");
    std::fs::create_dir_all(path.parent().unwrap())?;
    draw(&path, &orbits)?;
    println!("\nWrote {}", path.display());
    Ok(())
}

/// An angle in `(−π, π]`.
fn wrap(angle: f64) -> f64 {
    let turn = std::f64::consts::TAU;
    angle - turn * (angle / turn).round()
}

fn draw(path: &std::path::Path, orbits: &[Vec<(f64, f64)>]) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (900, 700)).into_drawing_area();
    root.fill(&WHITE)?;
    let (x_max, y_max) = orbits.iter().flatten().fold((0.0f64, 0.0f64), |(x, y), p| {
        (x.max(p.0.abs()), y.max(p.1.abs()))
    });
    let (x_max, y_max) = (x_max * 1.05, y_max * 1.05);
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("Double pendulum, Poincaré section theta1 = 0 rising, E = {ENERGY} J"),
            ("sans-serif", 22),
        )
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(-x_max..x_max, -y_max..y_max)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("theta2 [rad]")
        .y_desc("theta2' [rad/s]")
        .draw()?;
    for (k, points) in orbits.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 1, color.filled())))?;
    }
    root.present()?;
    Ok(())
}
