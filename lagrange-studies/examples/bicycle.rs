//! The Whipple bicycle (`lagrange::models::WhippleBicycle`), written in the
//! language as the full nonlinear model with rolling wheels, against the
//! benchmark of Meijaard, Papadopoulos, Ruina and Schwab (2007).
//!
//! `cargo run --release -p lagrange-studies --example bicycle`
//!
//! Prints:
//! - what the macro does with the model: expansion time (the engine built
//!   in release, as the example is), operation counts of `M` and `f`, and
//!   `cargo build --release` of a crate holding only the model, beside
//!   PyDy's and SymPy's figures for the same bicycle;
//! - the linearization about upright straight running against the
//!   benchmark's closed-form `M`, `C1`, `K0`, `K2` (the eigenvalues over
//!   0–10 m/s, and the largest difference of the state matrices);
//! - the weave and capsize speeds, ours against the benchmark's;
//! - nonlinear runs released at a lean of 0.01 rad at 5 and 3 m/s.
//!
//! Writes `docs/bicycle/eigenvalues.svg`: the eigenvalues against speed,
//! ours over the benchmark's.

#[path = "scaling/engine.rs"]
#[allow(dead_code)]
mod engine;

use lagrange::analysis::{linearize_steady_motion, stability_crossing};
use lagrange::models::WhippleBicycle;
use lagrange::nalgebra::{DMatrix, Matrix2, Matrix4, Vector4};
use lagrange::prelude::*;
use plotters::prelude::*;
use std::error::Error;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// The model's source, as `src/models/bicycle.rs` holds it.
const SOURCE: &str = include_str!("../../src/models/bicycle.rs");

/// The `lagrangian! { .. }` invocation of [`SOURCE`], as text.
fn invocation() -> &'static str {
    let start = SOURCE
        .find("lagrangian! {")
        .expect("the model's invocation");
    let end = start + SOURCE[start..].find("\n}\n").expect("its closing brace") + 2;
    &SOURCE[start..end]
}

/// The nonlinear model's linearization at `v`, reduced to lean and steer.
fn linearized(bike: &WhippleBicycle<f64>, v: f64) -> Result<Matrix4<f64>, Box<dyn Error>> {
    let (q, qdot) = bike.upright(0.0, v);
    let lin = linearize_steady_motion(bike, 0.0, &q, &qdot, &["phi", "delta"], &["phi", "delta"])?;
    Ok(Matrix4::from_iterator(lin.state_matrix.iter().copied()))
}

/// The eigenvalues of `a` as `(re, im)`, sorted by real part, then
/// imaginary part.
fn eigenvalues(a: &Matrix4<f64>) -> Vec<(f64, f64)> {
    let mut e: Vec<(f64, f64)> = a
        .complex_eigenvalues()
        .iter()
        .map(|l| (l.re, l.im))
        .collect();
    e.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    e
}

