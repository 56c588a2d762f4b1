//! A scene as a game would run it: several independent models stepped side by
//! side, one call per frame at a fixed 60 Hz, in `f32`, with cheap methods,
//! each model in a `lagrange::Stepper` that owns its state and allocates
//! nothing per frame; and the same chain in `f64` with Dormand–Prince at a
//! tight tolerance as the reference. The generated models are generic over
//! the scalar, so the game-rate chain is the reference's `Chain` at `f32`.
//!
//! Prints the tip error of each game-rate run against its reference and what
//! each run cost, and draws `docs/scene/scene.svg`: snapshots of the chains,
//! the tip paths, and the tip error over time. What a frame costs, against
//! one `integrate` call per frame, is measured by `cargo bench -p lagrange-studies --bench
//! frame`.
//!
//! `cargo run --release -p lagrange-studies --example scene`

use lagrange::StepMethod;
use lagrange::models::{Chain, DoublePendulum};
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use plotters::prelude::*;
use std::error::Error;
use std::time::Instant;

/// The links of `lagrange::models::Chain`.
const N: usize = Chain::<f64>::DOF;
const HZ: usize = 60;
const FRAMES: usize = 4 * HZ;

/// Joint positions from the pivot to the tip, in `f64` whatever the model's
/// scalar.
fn joints<S: Copy + Into<f64>>(lengths: &[S], angles: &[S]) -> Vec<(f64, f64)> {
    let mut p = (0.0, 0.0);
    let mut out = vec![p];
    for (&l, &a) in lengths.iter().zip(angles) {
        let (l, a): (f64, f64) = (l.into(), a.into());
        p = (p.0 + l * a.sin(), p.1 - l * a.cos());
        out.push(p);
    }
    out
}

/// One model's run: its joints at every frame, and what it cost.
struct Run {
    label: &'static str,
    frames: Vec<Vec<(f64, f64)>>,
    rhs_evals: usize,
    seconds: f64,
}

impl Run {
    fn tip(&self, frame: usize) -> (f64, f64) {
        *self.frames[frame].last().unwrap_or(&(0.0, 0.0))
    }
}

/// Steps a model frame by frame in a `Stepper`, one `advance` per frame, as
/// a game loop would.
fn game_loop<S, L, M, const D: usize>(
    label: &'static str,
    model: L,
    method: M,
    (q0, qdot0): (SVector<S, D>, SVector<S, D>),
    lengths: &[S],
) -> Result<Run, Box<dyn Error>>
where
    S: lagrange::nalgebra::RealField + Copy + Into<f64>,
    L: Lagrangian<D, Scalar = S>,
    M: StepMethod<S>,
    lagrange::IntegrationError<S, D>: Error + 'static,
{
    // Frame k ends at k/60 s, rounded once to S (accumulating `dt` in f32
    // would drift the clock by rounding).
    let frame_time = |k: usize| lagrange::nalgebra::convert::<f64, S>(k as f64 / HZ as f64);
    let mut states = Vec::with_capacity(FRAMES + 1);
    states.push(q0);
    let mut stepper = Stepper::new(model, method, S::zero(), q0, qdot0)?;
    let clock = Instant::now();
    for k in 1..=FRAMES {
        stepper.advance_to(frame_time(k))?;
        states.push(*stepper.q());
    }
    let seconds = clock.elapsed().as_secs_f64();
    let frames = states
        .iter()
        .map(|q| joints(lengths, q.as_slice()))
        .collect();
    Ok(Run {
        label,
        frames,
        rhs_evals: stepper.stats().rhs_evals,
        seconds,
    })
}

/// The `f64` reference: one adaptive run sampled at every frame.
fn reference<L: Lagrangian<D, Scalar = f64>, const D: usize>(
    label: &'static str,
    model: &L,
    (q0, qdot0): (SVector<f64, D>, SVector<f64, D>),
    lengths: &[f64],
) -> Result<Run, Box<dyn Error>> {
    let times: Vec<f64> = (1..=FRAMES).map(|k| k as f64 / HZ as f64).collect();
    let clock = Instant::now();
    let trajectory = Dopri5::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(model, 0.0, q0, qdot0, &times)?;
    let seconds = clock.elapsed().as_secs_f64();
    let states = std::iter::once(q0).chain(trajectory.positions().iter().copied());
    let frames = states.map(|q| joints(lengths, q.as_slice())).collect();
    let rhs_evals = trajectory.stats().rhs_evals;
    Ok(Run {
        label,
        frames,
        rhs_evals,
        seconds,
    })
}

