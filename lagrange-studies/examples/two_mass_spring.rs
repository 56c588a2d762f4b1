//! The textbook's damped two-mass chain: wall – k1 – m1 – k2 – m2 – k3 – wall,
//! with dampers c1, c2, c3 beside the springs, written with a Rayleigh
//! dissipation function. Prints the derived equations, simulates, and checks
//! the energy balance: what the dampers dissipate is what the energy loses.
//! The model is `lagrange::models::RayleighTwoMassChain`
//! (`src/models/two_mass_chain.rs`).
//!
//! `cargo run --release -p lagrange-studies --example two_mass_spring`

use lagrange::models::RayleighTwoMassChain;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let chain = RayleighTwoMassChain::new(1.0, 2.0, 10.0, 20.0, 15.0, 0.1, 0.2, 0.3);
    println!("Derived at compile time (M q'' = f):\n");
    println!("{}", RayleighTwoMassChain::<f64>::EQUATIONS);

    let (q0, qdot0) = (Vector2::new(0.1, -0.05), Vector2::zeros());
    let dt = 0.01;
    let times: Vec<f64> = (1..=2000).map(|k| dt * k as f64).collect();
    let trajectory = Dopri5::new()
        .rtol(1e-10)
        .atol(1e-12)
        .integrate(&chain, 0.0, q0, qdot0, &times)?;

    // Power dissipated by a quadratic Rayleigh function is 2R; integrate it
    // along the samples (trapezoid) and compare with the energy lost.
    let rayleigh = |v: &Vector2<f64>| {
        let dv = v[1] - v[0];
        0.5 * (chain.c1 * v[0] * v[0] + chain.c2 * dv * dv + chain.c3 * v[1] * v[1])
    };
    let e0 = chain.energy(0.0, &q0, &qdot0);
    let (mut dissipated, mut prev_power) = (0.0, 2.0 * rayleigh(&qdot0));
    println!(
        "{:>6} {:>12} {:>12} {:>12} {:>14}",
        "t", "x1", "x2", "E", "E0 - E - W"
    );
    for s in &trajectory {
        let power = 2.0 * rayleigh(&s.qdot);
        dissipated += 0.5 * dt * (power + prev_power);
        prev_power = power;
        let e = chain.energy(s.t, &s.q, &s.qdot);
        if (s.t * 100.0).round() as i64 % 200 == 0 {
            println!(
                "{:>6.1} {:>12.6} {:>12.6} {:>12.4e} {:>14.2e}",
                s.t,
                s.q[0],
                s.q[1],
                e,
                e0 - e - dissipated
            );
        }
    }
    println!(
        "\nEnergy fell from {e0:.6} to {:.3e}; the last column is the balance residual,\n\
         limited by the trapezoid rule's O(dt^2) error on the dissipated work.",
        chain.energy(
            20.0,
            &trajectory.last().unwrap().q,
            &trajectory.last().unwrap().qdot
        )
    );
    println!("{:?}", trajectory.stats());
    Ok(())
}