/// The largest real part among the eigenvalues of `a`.
fn growth(a: &Matrix4<f64>) -> f64 {
    eigenvalues(a)
        .iter()
        .map(|e| e.0)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The speed in `lo..hi` where the largest real part of the nonlinear
/// model's linearization changes sign, by the library's one call.
fn crossing_speed(bike: &WhippleBicycle<f64>, lo: f64, hi: f64) -> Result<f64, Box<dyn Error>> {
    let crossing = stability_crossing(lo, hi, |v| {
        let (q, qdot) = bike.upright(0.0, v);
        let states = ["phi", "delta"];
        linearize_steady_motion(bike, 0.0, &q, &qdot, &states, &states)
            .map(|l| l.state_matrix)
            .map_err(Box::new)
    })?;
    Ok(crossing.parameter)
}

/// The same on the benchmark's closed-form state matrix.
fn crossing_speed_closed_form(
    bike: &WhippleBicycle<f64>,
    lo: f64,
    hi: f64,
) -> Result<f64, Box<dyn Error>> {
    let crossing = stability_crossing(lo, hi, |v| {
        let a = bike.benchmark_state_matrix(v);
        Ok::<_, std::convert::Infallible>(DMatrix::from_iterator(4, 4, a.iter().copied()))
    })?;
    Ok(crossing.parameter)
}

fn main() -> Result<(), Box<dyn Error>> {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the workspace")
        .to_path_buf();
    let bike = WhippleBicycle::benchmark();

    println!("## The model through the macro\n");
    // The invocation's body, inside its braces: what the macro is handed.
    let inside = invocation()
        .trim_start_matches("lagrangian! {")
        .trim_end_matches('}');
    let stats = engine::measure(inside).map_err(|e| e.message)?;
    println!("| | ours | PyDy / SymPy (issue 24's anchors) |");
    println!("|---|---:|---|");
    println!(
        "| derivation (expansion of `lagrangian!`) | {:.0} ms (median of {}) | linearizing the bicycle: over an hour (sympy#21652) |",
        stats.expand.as_secs_f64() * 1e3,
        stats.reps
    );
    println!(
        "| operations of `M` (upper triangle) and `f`, shared | {} ({} of `M`, {} of `f`) | 2,367 after CSE (pydy#122) |",
        stats.shared.total(),
        stats.shared_mass.total(),
        stats.shared_forcing.total()
    );
    println!(
        "| the same as trees (no sharing) | {} | `M` alone 1,173,655 (pydy#122) |",
        stats.tree.total()
    );
    println!("| generated code | {} kB | |", stats.code_bytes / 1000);
    match build_time(&repo) {
        Ok((secs, cold)) => println!(
            "| `cargo build --release` of a crate holding the model | {secs:.1} s{} | its Cython build: over 12 hours (pydy#122) |",
            if cold {
                " (dependencies built first, not counted)"
            } else {
                ""
            }
        ),
        Err(e) => println!("| `cargo build --release` | failed: {e} | |"),
    }

    println!("\n## Linearized about upright straight running\n");
    println!("| v [m/s] | eigenvalues (ours) | largest difference from the benchmark's |");
    println!("|---:|---|---:|");
    let mut worst = 0.0f64;
    let mut ours_points = Vec::new();
    for k in 0..=20 {
        let v = 0.5 * k as f64;
        let (ours, theirs) = (linearized(&bike, v)?, bike.benchmark_state_matrix(v));
        worst = worst.max((ours - theirs).amax() / theirs.amax());
        let (e, e_ref) = (eigenvalues(&ours), eigenvalues(&theirs));
        let diff = e
            .iter()
            .zip(&e_ref)
            .map(|(a, b)| (a.0 - b.0).hypot(a.1 - b.1))
            .fold(0.0, f64::max);
        let shown: Vec<String> = e
            .iter()
            .map(|(re, im)| format!("{re:.4}{im:+.4}i"))
            .collect();
        if k % 2 == 0 {
            println!("| {v:.1} | {} | {diff:.1e} |", shown.join(", "));
        }
        ours_points.extend(e.iter().map(|&(re, im)| (v, re, im)));
    }
    println!(
        "\nState matrices: largest difference {worst:.1e} of the benchmark's largest entry, 0–10 m/s."
    );

    // M, C1, K0, K2 from the general reduced matrices of a steady motion
    // (`analysis::steady_motion_matrices`), at rest and at 5 m/s.
    let [m_ref, c1_ref, k0_ref, k2_ref] = bike.benchmark_matrices();
    let [m, c1, k0, k2] = bike.lean_steer_matrices(5.0)?;
    println!("\n| matrix | ours | benchmark's | relative difference |");
    println!("|---|---|---|---:|");
    for (name, ours, theirs) in [
        ("M", m, m_ref),
        ("C1", c1, c1_ref),
        ("K0", k0, k0_ref),
        ("K2", k2, k2_ref),
    ] {
        let show = |x: &Matrix2<f64>| {
            format!(
                "[[{:.10}, {:.10}], [{:.10}, {:.10}]]",
                x[(0, 0)],
                x[(0, 1)],
                x[(1, 0)],
                x[(1, 1)]
            )
        };
        println!(
            "| {name} | {} | {} | {:.1e} |",
            show(&ours),
            show(&theirs),
            (ours - theirs).amax() / theirs.amax()
        );
    }

    let weave = crossing_speed(&bike, 3.0, 5.0)?;
    let weave_ref = crossing_speed_closed_form(&bike, 3.0, 5.0)?;
    let capsize = crossing_speed(&bike, 5.5, 7.0)?;
    let capsize_ref = crossing_speed_closed_form(&bike, 5.5, 7.0)?;
    println!(
        "\n| speed | ours [m/s] | benchmark's closed form | published (table 2) | ours against the closed form |"
    );
    println!("|---|---:|---:|---:|---:|");
    for (name, ours, theirs, published) in [
        ("weave", weave, weave_ref, 4.29238253634111),
        ("capsize", capsize, capsize_ref, 6.02426201538837),
    ] {
        println!(
            "| {name} | {ours:.10} | {theirs:.10} | {published:.10} | {:.1e} |",
            (ours - theirs).abs() / theirs
        );
    }

    println!("\n## Released at a lean of 0.01 rad\n");
    println!(
        "| v [m/s] | growth rate (eigenvalues) [1/s] | lean at t [rad] | linear motion | largest difference | energy drift | Dop853 at 1e-11 |"
    );
    println!("|---:|---:|---|---:|---:|---:|---:|");
    for (v, end) in [(5.0, 4.0), (3.0, 1.0)] {
        let (mut q, qdot) = bike.upright(0.0, v);
        q[3] = 0.01;
        let times: Vec<f64> = (1..=40).map(|k| end * k as f64 / 40.0).collect();
        let start = Instant::now();
        let run = Dop853::new()
            .rtol(1e-11)
            .atol(1e-13)
            .integrate(&bike, 0.0, q, qdot, &times)?;
        let elapsed = start.elapsed();
        let a = bike.benchmark_state_matrix(v);
        let x0 = Vector4::new(0.01, 0.0, 0.0, 0.0);
        let off = run
            .iter()
            .map(|s| (s.q[3] - ((a * s.t).exp() * x0)[0]).abs())
            .fold(0.0, f64::max);
        let last = run.last().expect("samples");
        let e0 = bike.kinetic_energy(0.0, &q, &qdot) + bike.potential_energy(0.0, &q);
        let e1 = bike.kinetic_energy(last.t, &last.q, &last.qdot)
            + bike.potential_energy(last.t, &last.q);
        println!(
            "| {v} | {:.4} | {:.3e} at {end} s | {:.3e} | {off:.1e} | {:.0e} | {} steps, {:.1} ms |",
            growth(&a),
            last.q[3],
            ((a * last.t).exp() * x0)[0],
            (e1 - e0).abs() / e0.abs(),
            run.stats().steps_accepted,
            elapsed.as_secs_f64() * 1e3
        );
    }
    println!();

    let dir = repo.join("docs/bicycle");
    std::fs::create_dir_all(&dir)?;
    let path = dir.join("eigenvalues.svg");
    draw(&path, &bike, &ours_points, weave, capsize)?;
    println!("Wrote {}", path.display());
    Ok(())
}

/// `cargo build --release` of a crate holding only the model and one
/// function that evaluates `M`, `f`, `G` and `γ` for `f64` (so that the
/// generated code is compiled, not only expanded): seconds, and whether the
/// dependencies had to be built first (not counted).
fn build_time(repo: &Path) -> Result<(f64, bool), Box<dyn Error>> {
    let root = repo.join("target/bicycle");
    let target = repo.join("target/scaling/target");
    std::fs::create_dir_all(root.join("src"))?;
    std::fs::write(
        root.join("Cargo.toml"),
        format!(
            "# Generated by `cargo run --release -p lagrange-studies --example bicycle`.\n\
             [package]\nname = \"bicycle\"\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n\
             [dependencies]\nlagrange = {{ path = \"{}\" }}\n\n\
             [workspace]\n\n[profile.release.package.lagrange-engine]\nopt-level = 3\n",
            repo.display()
        ),
    )?;
    let lock = root.join("Cargo.lock");
    if !lock.exists() {
        std::fs::copy(repo.join("Cargo.lock"), &lock)?;
    }
    let lib = format!(
        "use lagrange::prelude::*;\nuse lagrange::nalgebra::{{SMatrix, SVector}};\n\n{}\n\n\
         /// `M`, `f`, `G` and `γ` at a state, for `f64`.\n\
         #[allow(clippy::type_complexity)]\n\
         pub fn system(p: [f64; 26], q: &SVector<f64, 8>, v: &SVector<f64, 8>) -> (SMatrix<f64, 8, 8>, SVector<f64, 8>, SMatrix<f64, 5, 8>, SVector<f64, 5>) {{\n    \
         let b = WhippleBicycle::<f64>::new({});\n    b.constrained_system(0.0, q, v)\n}}\n",
        invocation(),
        (0..26)
            .map(|i| format!("p[{i}]"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let build = |touch: bool| -> Result<f64, Box<dyn Error>> {
        if touch {
            std::fs::write(root.join("src/lib.rs"), &lib)?;
        }
        let start = Instant::now();
        let status = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
            .args(["build", "--release", "--quiet", "--manifest-path"])
            .arg(root.join("Cargo.toml"))
            .env("CARGO_TARGET_DIR", &target)
            .status()?;
        if !status.success() {
            return Err(format!("cargo build failed in {}", root.display()).into());
        }
        Ok(start.elapsed().as_secs_f64())
    };
    let cold = !target.join("release/deps").exists();
    std::fs::write(root.join("src/lib.rs"), &lib)?;
    build(false)?; // the dependencies, and the model once
    let secs = build(true)?; // the model alone
    Ok((secs, cold))
}

fn draw(
    path: &PathBuf,
    bike: &WhippleBicycle<f64>,
    ours: &[(f64, f64, f64)],
    weave: f64,
    capsize: f64,
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (900, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Whipple bicycle: eigenvalues against speed (lines: benchmark, dots: the nonlinear model linearized)",
            ("sans-serif", 16),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(0.0..10.0, -10.0..10.0)?;
    chart
        .configure_mesh()
        .x_desc("v [m/s]")
        .y_desc("1/s")
        .draw()?;
    // The benchmark's eigenvalues on a fine grid: real parts (black) and
    // imaginary parts (grey), as small points so that no branch is guessed.
    let fine: Vec<(f64, Vec<(f64, f64)>)> = (0..=400)
        .map(|k| {
            let v = 0.025 * k as f64;
            (v, eigenvalues(&bike.benchmark_state_matrix(v)))
        })
        .collect();
    chart
        .draw_series(fine.iter().flat_map(|(v, e)| {
            e.iter()
                .map(move |&(re, _)| Circle::new((*v, re), 1, BLACK.filled()))
        }))?
        .label("benchmark, real part")
        .legend(|(x, y)| Circle::new((x + 10, y), 3, BLACK.filled()));
    chart
        .draw_series(fine.iter().flat_map(|(v, e)| {
            e.iter()
                .filter(|(_, im)| *im > 0.0)
                .map(move |&(_, im)| Circle::new((*v, im), 1, RGBColor(150, 150, 150).filled()))
        }))?
        .label("benchmark, imaginary part")
        .legend(|(x, y)| Circle::new((x + 10, y), 3, RGBColor(150, 150, 150).filled()));
    chart
        .draw_series(
            ours.iter()
                .map(|&(v, re, _)| Circle::new((v, re), 4, BLUE.stroke_width(2))),
        )?
        .label("ours, real part")
        .legend(|(x, y)| Circle::new((x + 10, y), 4, BLUE.stroke_width(2)));
    chart
        .draw_series(
            ours.iter()
                .filter(|(_, _, im)| *im > 0.0)
                .map(|&(v, _, im)| Circle::new((v, im), 4, RED.stroke_width(2))),
        )?
        .label("ours, imaginary part")
        .legend(|(x, y)| Circle::new((x + 10, y), 4, RED.stroke_width(2)));
    for (v, name) in [(weave, "weave"), (capsize, "capsize")] {
        chart.draw_series(LineSeries::new([(v, -10.0), (v, 10.0)], BLACK.mix(0.4)))?;
        chart.draw_series(std::iter::once(Text::new(
            format!("{name} {v:.3} m/s"),
            (v + 0.1, 9.0),
            ("sans-serif", 13),
        )))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