fn main() -> Result<(), Box<dyn Error>> {
    // A one-metre, one-kilogram chain in five links, released bent.
    let (lengths, lengths32) = ([0.2; N], [0.2f32; N]);
    let chain = Chain::new([0.2; N], lengths);
    let chain32 = Chain::<f32>::new([0.2; N], lengths32);
    let bent = [1.6, 1.4, 1.2, 1.0, 0.8];
    let released = (SVector::<f64, N>::from(bent), SVector::zeros());
    let released32 = (
        SVector::<f32, N>::from(bent.map(|a| a as f32)),
        SVector::zeros(),
    );
    let h = 1.0 / HZ as f32;

    let chain_ref = reference("chain, f64 Dopri5 1e-12", &chain, released, &lengths)?;
    let chains = [
        game_loop(
            "chain, f32 Rk4 60 Hz",
            chain32,
            Rk4::new(h),
            released32,
            &lengths32,
        )?,
        game_loop(
            "chain, f64 Rk4 60 Hz",
            chain,
            Rk4::new(1.0 / HZ as f64),
            released,
            &lengths,
        )?,
        game_loop(
            "chain, f32 SymplecticEuler 60 Hz",
            chain32,
            SymplecticEuler::new(h),
            released32,
            &lengths32,
        )?,
    ];

    // A double pendulum alongside, on its own reference.
    let pendulum = DoublePendulum::new(1.0, 1.0, 0.5, 0.5, 9.81);
    let pendulum32 = DoublePendulum::<f32>::new(1.0, 1.0, 0.5, 0.5, 9.81);
    let start = (SVector::<f64, 2>::new(1.0, 1.5), SVector::zeros());
    let start32 = (SVector::<f32, 2>::new(1.0, 1.5), SVector::zeros());
    let pendulum_ref = reference(
        "double pendulum, f64 Dopri5 1e-12",
        &pendulum,
        start,
        &[0.5, 0.5],
    )?;
    let pendulum_game = game_loop(
        "double pendulum, f32 Rk4 60 Hz",
        pendulum32,
        Rk4::new(h),
        start32,
        &[0.5f32, 0.5],
    )?;

    let games: Vec<(&Run, &Run)> = chains
        .iter()
        .map(|run| (run, &chain_ref))
        .chain(std::iter::once((&pendulum_game, &pendulum_ref)))
        .collect();
    let error = |(run, reference): (&Run, &Run), k: usize| {
        let (a, b) = (run.tip(k), reference.tip(k));
        (a.0 - b.0).hypot(a.1 - b.1)
    };

    println!("Tip position error [m] against the f64 reference, {HZ} frames per second:");
    println!(
        "{:>5} {:>13} {:>13} {:>13} {:>13}",
        "t", "chain f32", "chain f64", "chain f32", "pendulum f32"
    );
    println!(
        "{:>5} {:>13} {:>13} {:>13} {:>13}",
        "", "Rk4", "Rk4", "SymplEuler", "Rk4"
    );
    for k in (0..=FRAMES).step_by(HZ / 4) {
        print!("{:>5.2}", k as f64 / HZ as f64);
        for &pair in &games {
            print!(" {:>13.2e}", error(pair, k));
        }
        println!();
    }

    let apart = (0..=FRAMES)
        .map(|k| error((games[0].0, games[1].0), k))
        .fold(0.0, f64::max);
    println!(
        "The f32 and f64 Rk4 tips stay within {apart:.1e} m of each other: at 60 Hz the step, \
         not single precision, sets the error."
    );

    println!(
        "\nCost over {FRAMES} frames ({} s of simulated time):",
        FRAMES / HZ
    );
    println!(
        "{:<36} {:>10} {:>10} {:>12}",
        "run", "rhs evals", "wall ms", "us / frame"
    );
    for run in chains
        .iter()
        .chain([&chain_ref, &pendulum_game, &pendulum_ref])
    {
        println!(
            "{:<36} {:>10} {:>10.3} {:>12.2}",
            run.label,
            run.rhs_evals,
            run.seconds * 1e3,
            run.seconds * 1e6 / FRAMES as f64
        );
    }

    let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/scene"));
    std::fs::create_dir_all(dir)?;
    let path = dir.join("scene.svg");
    let (gray, wide) = REFERENCE;
    let shown = [
        (&chain_ref, gray, wide),
        (&chains[0], COLORS[0], 2),
        (&chains[2], COLORS[2], 2),
    ];
    plot(&path, &shown, &games, &error)?;
    println!("\nWrote {}", path.display());
    Ok(())
}

