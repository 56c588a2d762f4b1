//! A four-bar linkage, the simplest closed loop, in three angles closed by
//! two loop constraints: derive, print the constraint equations, run it for
//! 100 s with every method, measure what each drift control does, and draw
//! it.
//!
//! `cargo run --release -p lagrange-studies --example four_bar`
//!
//! Writes `docs/four_bar/four_bar.svg`: the linkage through one crank turn
//! with the path of its coupler's midpoint, and the closure residual
//! `max |φ|` over 100 s with projection, Baumgarte stabilization and none.
//! With `--features csv`, `-- --csv FILE` writes the one-turn run as CSV,
//! the loop's multipliers included (`lambda_loop_x`, …).

#[path = "support/csv_option.rs"]
mod csv_option;

use lagrange::Method;
use lagrange::constraints::{Drift, annotate};
use lagrange::models::FourBar;
use lagrange::nalgebra::Vector3;
use lagrange::prelude::*;
use plotters::prelude::*;
use std::error::Error;
use std::time::Instant;

const END: f64 = 100.0;

fn main() -> Result<(), Box<dyn Error>> {
    let model = FourBar::crank_rocker();
    println!("Derived at compile time (M q'' + G^T lambda = f, G q'' = -gamma):\n");
    println!("{}", FourBar::<f64>::EQUATIONS);

    // The crank at 45° turning at 12 rad/s; the coupler and rocker placed
    // where the loop closes (`FourBar::state`, the circle intersection).
    let (q0, v0) = model
        .state(45f64.to_radians(), 12.0)
        .ok_or("does not assemble")?;
    let e0 = model.energy(0.0, &q0, &v0);
    let times: Vec<f64> = (1..=1000).map(|k| END * k as f64 / 1000.0).collect();
    let closure = |run: &Trajectory<f64, 3>| {
        run.iter()
            .map(|s| model.constraints(s.t, &s.q).amax())
            .fold(0.0, f64::max)
    };
    let energy = |run: &Trajectory<f64, 3>| {
        run.iter()
            .map(|s| ((model.energy(s.t, &s.q, &s.qdot) - e0) / e0).abs())
            .fold(0.0, f64::max)
    };

    // Fixed steps of 1e-3, 1e-4 for the first-order methods: explicit
    // Euler's energy grows like exp(h ω² t / 2), a factor 1e3 over 100 s at
    // h = 1e-3, until the linkage spins too fast to be projected back.
    println!(
        "Every method for {END} s, projection after each step \
         (h = 1e-3, 1e-4 for first order; tol = 1e-8):"
    );
    println!(
        "{:<18} {:>8} {:>12} {:>14} {:>10} {:>10} {:>9}",
        "method", "h / tol", "max |phi| m", "max |dE/E0|", "steps", "rhs evals", "seconds"
    );
    for method in Method::ALL {
        let h = if method.order() == 1 { 1e-4 } else { 1e-3 };
        let setting = if method.is_adaptive() { 1e-8 } else { h };
        let start = Instant::now();
        let run = method
            .integrator(h, 1e-8)
            .max_steps(10_000_000)
            .integrate(&model, 0.0, q0, v0, &times);
        let seconds = start.elapsed().as_secs_f64();
        match run {
            Ok(run) => println!(
                "{:<18} {:>8.0e} {:>12.1e} {:>14.1e} {:>10} {:>10} {:>9.3}",
                method.id(),
                setting,
                closure(&run),
                energy(&run),
                run.stats().steps_accepted,
                run.stats().rhs_evals,
                seconds
            ),
            Err(failure) => println!(
                "{:<18} {:>8.0e} stopped: {}",
                method.id(),
                setting,
                failure.error
            ),
        }
    }

    println!("\nDrift control, Dopri5 at rtol = atol = 1e-8 for {END} s:");
    println!(
        "{:<28} {:>12} {:>16} {:>14} {:>10}",
        "drift control", "max |phi| m", "max |phi dot| m/s", "max |dE/E0|", "rhs evals"
    );
    let dopri = Dopri5::new().rtol(1e-8).atol(1e-8).max_steps(10_000_000);
    let controls = [
        ("projection (default)", Drift::Projection),
        (
            "Baumgarte alpha=beta=20/s",
            Drift::Baumgarte {
                alpha: 20.0,
                beta: 20.0,
            },
        ),
        ("none", Drift::None),
    ];
    let mut curves = Vec::new();
    for (name, drift) in controls {
        let run = dopri
            .integrate(&model.with_drift(drift), 0.0, q0, v0, &times)
            .map_err(|failure| failure.error.to_string())?;
        let velocity = run
            .iter()
            .map(|s| model.constraint_velocities(s.t, &s.q, &s.qdot).amax())
            .fold(0.0, f64::max);
        println!(
            "{:<28} {:>12.1e} {:>16.1e} {:>14.1e} {:>10}",
            name,
            closure(&run),
            velocity,
            energy(&run),
            run.stats().rhs_evals
        );
        let points: Vec<(f64, f64)> = run
            .iter()
            .map(|s| (s.t, model.constraints(s.t, &s.q).amax().max(1e-17)))
            .collect();
        curves.push((name, points));
    }

    // One crank turn, finely sampled: the crank's speed varies along the
    // turn, so sample a second and keep what precedes θ1(0) + 2π.
    let frames: Vec<f64> = (0..=2000).map(|k| k as f64 / 2000.0).collect();
    let run = Dop853::new()
        .rtol(1e-12)
        .atol(1e-12)
        .integrate(&model, 0.0, q0, v0, &frames)
        .map_err(|failure| failure.error.to_string())?;
    csv_option::write(&model, &run)?;
    let turn: Vec<Vector3<f64>> = run
        .iter()
        .map(|s| s.q)
        .take_while(|q| q[0] <= q0[0] + 2.0 * std::f64::consts::PI)
        .collect();
    // The constraint forces along it: λ in newtons (the loop constraints
    // are in metres), the force on the coordinates −Gᵀλ.
    let forces = annotate(&model, &run)?;
    let peak = forces[..turn.len()]
        .iter()
        .map(|s| s.multipliers.amax())
        .fold(0.0, f64::max);
    println!(
        "\nOne crank turn takes {:.3} s; largest loop force over it: {peak:.2} N",
        run.times()[turn.len() - 1]
    );

    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/four_bar/four_bar.svg");
    std::fs::create_dir_all(path.parent().unwrap())?;
    draw(&path, &model, &turn, &curves)?;
    println!("Wrote {}", path.display());
    Ok(())
}

