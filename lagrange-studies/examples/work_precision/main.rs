//! The speed–accuracy trade, measured: every integrator on five problems,
//! sweeping step sizes (fixed-step methods) or tolerances (adaptive ones),
//! recording the error reached, the worst energy error, right-hand-side
//! evaluations and wall time (median of several runs).
//!
//! `cargo run --release -p lagrange-studies --example work_precision`
//!
//! Two of the five problems are constrained models (a Cartesian pendulum on
//! its rod, a slider-crank closed by two loop constraints), run with the
//! default projection after each step.
//!
//! Writes `docs/work_precision/work_precision.csv` and SVG plots beside it:
//! per problem, error against wall time and against evaluations; and the
//! energy error of a long Kepler run for a symplectic method, RK4 and
//! Dormand–Prince.

/// The exact pendulum, for the constrained Cartesian one.
#[allow(dead_code)]
#[path = "../../../tests/support/elliptic.rs"]
mod elliptic;
mod plot;
/// The tests' reader of `tests/data/*.json`; the study needs part of it.
#[allow(dead_code)]
#[path = "../../../tests/support/reference.rs"]
mod reference;
mod systems;

use lagrange::IntegrationResult;
use lagrange::Method;
use lagrange::models::Kepler;
use lagrange::prelude::*;
use std::time::Instant;
use systems::Problem;

/// One integrator with one setting: a step size for the fixed-step methods,
/// a tolerance (rtol = atol) for the adaptive ones.
#[derive(Clone, Copy, Debug)]
pub struct Setting {
    pub method: Method,
    pub value: f64,
}

impl Setting {
    pub fn integrate<L: Lagrangian<N, Scalar = f64>, const N: usize>(
        self,
        p: &Problem<L, N>,
        times: &[f64],
    ) -> IntegrationResult<f64, N> {
        let budget = if self.method.is_adaptive() {
            10_000_000
        } else {
            usize::MAX
        };
        self.method
            .integrator(self.value, self.value)
            .max_steps(budget)
            .integrate(&p.model, 0.0, p.q0, p.qdot0, times)
    }
}

/// Every method at every setting worth running on a problem.
fn sweep(steps: &[f64]) -> Vec<Setting> {
    let tolerances: Vec<f64> = (3..=13).map(|k| 10f64.powi(-k)).collect();
    let mut settings = Vec::new();
    for method in Method::ALL {
        let values = if method.is_adaptive() {
            &tolerances
        } else {
            steps
        };
        settings.extend(values.iter().map(|&value| Setting { method, value }));
    }
    settings
}

/// One row of the CSV.
#[derive(Clone, Debug)]
pub struct Run {
    pub system: &'static str,
    pub method: &'static str,
    pub setting: f64,
    pub error: f64,
    pub energy_error: f64,
    pub rhs_evals: usize,
    pub wall_seconds: f64,
}

/// Runs one method on one problem: the error at the last sample (max norm
/// over q and q̇), the worst relative energy error over the samples, and the
/// median wall time of up to five runs (fewer when one run takes > 0.5 s).
fn measure<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    p: &Problem<L, N>,
    setting: Setting,
) -> Result<Run, String> {
    let end = *p.times.last().unwrap();
    if !setting.method.is_adaptive() && end / setting.value > 3e6 {
        return Err("skipped: more than 3e6 steps".into());
    }
    let mut seconds = Vec::new();
    let mut trajectory = None;
    for _ in 0..5 {
        let start = Instant::now();
        let result = setting.integrate(p, &p.times);
        seconds.push(start.elapsed().as_secs_f64());
        trajectory = Some(result.map_err(|f| f.error.to_string())?);
        if seconds.iter().sum::<f64>() > 0.5 {
            break;
        }
    }
    seconds.sort_by(f64::total_cmp);
    let trajectory = trajectory.unwrap();
    let last = trajectory.last().unwrap();
    let (q, v) = &p.final_state;
    let error = (last.q - q).amax().max((last.qdot - v).amax());
    let e0 = p.model.energy(0.0, &p.q0, &p.qdot0).abs();
    let energy_error = trajectory
        .iter()
        .zip(&p.energies)
        .map(|(s, e)| (p.model.energy(s.t, &s.q, &s.qdot) - e).abs() / e0)
        .fold(0.0, f64::max);
    // An unstable run can end finite but absurd (explicit Euler on the stiff
    // chain: 1e245): the states here are O(1)–O(10), so an error above 1e3
    // or a non-finite energy is divergence, not a point on the curve.
    if !(error.is_finite() && error < 1e3 && energy_error.is_finite()) {
        return Err(format!(
            "diverged: error {error:.1e}, energy error {energy_error:.1e}"
        ));
    }
    Ok(Run {
        system: p.name,
        method: setting.method.id(),
        setting: setting.value,
        error,
        energy_error,
        rhs_evals: trajectory.stats().rhs_evals,
        wall_seconds: seconds[seconds.len() / 2],
    })
}