/// The reference is drawn wide and grey, underneath; the runs on top of it.
const REFERENCE: (RGBColor, u32) = (RGBColor(170, 170, 170), 6);
const COLORS: [RGBColor; 4] = [
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(31, 119, 180),
    RGBColor(148, 103, 189),
];

type Range = std::ops::Range<f64>;

/// Ranges around the points, padded and widened so that a metre is as long
/// across as up on a plotting area of about `w` by `h` pixels.
fn equal_aspect(points: &[(f64, f64)], (w, h): (f64, f64)) -> (Range, Range) {
    let (mut x0, mut x1, mut y0, mut y1) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
    for &(x, y) in points {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    let pad = 0.05;
    let scale = ((x1 - x0 + 2.0 * pad) / w).max((y1 - y0 + 2.0 * pad) / h);
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (hw, hh) = (scale * w / 2.0, scale * h / 2.0);
    (cx - hw..cx + hw, cy - hh..cy + hh)
}

/// Snapshots of the reference chain and two game-rate ones on top; the tip
/// paths and the tip errors below.
fn plot(
    path: &std::path::Path,
    shown: &[(&Run, RGBColor, u32)],
    games: &[(&Run, &Run)],
    error: &dyn Fn((&Run, &Run), usize) -> f64,
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (1200, 760)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "A 60 Hz scene against its f64 reference: a 5-link chain released bent",
        ("sans-serif", 24),
    )?;
    let (top, bottom) = root.split_vertically(230);

    let snapshots: Vec<usize> = (0..6).map(|i| i * HZ / 2).collect();
    let joints: Vec<(f64, f64)> = shown
        .iter()
        .flat_map(|(run, ..)| snapshots.iter().flat_map(|&k| run.frames[k].clone()))
        .collect();
    let (xs, ys) = equal_aspect(&joints, (188.0, 190.0));
    for (panel, &k) in top
        .split_evenly((1, snapshots.len()))
        .iter()
        .zip(&snapshots)
    {
        let mut chart = ChartBuilder::on(panel)
            .caption(
                format!("t = {:.1} s", k as f64 / HZ as f64),
                ("sans-serif", 16),
            )
            .margin(6)
            .build_cartesian_2d(xs.clone(), ys.clone())?;
        for &(run, color, width) in shown {
            let joints = run.frames[k].clone();
            let style = color.stroke_width(width);
            chart.draw_series(LineSeries::new(joints.clone(), style))?;
            let masses = joints.into_iter().skip(1);
            chart.draw_series(masses.map(|p| Circle::new(p, width + 1, color.filled())))?;
        }
        chart.draw_series(std::iter::once(Circle::new((0.0, 0.0), 3, BLACK.filled())))?;
    }

    let (left, right) = bottom.split_horizontally(520);
    let seconds = 2;
    let tips: Vec<(f64, f64)> = shown
        .iter()
        .flat_map(|(run, ..)| (0..=seconds * HZ).map(|k| run.tip(k)))
        .collect();
    let (xs, ys) = equal_aspect(&tips, (455.0, 400.0));
    let mut paths = ChartBuilder::on(&left)
        .caption(format!("tip path, first {seconds} s"), ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(xs, ys)?;
    paths
        .configure_mesh()
        .x_desc("x [m]")
        .y_desc("y [m]")
        .draw()?;
    for &(run, color, width) in shown {
        let tip: Vec<_> = (0..=seconds * HZ).map(|k| run.tip(k)).collect();
        let style = color.stroke_width(width);
        paths
            .draw_series(LineSeries::new(tip, style))?
            .label(run.label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
    }
    paths
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperMiddle)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;

    let floor = 1e-9;
    let mut errors = ChartBuilder::on(&right)
        .caption("tip error against the f64 reference", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..(FRAMES / HZ) as f64, (floor..3.0).log_scale())?;
    errors
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc("|tip - tip_ref| [m]")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()?;
    // Wide runs first, so that a run which coincides with another shows.
    let mut curves: Vec<_> = games.iter().zip(COLORS).collect();
    curves.sort_by_key(|(pair, _)| std::cmp::Reverse(width(pair.0)));
    for (&pair, color) in curves {
        let points: Vec<_> = (1..=FRAMES)
            .map(|k| (k as f64 / HZ as f64, error(pair, k).max(floor)))
            .collect();
        let style = color.stroke_width(width(pair.0));
        errors
            .draw_series(LineSeries::new(points, style))?
            .label(pair.0.label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
    }
    errors
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

/// Line width of a run in the error plot: `f64` runs wide, under the `f32`
/// ones they may hide.
fn width(run: &Run) -> u32 {
    if run.label.contains("f64") { 6 } else { 2 }
}
