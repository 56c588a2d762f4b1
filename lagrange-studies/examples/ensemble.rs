//! An ensemble in parallel: 10⁴ double pendulums released from rest on a
//! 100 × 100 grid of initial angles, each integrated until either rod flips
//! over (an angle passes ±π) or 20 s pass, and the classic "time to first
//! flip" picture drawn from the result. Models are plain `Send + Sync`
//! values and a `Stepper` per pendulum owns its state, so the sweep is one
//! `rayon` `par_iter`; it is run on one thread and on every core, and the
//! speed-up printed.
//!
//! `cargo run --release -p lagrange-studies --example ensemble`
//!
//! Then the same grid in SIMD lanes, on one thread: the first 2 s of every
//! pendulum with RK4 at `h = 1e-3`, as 10⁴ scalar `Stepper`s and as
//! `Ensemble`s of four pendulums in the lanes of `AutoF64x4`. Each lane is
//! its scalar stepper bit for bit, so the flips are the same; the example
//! checks that and prints both times (on an AVX2 CPU the ensembles step
//! in code compiled for it, chosen at run time; `cargo bench -p
//! lagrange-studies --bench ensemble` has the tables).
//!
//! Writes `docs/ensemble/first_flip.png`: each pixel a pair of initial
//! angles (θ1 across, θ2 up, both from −3 to 3 rad), its colour the time to
//! the first flip on a log scale (bright: soon; dark: late), black where no
//! rod flips within 20 s. Pendulums with `3 cos θ1 + cos θ2 > 2` cannot
//! flip (too little energy): the black region in the middle is that bound,
//! found by the integration, not assumed.

use lagrange::ensemble::{AutoF64x4, Ensemble};
use lagrange::models::DoublePendulum;
use lagrange::nalgebra::{SimdValue, Vector2};
use lagrange::prelude::*;
use rayon::prelude::*;
use std::error::Error;
use std::f64::consts::PI;
use std::time::Instant;

const SIDE: usize = 100;
const T_MAX: f64 = 20.0;
/// The flip test runs at the end of every frame of this length: a flip
/// is timed to within it.
const FRAME: f64 = 0.01;

/// The time until either rod first passes ±π, released from rest at
/// `(θ1, θ2)`; `None` if neither does within `T_MAX`.
fn first_flip(
    model: DoublePendulum,
    theta1: f64,
    theta2: f64,
) -> Result<Option<f64>, Box<dyn Error + Send + Sync>> {
    let method = Dop853::new().rtol(1e-9).atol(1e-9);
    let q0 = Vector2::new(theta1, theta2);
    let mut stepper = Stepper::new(model, method, 0.0, q0, Vector2::zeros())?;
    let frames = (T_MAX / FRAME).round() as usize;
    for k in 1..=frames {
        stepper.advance_to(k as f64 * FRAME)?;
        if stepper.q().iter().any(|a| a.abs() > PI) {
            return Ok(Some(stepper.t()));
        }
    }
    Ok(None)
}

/// The grid's initial angles, row by row from the bottom (θ2 = −3).
fn angle(i: usize) -> f64 {
    -3.0 + 6.0 * (i as f64 + 0.5) / SIDE as f64
}

type Sweep = Vec<Option<f64>>;

fn sweep(model: DoublePendulum) -> Result<Sweep, Box<dyn Error + Send + Sync>> {
    (0..SIDE * SIDE)
        .into_par_iter()
        .map(|k| first_flip(model, angle(k % SIDE), angle(k / SIDE)))
        .collect()
}

fn main() -> Result<(), Box<dyn Error + Send + Sync>> {
    let model = DoublePendulum::unit();
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());

    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let clock = Instant::now();
    let serial = one.install(|| sweep(model))?;
    let t_one = clock.elapsed().as_secs_f64();

    let all = rayon::ThreadPoolBuilder::new().num_threads(cores).build()?;
    let clock = Instant::now();
    let parallel = all.install(|| sweep(model))?;
    let t_all = clock.elapsed().as_secs_f64();
    assert_eq!(
        serial, parallel,
        "each pendulum is integrated alone: the same on any thread"
    );

    let flipped = parallel.iter().flatten().count();
    let energy_bound = (0..SIDE * SIDE)
        .filter(|&k| 3.0 * angle(k % SIDE).cos() + angle(k / SIDE).cos() > 2.0)
        .collect::<Vec<_>>();
    let bound_kept = energy_bound.iter().all(|&k| parallel[k].is_none());
    println!(
        "{} pendulums, {T_MAX} s each (Dop853 1e-9, flip checked every {FRAME} s): {flipped} flip",
        SIDE * SIDE
    );
    println!(
        "none of the {} below the energy bound 3 cos θ1 + cos θ2 > 2 flips: {bound_kept}",
        energy_bound.len()
    );
    println!(
        "1 thread: {t_one:.2} s; {cores} threads: {t_all:.2} s; speed-up {:.2}×",
        t_one / t_all
    );

    let clock = Instant::now();
    let scalar = lanes_sweep_scalar()?;
    let t_scalar = clock.elapsed().as_secs_f64();
    let clock = Instant::now();
    let lanes = lanes_sweep()?;
    let t_lanes = clock.elapsed().as_secs_f64();
    assert_eq!(
        scalar, lanes,
        "each lane is its scalar stepper, bit for bit"
    );
    println!(
        "RK4 h = {H}, first {T_LANES} s, 1 thread: {} flip; scalar steppers {t_scalar:.2} s, \
         ensembles of 4 lanes {t_lanes:.2} s: {:.2}× the throughput",
        lanes.iter().flatten().count(),
        t_scalar / t_lanes
    );

    let path = std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../docs/ensemble/first_flip.png"
    ));
    draw(&parallel, path)?;
    println!("Wrote {}", path.display());
    Ok(())
}