fn study<L: Lagrangian<N, Scalar = f64>, const N: usize>(p: &Problem<L, N>, runs: &mut Vec<Run>) {
    println!("\n{}", p.name);
    println!(
        "{:<18} {:>10} {:>10} {:>10} {:>10} {:>11}",
        "method", "setting", "error", "energy", "rhs evals", "seconds"
    );
    let settings = sweep(&p.steps);
    // A bar on the terminal (stderr; hidden when it is not a terminal), the
    // table above it on stdout.
    let bar = indicatif::ProgressBar::new(settings.len() as u64).with_style(
        indicatif::ProgressStyle::with_template("{prefix} {bar:40} {pos}/{len} runs, {elapsed}")
            .expect("a valid template"),
    );
    bar.set_prefix(p.name);
    for setting in settings {
        bar.inc(1);
        match measure(p, setting) {
            Ok(run) => {
                bar.suspend(|| {
                    println!(
                        "{:<18} {:>10.2e} {:>10.2e} {:>10.2e} {:>10} {:>11.3e}",
                        run.method,
                        run.setting,
                        run.error,
                        run.energy_error,
                        run.rhs_evals,
                        run.wall_seconds
                    )
                });
                runs.push(run);
            }
            Err(why) => bar
                .suspend(|| println!("{:<18} {:>10.2e} {why}", setting.method.id(), setting.value)),
        }
    }
    bar.finish_and_clear();
}

/// The right-hand sides each explicit pair (third, fifth or eighth order)
/// needs to reach an error: between the two runs of the sweep whose errors
/// bracket it, the evaluations interpolated linearly in
/// log(error)–log(evaluations) (BENCHMARKS.md's table of the explicit
/// pairs, and the methods guide's).
fn pairs_at_equal_error(runs: &[Run]) {
    let cases = [
        ("double_pendulum", 1e-2),
        ("double_pendulum", 1e-4),
        ("double_pendulum", 1e-8),
        ("kepler_e0.9", 1e-4),
        ("stiff_chain_1e6", 1e-4),
        ("cartesian_pendulum", 1e-4),
        ("cartesian_pendulum", 1e-8),
        ("slider_crank", 1e-8),
    ];
    println!("\nEvaluations to reach an error (log-log interpolation):");
    println!(
        "{:<20} {:>7} {:>9} {:>9} {:>9} {:>9}",
        "system", "error", "bs3", "dopri5", "tsit5", "dop853"
    );
    for (system, target) in cases {
        let cell = |method: &str| -> String {
            let mut points: Vec<(f64, f64)> = runs
                .iter()
                .filter(|r| r.system == system && r.method == method && r.error > 0.0)
                .map(|r| (r.error, r.rhs_evals as f64))
                .collect();
            points.sort_by(|a, b| b.0.total_cmp(&a.0));
            points
                .windows(2)
                .find(|w| w[0].0 >= target && target >= w[1].0)
                .map(|w| {
                    let a = (target.ln() - w[0].0.ln()) / (w[1].0.ln() - w[0].0.ln());
                    format!(
                        "{:.0}",
                        (w[0].1.ln() + a * (w[1].1.ln() - w[0].1.ln())).exp()
                    )
                })
                .unwrap_or_else(|| "-".into())
        };
        println!(
            "{system:<20} {target:>7.0e} {:>9} {:>9} {:>9} {:>9}",
            cell("bs3"),
            cell("dopri5"),
            cell("tsit5"),
            cell("dop853")
        );
    }
}

