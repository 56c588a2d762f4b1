//! A torsion pendulum whose bearing carries a given load: Coulomb friction
//! in a joint, against a given normal force.

use crate::lagrangian;

lagrangian! {
    /// A disk of moment of inertia `inertia` on a torsion spring of
    /// stiffness `kappa` (rest at `theta = 0`), turning in a bearing pressed
    /// by a given load `load` at radius `r`: static friction `mus` above
    /// kinetic `muk`, a friction torque of at most `mus load r` while it
    /// sticks and `muk load r` against its turning while it slides. The
    /// contact has no gap: its normal force is the load, not a reaction.
    pub struct TorsionBearing {
        coordinates: theta;
        parameters: inertia, kappa, load, r, mus, muk;
        kinetic: inertia/2*dot(theta)^2;
        potential: kappa/2*theta^2;
        contacts: bearing: { normal: load, static_friction: mus, kinetic_friction: muk, slip: r*dot(theta) };
    }
}

/// One swing of [`TorsionBearing`] between two turning points, in closed
/// form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Swing {
    /// When it starts, at rest.
    pub start: f64,
    /// Where it starts.
    pub from: f64,
    /// Where it comes to rest again, half a period later: `2 s d − θₙ`,
    /// `s` the sign of `θₙ`, `d = μ_k load r / κ`.
    pub to: f64,
}

impl TorsionBearing<f64> {
    /// The swings from rest at `theta0` (the Coulomb-damped oscillator:
    /// each half period `π √(inertia/κ)` is harmonic about `s d`, the
    /// friction torque's balance point, so each swing is `2d` shorter),
    /// until a turning point where the spring's torque `κ |θ|` is within
    /// static friction's `μ_s load r`: there it sticks for good. Released
    /// from rest; empty where it never slips (`κ |θ₀| ≤ μ_s load r`).
    pub fn swings(&self, theta0: f64) -> Vec<Swing> {
        let omega = (self.kappa / self.inertia).sqrt();
        let d = self.muk * self.load * self.r / self.kappa;
        let holds = self.mus * self.load * self.r / self.kappa;
        let mut swings = Vec::new();
        let (mut t, mut theta) = (0.0, theta0);
        while theta.abs() > holds && swings.len() < 1000 {
            let to = 2.0 * theta.signum() * d - theta;
            swings.push(Swing {
                start: t,
                from: theta,
                to,
            });
            t += core::f64::consts::PI / omega;
            theta = to;
        }
        swings
    }

    /// The angle during `swing` at time `t` (within its half period):
    /// `s d + (θₙ − s d) cos(ω (t − tₙ))`.
    pub fn angle(&self, swing: &Swing, t: f64) -> f64 {
        let omega = (self.kappa / self.inertia).sqrt();
        let center = swing.from.signum() * self.muk * self.load * self.r / self.kappa;
        center + (swing.from - center) * (omega * (t - swing.start)).cos()
    }
}
