//! Parameters from data: a damped double pendulum (the first mass given)
//! "recorded" for 10 s at 100 Hz by Radau5 at 1e-12, with Gaussian noise
//! of 1e-3 rad on both angles, fitted by `lagrange::identify::fit` (Dop853
//! at 1e-10 over the model's sensitivities) from a start 20 % off: the
//! second mass, both lengths and both dampers, with their standard errors
//! and 95 % intervals. Writes `docs/identify/identify.svg` (the data and
//! the fitted motion).
//!
//! ```sh
//! cargo run --release -p lagrange-studies --example identify
//! cargo run --release -p lagrange-studies --example identify -- --coverage 100
//! LAGRANGE_PEERS_PYTHON=../peers-venv/bin/python \
//!   cargo run --release -p lagrange-studies --example identify -- --scipy
//! ```
//!
//! `--coverage K` repeats the fit over noise seeds 0..K and counts, for
//! each parameter, the seeds whose 95 % interval holds the true value
//! (about 95 of 100 if the standard errors are right; 89 to 99 is the
//! binomial's 99 % range). `--scipy` fits the same data with SciPy
//! (`least_squares` over `solve_ivp`, `identify/scipy_fit.py`) from the
//! same start, and prints both side by side with the time each took; it
//! needs a Python with numpy and scipy (`LAGRANGE_PEERS_PYTHON`, else
//! `python3`) and says so and skips without one.

#[path = "../support/peers_python.rs"]
mod peers_python;

use lagrange::identify::{Fit, FitSettings, Measurements, fit};
use lagrange::models::DampedDoublePendulum;
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use lagrange::sensitivity::Direction;
use lagrange::{Dop853, Radau5};
use plotters::prelude::*;
use std::error::Error;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// m1, m2, l1, l2, g, c1, c2.
const TRUTH: [f64; 7] = [1.0, 0.8, 1.1, 0.9, 9.81, 0.3, 0.2];
/// The fitted ones (indices into `TRUTH`), and the start: 20 % off each.
const FITTED: [usize; 5] = [1, 2, 3, 5, 6];
const START: [f64; 5] = [1.2, 0.8, 1.2, 0.8, 1.2];
const NOISE: f64 = 1e-3;
const START_STATE: ([f64; 2], [f64; 2]) = ([1.0, -0.5], [0.0, 0.3]);

fn model(p: &[f64; 7]) -> DampedDoublePendulum {
    DampedDoublePendulum::new(p[0], p[1], p[2], p[3], p[4], p[5], p[6])
}

fn start() -> (SVector<f64, 2>, SVector<f64, 2>) {
    (SVector::from(START_STATE.0), SVector::from(START_STATE.1))
}

fn times() -> Vec<f64> {
    (1..=1000).map(|i| i as f64 / 100.0).collect()
}

/// The noiseless motion, Radau5 at 1e-12.
fn truth() -> Vec<SVector<f64, 2>> {
    let (q0, v0) = start();
    Radau5::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&model(&TRUTH), 0.0, q0, v0, &times())
        .expect("the recording runs")
        .positions()
        .to_vec()
}

/// SplitMix64 and Box–Muller: Gaussian noise from a seed, the same on
/// every machine.
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

fn recorded(truth: &[SVector<f64, 2>], seed: u64) -> Measurements<2> {
    let mut gauss = noise(seed);
    let noisy = truth
        .iter()
        .map(|q| q.map(|x| x + NOISE * gauss()))
        .collect();
    Measurements::positions(times(), noisy)
}

fn directions() -> [Direction; 5] {
    FITTED.map(Direction::Parameter)
}

fn guess() -> [f64; 7] {
    let mut p = TRUTH;
    for (k, factor) in FITTED.iter().zip(START) {
        p[*k] *= factor;
    }
    p
}