/// The lanes' sweep: its span and step.
const T_LANES: f64 = 2.0;
const H: f64 = 1e-3;

/// The first flip within `T_LANES` of every pendulum of the grid, each in
/// its own RK4 `Stepper`.
fn lanes_sweep_scalar() -> Result<Sweep, Box<dyn Error + Send + Sync>> {
    let frames = (T_LANES / FRAME).round() as usize;
    (0..SIDE * SIDE)
        .map(|k| {
            let q0 = Vector2::new(angle(k % SIDE), angle(k / SIDE));
            let model = DoublePendulum::unit();
            let mut stepper = Stepper::new(model, Rk4::new(H), 0.0, q0, Vector2::zeros())?;
            for frame in 1..=frames {
                stepper.advance_to(frame as f64 * FRAME)?;
                if stepper.q().iter().any(|a| a.abs() > PI) {
                    return Ok(Some(stepper.t()));
                }
            }
            Ok(None)
        })
        .collect()
}

/// The same, four pendulums to an `Ensemble` in the lanes of `AutoF64x4`.
fn lanes_sweep() -> Result<Sweep, Box<dyn Error + Send + Sync>> {
    let frames = (T_LANES / FRAME).round() as usize;
    let unit = |x: f64| AutoF64x4::splat(x);
    let model = DoublePendulum::new(unit(1.0), unit(1.0), unit(1.0), unit(1.0), unit(9.81));
    let mut flips = vec![None; SIDE * SIDE];
    for (group, flips) in flips.chunks_mut(4).enumerate() {
        let q0: Vec<_> = (0..4)
            .map(|j| group * 4 + j)
            .map(|k| Vector2::new(angle(k % SIDE), angle(k / SIDE)))
            .collect();
        let mut ensemble = Ensemble::new(model, Rk4::new(H), 0.0, &q0, &[Vector2::zeros(); 4])?;
        for frame in 1..=frames {
            ensemble.advance_to(frame as f64 * FRAME)?;
            for (lane, flip) in flips.iter_mut().enumerate() {
                if flip.is_none() && ensemble.q(lane).iter().any(|a| a.abs() > PI) {
                    *flip = Some(ensemble.t());
                }
            }
            if flips.iter().all(Option::is_some) {
                break;
            }
        }
    }
    Ok(flips)
}

/// The picture, each grid cell a 4 × 4 block of pixels, θ2 up.
fn draw(flips: &Sweep, path: &std::path::Path) -> Result<(), Box<dyn Error + Send + Sync>> {
    const SCALE: usize = 4;
    let size = SIDE * SCALE;
    let mut pixels = vec![0u8; size * size * 3];
    let (log_min, log_max) = (FRAME.ln(), T_MAX.ln());
    for (k, flip) in flips.iter().enumerate() {
        let (col, row) = (k % SIDE, SIDE - 1 - k / SIDE);
        let rgb = match flip {
            None => [0, 0, 0],
            Some(t) => ramp(1.0 - (t.ln() - log_min) / (log_max - log_min)),
        };
        for dy in 0..SCALE {
            for dx in 0..SCALE {
                let p = ((row * SCALE + dy) * size + col * SCALE + dx) * 3;
                pixels[p..p + 3].copy_from_slice(&rgb);
            }
        }
    }
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut encoder = png::Encoder::new(file, size as u32, size as u32);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.write_header()?.write_image_data(&pixels)?;
    Ok(())
}

/// A dark-blue → red → yellow ramp for `x` in [0, 1].
fn ramp(x: f64) -> [u8; 3] {
    let x = x.clamp(0.0, 1.0);
    let c = |v: f64| (255.0 * v.clamp(0.0, 1.0)) as u8;
    [
        c(1.6 * x),
        c(2.0 * x - 0.8),
        c(0.45 - 1.2 * x + 1.6 * x * x * (x - 0.6).max(0.0)),
    ]
}