/// The pins of the linkage at `q`: ground, crank pin, coupler end, ground.
fn pins(model: &FourBar, q: &Vector3<f64>) -> [(f64, f64); 4] {
    let a = (model.a * q[0].cos(), model.a * q[0].sin());
    let b = (a.0 + model.b * q[1].cos(), a.1 + model.b * q[1].sin());
    [(0.0, 0.0), a, b, (model.d, 0.0)]
}

fn draw(
    path: &std::path::Path,
    model: &FourBar,
    turn: &[Vector3<f64>],
    curves: &[(&str, Vec<(f64, f64)>)],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (1200, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "A crank-rocker four-bar in three angles and two loop constraints",
        ("sans-serif", 24),
    )?;
    let (left, right) = root.split_horizontally(560);

    let mut linkage = ChartBuilder::on(&left)
        .caption(
            "six instants of one crank turn, coupler midpoint path",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(-0.35..0.95, -0.35..0.75)?;
    linkage
        .configure_mesh()
        .x_desc("x [m]")
        .y_desc("y [m]")
        .draw()?;
    let midpoint = |q: &Vector3<f64>| {
        let p = pins(model, q);
        ((p[1].0 + p[2].0) / 2.0, (p[1].1 + p[2].1) / 2.0)
    };
    linkage.draw_series(LineSeries::new(
        [(0.0, 0.0), (model.d, 0.0)],
        BLACK.stroke_width(5),
    ))?;
    let path_points: Vec<(f64, f64)> = turn.iter().map(midpoint).collect();
    linkage.draw_series(LineSeries::new(path_points, BLACK.stroke_width(1)))?;
    let colors = [BLUE, RED, GREEN, MAGENTA, CYAN, RGBColor(230, 140, 0)];
    for (k, color) in colors.iter().enumerate() {
        let q = turn[k * turn.len() / colors.len()];
        let joints = pins(model, &q);
        linkage.draw_series(LineSeries::new(joints, color.stroke_width(3)))?;
        linkage.draw_series(
            joints
                .into_iter()
                .map(|p| Circle::new(p, 4, color.filled())),
        )?;
        linkage.draw_series(std::iter::once(Circle::new(
            midpoint(&q),
            4,
            BLACK.filled(),
        )))?;
    }

    let mut residual = ChartBuilder::on(&right)
        .caption(
            "closure residual max |phi|, Dopri5 tol 1e-8",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..END, (1e-17..1e-2).log_scale())?;
    residual
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc("max |phi| [m]")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .draw()?;
    for ((name, points), color) in curves.iter().zip([BLUE, GREEN, RED]) {
        residual
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?
            .label(*name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    residual
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}