fn fit_once(data: &Measurements<2>) -> Result<Fit<DampedDoublePendulum, 2, 5>, Box<dyn Error>> {
    Ok(fit(
        model(&guess()),
        &Dop853::new().rtol(1e-10).atol(1e-10),
        directions(),
        0.0,
        start(),
        data,
        &FitSettings::default(),
    )?)
}

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average at the start: {}", load.trim());
    let truth = truth();
    if let Some(at) = args.iter().position(|a| a == "--coverage") {
        let seeds: u64 = args.get(at + 1).and_then(|s| s.parse().ok()).unwrap_or(100);
        return coverage(&truth, seeds);
    }
    let data = recorded(&truth, 1);
    let clock = Instant::now();
    let fitted = fit_once(&data)?;
    let ours = clock.elapsed().as_secs_f64();
    println!();
    println!(
        "Fit of {} parameters to {} samples of both angles (noise {NOISE} rad): {} iterations, {} sensitivity runs, {ours:.3} s; σ̂ = {:.3e} rad.",
        FITTED.len(),
        data.times.len(),
        fitted.iterations,
        fitted.runs,
        fitted.sigma
    );
    println!();
    println!(
        "| parameter | true | start | fitted | standard error | 95 % interval | (fitted − true) / s.e. |"
    );
    println!("|---|---:|---:|---:|---:|---|---:|");
    for (j, &k) in FITTED.iter().enumerate() {
        let (lo, hi) = fitted.interval(j);
        println!(
            "| {} | {} | {:.3} | {:.5} | {:.1e} | [{lo:.5}, {hi:.5}] | {:+.2} |",
            fitted.names[j],
            TRUTH[k],
            fitted.initial_values[j],
            fitted.values[j],
            fitted.standard_errors[j],
            (fitted.values[j] - TRUTH[k]) / fitted.standard_errors[j]
        );
    }
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/identify/identify.svg");
    draw(&path, &data, &fitted.fitted)?;
    println!();
    println!("wrote {}", path.display());
    linear_route(&data, &truth);
    if args.iter().any(|a| a == "--scipy") {
        scipy(&data, &fitted, ours)?;
    }
    Ok(())
}

/// Least squares on the regressor, `Y π = 0` with `m1` given: `Y' π' =
/// −y₁ m1` for `π' = (m2, c1, c2)`, stacked over the samples, `q̇` and
/// `q̈` from the angles by Savitzky–Golay with half-window `M`: the noisy
/// ones, and the noiseless ones (what the route gives without noise).
fn linear_route(data: &Measurements<2>, truth: &[SVector<f64, 2>]) {
    use lagrange::identify::savitzky_golay;
    use lagrange::nalgebra::{DMatrix, DVector};
    assert_eq!(
        DampedDoublePendulum::<f64>::REGRESSOR_PARAMETERS,
        ["m1", "m2", "c1", "c2"]
    );
    // The lengths as measured with a ruler: the true ones.
    let model = model(&TRUTH);
    println!();
    println!(
        "The linear route: M q̈ − f = Y π in (m1, m2, c1, c2), m1 given, q̇ and q̈ by Savitzky–Golay (cubic, 2M + 1 samples); each estimate's error against the truth:"
    );
    println!();
    println!(
        "| data | M | σ of q̈ from the noise (rad/s²) | m2 | c1 | c2 | errors (m2, c1, c2) | time (ms) |"
    );
    println!("|---|---:|---:|---:|---:|---:|---|---:|");
    let runs = [
        ("noiseless", truth, 2),
        ("noiseless", truth, 5),
        ("noiseless", truth, 20),
        ("noisy", &data.positions[..], 5),
        ("noisy", &data.positions[..], 10),
        ("noisy", &data.positions[..], 20),
        ("noisy", &data.positions[..], 40),
    ];
    for (label, positions, half) in runs {
        let clock = Instant::now();
        let Some(samples) = savitzky_golay(&data.times, positions, half) else {
            continue;
        };
        let rows = 2 * samples.len();
        let mut a = DMatrix::<f64>::zeros(rows, 3);
        let mut b = DVector::<f64>::zeros(rows);
        for (s, (t, q, v, acc)) in samples.iter().enumerate() {
            let y = model.regressor(*t, q, v, acc);
            let offset = model.regressor_offset(*t, q, v, acc);
            for i in 0..2 {
                let row = 2 * s + i;
                for j in 0..3 {
                    a[(row, j)] = y[(i, j + 1)];
                }
                b[row] = -(y[(i, 0)] * TRUTH[0] + offset[i]);
            }
        }
        let estimate = a
            .svd(true, true)
            .solve(&b, 1e-12)
            .expect("a least-squares solution");
        let ms = clock.elapsed().as_secs_f64() * 1e3;
        let m = half as f64;
        let sigma = if label == "noisy" { NOISE } else { 0.0 };
        let noise = sigma
            * (180.0 / (m * (m + 1.0) * (2.0 * m + 1.0) * (2.0 * m - 1.0) * (2.0 * m + 3.0)))
                .sqrt()
            / 1e-4;
        let truth = [TRUTH[1], TRUTH[5], TRUTH[6]];
        let off: Vec<String> = (0..3)
            .map(|j| format!("{:+.2} %", 100.0 * (estimate[j] - truth[j]) / truth[j]))
            .collect();
        println!(
            "| {label} | {half} | {noise:.3} | {:.5} | {:.5} | {:.5} | {} | {ms:.1} |",
            estimate[0],
            estimate[1],
            estimate[2],
            off.join(", ")
        );
    }
}

