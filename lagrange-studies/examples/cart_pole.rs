//! A cart on a rail carrying a pendulum, pushed by a motor and slowed by air
//! drag on the bob. The drag is written where it acts, along the bob's
//! position (`forces: xb = .., yb = ..`), and the macro turns it into
//! generalized forces by virtual work, `Q_i = F · ∂r/∂q_i`.
//!
//! The check is physical: the energy gained, `E(t) − E(0)`, must equal the
//! work the forces did, `∫ (F ẋ − c |v_bob|²) dt`, integrated here along the
//! trajectory with Simpson's rule on a dense sample grid.
//!
//! `cargo run --release -p lagrange-studies --example cart_pole`

use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;
use std::error::Error;

lagrangian! {
    /// A cart of mass `mc` on a horizontal rail (position `x`) with a
    /// pendulum: bob `m` on a massless rod `l`, angle `theta` from the
    /// downward vertical. The motor pushes the cart with `f0 sin(w t)`; air
    /// drag `−c v` acts on the bob.
    pub struct CartPole {
        coordinates: x, theta;
        parameters: mc, m, l, f0, w, c;
        constants: g = 9.81;
        let xb = x + l*sin(theta);
        let yb = -l*cos(theta);
        kinetic: mc/2*dot(x)^2 + m/2*(dot(xb)^2 + dot(yb)^2);
        potential: m*g*yb;
        forces: x = f0*sin(w*t), xb = -c*dot(xb), yb = -c*dot(yb);
    }
}

fn main() -> Result<(), Box<dyn Error>> {
    // Driven near the pendulum's own frequency, sqrt(g/l) = 4.4 rad/s.
    let cart = CartPole::new(1.0, 0.3, 0.5, 2.0, 4.0, 0.05);
    println!("Derived at compile time (M q'' = f):\n");
    println!("{}", CartPole::<f64>::EQUATIONS);

    let (q0, qdot0) = (Vector2::new(0.0, 0.1), Vector2::zeros());
    let (dt, samples) = (1e-3, 10_000);
    let times: Vec<f64> = (1..=samples).map(|k| dt * k as f64).collect();
    let tol = 1e-11;
    let trajectory = Dopri5::new()
        .rtol(tol)
        .atol(tol)
        .integrate(&cart, 0.0, q0, qdot0, &times)?;

    // The power of each force: the motor's F ẋ and the drag's −c |v_bob|².
    let power = |t: f64, q: &Vector2<f64>, qdot: &Vector2<f64>| {
        let vx = qdot[0] + cart.l * q[1].cos() * qdot[1];
        let vy = cart.l * q[1].sin() * qdot[1];
        let motor = cart.f0 * (cart.w * t).sin() * qdot[0];
        (motor, -cart.c * (vx * vx + vy * vy))
    };
    let start = std::iter::once((0.0, q0, qdot0));
    let states: Vec<_> = start
        .chain(trajectory.iter().map(|s| (s.t, s.q, s.qdot)))
        .collect();
    let powers: Vec<(f64, f64)> = states.iter().map(|(t, q, v)| power(*t, q, v)).collect();

    let e0 = cart.energy(0.0, &q0, &qdot0);
    let (mut motor, mut drag, mut moved) = (0.0, 0.0, 0.0);
    let mut worst: f64 = 0.0;
    println!(
        "Dormand–Prince 5(4), rtol = atol = {tol:.0e}; work by Simpson's rule, dt = {dt:.0e}:"
    );
    println!(
        "{:>5} {:>10} {:>10} {:>10} {:>11} {:>11} {:>12}",
        "t", "x", "theta", "E - E0", "W motor", "W drag", "E - E0 - W"
    );
    for k in (0..=samples).step_by(2) {
        if k > 0 {
            let simpson = |p: fn(&(f64, f64)) -> f64| {
                dt / 3.0 * (p(&powers[k - 2]) + 4.0 * p(&powers[k - 1]) + p(&powers[k]))
            };
            motor += simpson(|p| p.0);
            drag += simpson(|p| p.1);
            moved += simpson(|p| p.0.abs() - p.1);
        }
        let (t, q, qdot) = &states[k];
        let gained = cart.energy(*t, q, qdot) - e0;
        let residual = gained - motor - drag;
        worst = worst.max(residual.abs());
        if k % 1000 == 0 {
            println!(
                "{t:>5.1} {:>10.5} {:>10.5} {gained:>10.5} {motor:>11.6} {drag:>11.6} {residual:>12.2e}",
                q[0], q[1]
            );
        }
    }
    println!(
        "\nThe motor put in {motor:.6} J net and the drag took {:.6} J; energy moved in or out \
         in total: {moved:.6} J.\nWorst |E - E0 - W| over the run: {worst:.2e} J, \
         {:.1e} of the energy moved.",
        -drag,
        worst / moved
    );
    println!("{:?}", trajectory.stats());
    Ok(())
}
