//! Parameters, coordinates and inputs named as physics writes them (`R`,
//! `Omega`, `I1`, `Theta`) compile without a `non_snake_case` warning in
//! the user's crate: the generated items allow the names the user chose.
//! (Denied here, so that a warning would fail the build.)

#![deny(non_snake_case)]

use lagrange::prelude::*;

lagrangian! {
    /// A bead on a hoop of radius `R` spun at `Omega` about its vertical
    /// diameter, with moment of inertia `I1` of the hoop's hub on the
    /// driven axis (unused by the bead) and a torque `Tau` on the angle.
    pub struct SpunHoop {
        coordinates: Theta;
        parameters: m, R, Omega, g;
        inputs: Tau;
        kinetic: m/2*R^2*(dot(Theta)^2 + Omega^2*sin(Theta)^2);
        potential: -m*g*R*cos(Theta);
        forces: Theta = Tau;
    }
}

/// The bead's relative equilibrium off the bottom, `cos Θ = g / (R Ω²)`
/// for `Ω² > g / R`: the model is usable as written, not only compiled.
#[test]
fn a_model_named_as_physics_writes_it_compiles_and_runs() {
    let (m, r, omega, g) = (0.1f64, 0.5f64, 6.0f64, 9.81f64);
    let hoop = SpunHoop::new(m, r, omega, g).with_inputs(&lagrange::nalgebra::Vector1::new(0.0));
    let theta = (g / (r * omega * omega)).acos();
    let q = lagrange::nalgebra::Vector1::new(theta);
    let qddot =
        lagrange::dynamics::acceleration(&hoop, 0.0, &q, &lagrange::nalgebra::Vector1::zeros())
            .unwrap();
    // Rounding of terms of size g / R ≈ 20 /s².
    assert!(qddot[0].abs() < 1e-13, "θ̈ = {}", qddot[0]);
}
