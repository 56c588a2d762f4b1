//! The textbook double pendulum: derive, print the equations, simulate the
//! chaotic case, and report how well each integrator keeps the energy. The
//! model is `lagrange::models::DoublePendulum` (`src/models/double_pendulum.rs`,
//! written as in the README); `lagrange-studies/examples/chain.rs` shows a model written out.
//!
//! `cargo run --release -p lagrange-studies --example double_pendulum`
//!
//! With `--features csv`, `-- --csv FILE` also writes the Dormand–Prince run
//! as CSV (`t, theta1, theta2, theta1_dot, theta2_dot, energy`).

#[path = "support/csv_option.rs"]
mod csv_option;

use lagrange::models::DoublePendulum;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let pendulum = DoublePendulum::unit();
    println!("Derived at compile time (M q'' = f, with e_k shared subexpressions):\n");
    println!("{}", DoublePendulum::<f64>::EQUATIONS);

    // Released from rest at large angles: chaotic.
    let (q0, qdot0) = (Vector2::new(2.0, 2.5), Vector2::zeros());
    let e0 = pendulum.energy(0.0, &q0, &qdot0);
    let times: Vec<f64> = (0..=20).map(|k| 0.5 * k as f64).collect();

    let trajectory = Dopri5::new()
        .rtol(1e-10)
        .atol(1e-10)
        .integrate(&pendulum, 0.0, q0, qdot0, &times)?;
    println!("Dormand–Prince 5(4), rtol = atol = 1e-10:");
    println!(
        "{:>6} {:>12} {:>12} {:>12}",
        "t", "theta1", "theta2", "E - E0"
    );
    for s in &trajectory {
        let de = pendulum.energy(s.t, &s.q, &s.qdot) - e0;
        println!(
            "{:>6.1} {:>12.6} {:>12.6} {:>12.2e}",
            s.t, s.q[0], s.q[1], de
        );
    }
    println!("{:?}\n", trajectory.stats());
    csv_option::write(&pendulum, &trajectory)?;

    println!("Energy error at t = 10 by method (the flow conserves E = {e0:.6}):");
    println!("{:<28} {:>12} {:>10}", "method", "|E - E0|", "rhs evals");
    let end = |t: &Trajectory<f64, 2>| {
        let s = t.last().unwrap();
        (pendulum.energy(s.t, &s.q, &s.qdot) - e0).abs()
    };
    for tol in [1e-6, 1e-8, 1e-10, 1e-12] {
        let t = Dopri5::new()
            .rtol(tol)
            .atol(tol)
            .integrate(&pendulum, 0.0, q0, qdot0, &[10.0])?;
        println!(
            "{:<28} {:>12.2e} {:>10}",
            format!("dopri5 tol {tol:.0e}"),
            end(&t),
            t.stats().rhs_evals
        );
    }
    for h in [1e-2, 1e-3, 1e-4] {
        let t = Rk4::new(h).integrate(&pendulum, 0.0, q0, qdot0, &[10.0])?;
        println!(
            "{:<28} {:>12.2e} {:>10}",
            format!("rk4 h {h:.0e}"),
            end(&t),
            t.stats().rhs_evals
        );
    }
    Ok(())
}
