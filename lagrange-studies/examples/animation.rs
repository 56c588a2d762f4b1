//! Animations drawn from a model's own `let`s: the double pendulum and the
//! four-bar linkage, each integrated once and drawn frame by frame as a
//! GIF, the joint positions read from `lets(t, q, q̇)` (the `x1, y1, x2, y2`
//! and `xa, ya, x2, y2` the models wrote), not derived again here.
//!
//! `cargo run --release -p lagrange-studies --example animation`
//!
//! Writes `docs/animation/double_pendulum.gif` and
//! `docs/animation/four_bar.gif`.

use lagrange::models::{DoublePendulum, FourBar};
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;
use plotters::prelude::*;
use std::error::Error;

const FPS: u32 = 25;
const SIZE: u32 = 240;
const LINK: RGBColor = RGBColor(40, 40, 40);
const BOB: RGBColor = RGBColor(214, 39, 40);
const TRAIL: RGBColor = RGBColor(31, 119, 180);

/// Sample times of an animation `seconds` long at `FPS`.
fn frames(seconds: f64) -> Vec<f64> {
    let n = (seconds * FPS as f64).round() as usize;
    (0..=n).map(|k| k as f64 / FPS as f64).collect()
}

type Area<'b> = DrawingArea<BitMapBackend<'b>, plotters::coord::Shift>;
type Range = plotters::coord::types::RangedCoordf64;
type Chart<'a, 'b> = ChartContext<'a, BitMapBackend<'b>, Cartesian2d<Range, Range>>;

/// An empty frame with `extent` metres each way around `centre`, no axes.
fn frame<'a, 'b>(
    root: &'a Area<'b>,
    centre: (f64, f64),
    extent: f64,
) -> Result<Chart<'a, 'b>, Box<dyn Error>> {
    root.fill(&WHITE)?;
    let (x, y) = centre;
    Ok(ChartBuilder::on(root)
        .margin(4)
        .build_cartesian_2d(x - extent..x + extent, y - extent..y + extent)?)
}

fn double_pendulum(path: &str) -> Result<(), Box<dyn Error>> {
    let model = DoublePendulum::unit();
    let (q0, v0) = (Vector2::new(2.0, 2.5), Vector2::zeros());
    let times = frames(6.0);
    let run = Dop853::new()
        .rtol(1e-10)
        .atol(1e-10)
        .integrate(&model, 0.0, q0, v0, &times)?;
    let root = BitMapBackend::gif(path, (SIZE, SIZE), 1000 / FPS)?.into_drawing_area();
    let mut trail: Vec<(f64, f64)> = Vec::new();
    for s in &run {
        let [x1, y1, x2, y2] = model.lets(s.t, &s.q, &s.qdot);
        trail.push((x2, y2));
        let mut chart = frame(&root, (0.0, 0.0), 2.15)?;
        let recent = trail.len().saturating_sub(2 * FPS as usize);
        chart.draw_series(LineSeries::new(
            trail[recent..].to_vec(),
            TRAIL.stroke_width(1),
        ))?;
        chart.draw_series(LineSeries::new(
            [(0.0, 0.0), (x1, y1), (x2, y2)],
            LINK.stroke_width(3),
        ))?;
        chart.draw_series([(x1, y1), (x2, y2)].map(|p| Circle::new(p, 6, BOB.filled())))?;
        chart.draw_series([Circle::new((0.0, 0.0), 3, BLACK.filled())])?;
        root.present()?;
    }
    println!("Wrote {path} ({} frames)", run.len());
    Ok(())
}

fn four_bar(path: &str) -> Result<(), Box<dyn Error>> {
    let model = FourBar::crank_rocker();
    let (q0, v0) = model
        .state(0.0, 2.0 * std::f64::consts::PI)
        .ok_or("the loop closes at 0")?;
    let times = frames(3.0);
    let run = Dop853::new()
        .rtol(1e-10)
        .atol(1e-10)
        .integrate(&model, 0.0, q0, v0, &times)
        .map_err(|f| f.error.to_string())?;
    let root = BitMapBackend::gif(path, (SIZE, SIZE), 1000 / FPS)?.into_drawing_area();
    let mut path_of_midpoint: Vec<(f64, f64)> = Vec::new();
    let (d, extent) = (model.d, 0.62);
    for s in &run {
        // The crank pin and the coupler's midpoint are the model's `let`s;
        // the coupler's far end is the pin mirrored through the midpoint.
        let [xa, ya, x2, y2] = model.lets(s.t, &s.q, &s.qdot);
        let (xb, yb) = (2.0 * x2 - xa, 2.0 * y2 - ya);
        path_of_midpoint.push((x2, y2));
        let mut chart = frame(&root, (d / 2.0, 0.2), extent)?;
        chart.draw_series(LineSeries::new(
            path_of_midpoint.clone(),
            TRAIL.stroke_width(1),
        ))?;
        chart.draw_series(LineSeries::new(
            [(0.0, 0.0), (xa, ya), (xb, yb), (d, 0.0)],
            LINK.stroke_width(3),
        ))?;
        chart.draw_series([Circle::new((x2, y2), 5, BOB.filled())])?;
        chart.draw_series([(0.0, 0.0), (d, 0.0)].map(|p| Circle::new(p, 4, BLACK.filled())))?;
        root.present()?;
    }
    println!("Wrote {path} ({} frames)", run.len());
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    const DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/animation");
    std::fs::create_dir_all(DIR)?;
    double_pendulum(&format!("{DIR}/double_pendulum.gif"))?;
    four_bar(&format!("{DIR}/four_bar.gif"))?;
    Ok(())
}