fn write_csv(path: &std::path::Path, runs: &[Run]) -> std::io::Result<()> {
    let mut out = String::from("system,method,setting,error,energy_error,rhs_evals,wall_seconds\n");
    for r in runs {
        out.push_str(&format!(
            "{},{},{:e},{:e},{:e},{},{:e}\n",
            r.system, r.method, r.setting, r.error, r.energy_error, r.rhs_evals, r.wall_seconds
        ));
    }
    std::fs::write(path, out)
}

/// Energy error against time over a long Kepler run (e = 0.6, 1000 orbits,
/// h = T/500: 5e5 steps, sampled ten times per orbit) for the methods that
/// show the trade.
fn long_run(dir: &std::path::Path) -> Result<(), Box<dyn std::error::Error>> {
    let period = 2.0 * std::f64::consts::PI;
    let model = Kepler::new(1.0);
    let (q0, v0) = model.pericentre(0.6);
    let e0 = model.energy(0.0, &q0, &v0);
    let times: Vec<f64> = (1..=10_000).map(|k| period * k as f64 / 10.0).collect();
    let h = period / 500.0;
    let mut curves: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    // The worst relative energy error within each orbit: the envelope of the
    // oscillation, which is what grows (drift) or does not (no drift).
    let mut add = |name: String, t: Trajectory<f64, 2>| {
        let errors: Vec<f64> = t
            .iter()
            .map(|s| {
                ((model.energy(s.t, &s.q, &s.qdot) - e0) / e0)
                    .abs()
                    .max(1e-17)
            })
            .collect();
        let points = errors
            .chunks(10)
            .enumerate()
            .map(|(k, c)| ((k + 1) as f64, c.iter().copied().fold(0.0, f64::max)))
            .collect();
        println!("{name}: {:?}", t.stats());
        curves.push((name, points));
    };
    add(
        "rk4 h = T/500".to_string(),
        Rk4::new(h)
            .max_steps(usize::MAX)
            .integrate(&model, 0.0, q0, v0, &times)?,
    );
    add(
        "gauss-legendre 2 h = T/500".to_string(),
        GaussLegendre::two_stage(h)
            .max_steps(usize::MAX)
            .integrate(&model, 0.0, q0, v0, &times)?,
    );
    add(
        "variational h = T/500".to_string(),
        Variational::new(h)
            .max_steps(usize::MAX)
            .integrate(&model, 0.0, q0, v0, &times)?,
    );
    add(
        "dopri5 tol 1e-8".into(),
        Dopri5::new()
            .rtol(1e-8)
            .atol(1e-8)
            .max_steps(10_000_000)
            .integrate(&model, 0.0, q0, v0, &times)?,
    );
    plot::energy_over_time(&dir.join("energy_long_run.svg"), &curves)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/work_precision");
    std::fs::create_dir_all(&dir)?;
    let mut runs = Vec::new();
    study(&systems::double_pendulum(), &mut runs);
    study(&systems::kepler(), &mut runs);
    study(&systems::stiff_chain(), &mut runs);
    study(&systems::cartesian_pendulum(), &mut runs);
    study(&systems::slider_crank(), &mut runs);
    write_csv(&dir.join("work_precision.csv"), &runs)?;
    pairs_at_equal_error(&runs);
    for system in [
        "double_pendulum",
        "kepler_e0.9",
        "stiff_chain_1e6",
        "cartesian_pendulum",
        "slider_crank",
    ] {
        let mine: Vec<&Run> = runs.iter().filter(|r| r.system == system).collect();
        plot::work_precision(
            &dir.join(format!("{system}_time.svg")),
            system,
            &mine,
            plot::Work::Time,
        )?;
        plot::work_precision(
            &dir.join(format!("{system}_evals.svg")),
            system,
            &mine,
            plot::Work::Evals,
        )?;
    }
    println!("\nLong run (energy error against time):");
    long_run(&dir)?;
    println!("\nWrote {}", dir.display());
    Ok(())
}