/// The fit over `seeds` noise seeds: how often each 95 % interval holds
/// the truth.
fn coverage(truth: &[SVector<f64, 2>], seeds: u64) -> Result<(), Box<dyn Error>> {
    let mut inside = [0u32; 5];
    let mut failed = 0;
    let clock = Instant::now();
    for seed in 0..seeds {
        match fit_once(&recorded(truth, seed)) {
            Ok(fitted) => {
                for (j, &k) in FITTED.iter().enumerate() {
                    let (lo, hi) = fitted.interval(j);
                    inside[j] += u32::from(lo <= TRUTH[k] && TRUTH[k] <= hi);
                }
            }
            Err(e) => {
                failed += 1;
                println!("seed {seed}: {e}");
            }
        }
    }
    println!();
    println!(
        "{seeds} noise seeds ({failed} fits failed), {:.1} s: seeds whose 95 % interval holds the true value",
        clock.elapsed().as_secs_f64()
    );
    println!();
    println!("| parameter | inside | of |");
    println!("|---|---:|---:|");
    let names = ["m2", "l1", "l2", "c1", "c2"];
    for (name, count) in names.iter().zip(inside) {
        println!("| {name} | {count} | {seeds} |");
    }
    Ok(())
}

/// The same data fitted by SciPy from the same start, side by side.
fn scipy(
    data: &Measurements<2>,
    fitted: &Fit<DampedDoublePendulum, 2, 5>,
    ours: f64,
) -> Result<(), Box<dyn Error>> {
    println!();
    let python = match peers_python::importing("numpy, scipy") {
        Ok(python) => python,
        Err(why) => {
            println!("scipy: skipped: {why}");
            return Ok(());
        }
    };
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/identify");
    std::fs::create_dir_all(&dir)?;
    let csv = dir.join("data.csv");
    let mut text = String::from("t,theta1,theta2\n");
    for (t, q) in data.times.iter().zip(&data.positions) {
        text += &format!("{t:?},{:?},{:?}\n", q[0], q[1]);
    }
    std::fs::write(&csv, text)?;
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/identify/scipy_fit.py");
    let guess = guess();
    let (q0, v0) = START_STATE;
    let output = Command::new(&python)
        .arg(&script)
        .arg(&csv)
        .arg(format!(
            "{:?}",
            [
                guess[0], guess[1], guess[2], guess[3], guess[4], guess[5], guess[6]
            ]
        ))
        .arg(format!("{:?}", [q0[0], q0[1], v0[0], v0[1]]))
        .output()?;
    if !output.status.success() {
        return Err(format!(
            "scipy_fit.py failed: {}",
            String::from_utf8_lossy(&output.stderr)
        )
        .into());
    }
    // One line: the five values, the five standard errors, the seconds,
    // the number of solve_ivp runs.
    let line = String::from_utf8(output.stdout)?;
    let numbers: Vec<f64> = line
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()?;
    let (values, errors) = (&numbers[0..5], &numbers[5..10]);
    let (seconds, runs) = (numbers[10], numbers[11]);
    println!(
        "SciPy (`least_squares`, MINPACK's Levenberg–Marquardt, over `solve_ivp` DOP853 at 1e-10, Jacobian by differences of whole runs): {runs} runs, {seconds:.2} s; ours {ours:.3} s, {:.0}× less.",
        seconds / ours
    );
    println!();
    println!("| parameter | ours | s.e. | SciPy | s.e. | difference / our s.e. |");
    println!("|---|---:|---:|---:|---:|---:|");
    for j in 0..5 {
        println!(
            "| {} | {:.6} | {:.1e} | {:.6} | {:.1e} | {:+.1e} |",
            fitted.names[j],
            fitted.values[j],
            fitted.standard_errors[j],
            values[j],
            errors[j],
            (values[j] - fitted.values[j]) / fitted.standard_errors[j]
        );
    }
    Ok(())
}

fn draw(
    path: &Path,
    data: &Measurements<2>,
    fitted: &[SVector<f64, 2>],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Damped double pendulum: noisy angles (dots, every 4th sample) and the fitted motion",
        ("sans-serif", 20),
    )?;
    let (top, bottom) = root.split_vertically(270);
    for (area, c, label, color) in [(&top, 0, "θ1 [rad]", BLUE), (&bottom, 1, "θ2 [rad]", RED)] {
        let lo = data.positions.iter().map(|q| q[c]).fold(0.0, f64::min);
        let hi = data.positions.iter().map(|q| q[c]).fold(0.0, f64::max);
        let pad = 0.1 * (hi - lo);
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(55)
            .build_cartesian_2d(0.0..10.0, (lo - pad)..(hi + pad))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc(label)
            .draw()?;
        chart.draw_series(
            data.times
                .iter()
                .zip(&data.positions)
                .step_by(4)
                .map(|(t, q)| Circle::new((*t, q[c]), 2, BLACK.filled())),
        )?;
        chart.draw_series(LineSeries::new(
            data.times.iter().zip(fitted).map(|(t, q)| (*t, q[c])),
            color.stroke_width(2),
        ))?;
    }
    root.present()?;
    Ok(())
}
