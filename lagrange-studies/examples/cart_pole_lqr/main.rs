//! From a model to a controller: the cart-pole linearized at its upright
//! equilibrium, an LQR gain from the Riccati equation, and the nonlinear
//! closed loop simulated from a 20° tilt with the controller as a closure.
//!
//! `cargo run --release -p lagrange-studies --example cart_pole_lqr`
//!
//! Writes `docs/cart_pole_lqr/cart_pole_lqr.svg`: the pole angle and the
//! force on the cart over time.

mod riccati;

use lagrange::analysis::{linearize_with_inputs, modes};
use lagrange::models::CartPole;
use lagrange::nalgebra::{DMatrix, Vector1, Vector2};
use lagrange::prelude::*;
use plotters::prelude::*;
use std::error::Error;

fn main() -> Result<(), Box<dyn Error>> {
    // Cart 1 kg, bob 0.1 kg on a 0.5 m rod, θ from the upright vertical,
    // a force on the cart as the one input.
    let model = CartPole::new(1.0, 0.1, 0.5, 9.81);
    let upright = (Vector2::zeros(), Vector2::zeros(), Vector1::new(0.0));

    // At rest upright the pole falls: one unstable mode.
    let at_rest = model.with_inputs(&Vector1::new(0.0));
    let modes = modes(&at_rest, 0.0, &upright.0)?;
    for mode in &modes.modes {
        println!(
            "mode at rest upright: ω² = {:.6} /s², {:?}",
            mode.omega_squared, mode.kind
        );
    }

    // The linearization there, exact (the model has #[lagrange(jacobians)]).
    let lin = linearize_with_inputs(&model, 0.0, &upright.0, &upright.1, &upright.2)?;
    let (a, b) = (lin.state.state_matrix(), lin.input_matrix());
    println!("exact linearization at the upright (x = (x, θ, ẋ, θ̇), u = force):");
    print_matrix("A", &a);
    print_matrix("B", &b);

    // LQR: weights on cart position, angle, their rates; a unit force costs
    // 0.1 of a radian squared.
    let q = DMatrix::from_diagonal(&lagrange::nalgebra::DVector::from_vec(vec![
        10.0, 100.0, 1.0, 1.0,
    ]));
    let r = DMatrix::from_element(1, 1, 0.1);
    let (p, residual) = riccati::care(&a, &b, &q, &r)?;
    let gain = r.clone().try_inverse().ok_or("R is singular")? * b.transpose() * &p;
    println!("LQR, Q = diag(10, 100, 1, 1), R = 0.1: Riccati residual {residual:.1e}");
    print_matrix("K", &gain);
    let closed = &a - &b * &gain;
    let poles = closed.complex_eigenvalues();
    let listed: Vec<String> = poles
        .iter()
        .map(|z| format!("{:.3}{:+.3}i", z.re, z.im))
        .collect();
    println!("closed-loop poles: {}", listed.join(", "));
    if poles.iter().any(|z| z.re >= 0.0) {
        return Err("the LQR gain does not stabilize the linearization".into());
    }

    // The nonlinear closed loop from a 20° tilt: u = −K x at every
    // right-hand side.
    let k: [f64; 4] = [gain[(0, 0)], gain[(0, 1)], gain[(0, 2)], gain[(0, 3)]];
    let control = move |q: &Vector2<f64>, qdot: &Vector2<f64>| {
        -(k[0] * q[0] + k[1] * q[1] + k[2] * qdot[0] + k[3] * qdot[1])
    };
    let controlled = model.with_controller(move |_t, q, qdot| Vector1::new(control(q, qdot)));
    let q0 = Vector2::new(0.0, 20f64.to_radians());
    let times: Vec<f64> = (0..=500).map(|i| 0.01 * i as f64).collect();
    let run = Dopri5::new()
        .rtol(1e-10)
        .atol(1e-10)
        .integrate(&controlled, 0.0, q0, Vector2::zeros(), &times)
        .map_err(|f| f.error.to_string())?;
    let angle: Vec<(f64, f64)> = run.iter().map(|s| (s.t, s.q[1].to_degrees())).collect();
    let force: Vec<(f64, f64)> = run.iter().map(|s| (s.t, control(&s.q, &s.qdot))).collect();
    let settled = run
        .iter()
        .find(|s| {
            run.iter()
                .filter(|later| later.t >= s.t)
                .all(|later| later.q[1].abs() < 1f64.to_radians())
        })
        .map_or(f64::NAN, |s| s.t);
    let end = run.last().ok_or("no samples")?;
    let peak = force.iter().map(|(_, f)| f.abs()).fold(0.0, f64::max);
    println!(
        "from 20°: within 1° from t = {settled:.2} s; at t = {:.0} s angle {:.1e}°, cart {:.2e} m; peak force {peak:.1} N; {} right-hand sides",
        end.t,
        end.q[1].to_degrees(),
        end.q[0],
        run.stats().rhs_evals
    );

    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../docs/cart_pole_lqr/cart_pole_lqr.svg");
    std::fs::create_dir_all(path.parent().unwrap())?;
    draw(&path, &angle, &force)?;
    println!("Wrote {}", path.display());
    Ok(())
}

fn print_matrix(name: &str, m: &DMatrix<f64>) {
    for i in 0..m.nrows() {
        let row: Vec<String> = m
            .row(i)
            .iter()
            .map(|x| format!("{:>10.4}", x + 0.0))
            .collect();
        let label = if i == 0 {
            format!("{name} =")
        } else {
            String::new()
        };
        println!("{label:>4} [{} ]", row.join(""));
    }
}

fn draw(
    path: &std::path::Path,
    angle: &[(f64, f64)],
    force: &[(f64, f64)],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Cart-pole, LQR from the exact linearization, nonlinear closed loop from 20°",
        ("sans-serif", 20),
    )?;
    let (top, bottom) = root.split_vertically(270);
    let end = angle.last().map_or(5.0, |p| p.0);
    for (area, points, label, color) in [
        (&top, angle, "pole angle [deg]", BLUE),
        (&bottom, force, "force on the cart [N]", RED),
    ] {
        let lo = points.iter().map(|p| p.1).fold(0.0, f64::min);
        let hi = points.iter().map(|p| p.1).fold(0.0, f64::max);
        let pad = 0.1 * (hi - lo).max(1e-9);
        let mut chart = ChartBuilder::on(area)
            .margin(10)
            .x_label_area_size(35)
            .y_label_area_size(55)
            .build_cartesian_2d(0.0..end, (lo - pad)..(hi + pad))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc(label)
            .draw()?;
        chart.draw_series(LineSeries::new(
            points.iter().copied(),
            color.stroke_width(2),
        ))?;
    }
    root.present()?;
    Ok(())
}
