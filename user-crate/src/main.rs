//! The README's model and its use, as a user's crate holds them: built and
//! run by CI without a warning (`.ci/run`). The README's blocks are copied
//! here as they are; `lagrange-engine/tests/engine/readme.rs` checks that
//! they still are.
#![deny(warnings)]

use lagrange::prelude::*;

lagrangian! {
    /// The double pendulum, absolute angles from the downward vertical.
    pub struct DoublePendulum {
        coordinates: theta1, theta2;
        parameters: m1, m2, l1, l2, g;
        let x1 = l1*sin(theta1);
        let y1 = -l1*cos(theta1);
        let x2 = x1 + l2*sin(theta2);
        let y2 = y1 - l2*cos(theta2);
        kinetic: m1/2*(dot(x1)^2 + dot(y1)^2) + m2/2*(dot(x2)^2 + dot(y2)^2);
        potential: m1*g*y1 + m2*g*y2;
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    use lagrange::nalgebra::Vector2;

    let pendulum = DoublePendulum::new(1.0, 1.0, 1.0, 1.0, 9.81);
    let (q0, qdot0) = (Vector2::new(2.0, 2.5), Vector2::zeros());

    let m = pendulum.mass_matrix(0.0, &q0); // M(q)
    let f = pendulum.forcing(0.0, &q0, &qdot0); // f(q, q̇)
    println!("M = {m}f = {f}");
    println!("{}", DoublePendulum::<f64>::EQUATIONS); // the derived equations as text

    // Adaptive Dormand–Prince, sampled at the times asked for.
    let method = Dopri5::new().rtol(1e-10).atol(1e-10);
    let trajectory = method.integrate(&pendulum, 0.0, q0, qdot0, &[0.5, 1.0, 2.0])?;
    for s in &trajectory {
        let energy = pendulum.energy(s.t, &s.q, &s.qdot);
        println!("t = {}: q = {}, energy = {energy}", s.t, s.q);
    }
    println!("{:?}", trajectory.stats()); // steps accepted/rejected, rhs evaluations
    Ok(())
}
