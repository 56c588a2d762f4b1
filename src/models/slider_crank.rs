//! The slider-crank: a crank, a connecting rod and a piston, the mechanism
//! of every piston engine and pump. Written twice: in three redundant
//! coordinates closed by two loop constraints, and in the one minimal
//! coordinate, the crank angle, with the rod and piston eliminated by hand.
//! The two must move alike, and the closed form of the kinematics,
//! `s = r cos θ + √(l² − r² sin² θ)`, holds along the constrained one.

use nalgebra::Vector3;

use crate::lagrangian;

lagrangian! {
    /// Crank of radius `r` about the origin (inertia `j` about its pivot,
    /// balanced), rod of length `l` and mass `mr` (uniform), piston of mass
    /// `ms` sliding on the x axis; gravity `g` along −y. Coordinates: the
    /// crank angle `theta`, the rod angle `phi` (from the x axis, crank pin
    /// to piston) and the piston position `s`.
    pub struct SliderCrank {
        coordinates: theta, phi, s;
        parameters: r, l, j, mr, ms, g;
        let xa = r*cos(theta);
        let ya = r*sin(theta);
        let xg = xa + l/2*cos(phi);
        let yg = ya + l/2*sin(phi);
        kinetic: j/2*dot(theta)^2 + mr/2*(dot(xg)^2 + dot(yg)^2) + mr*l^2/24*dot(phi)^2
            + ms/2*dot(s)^2;
        potential: mr*g*yg;
        constraints: pin_x: xa + l*cos(phi) = s, pin_y: ya + l*sin(phi) = 0;
    }
}

lagrangian! {
    /// The same slider-crank in its one degree of freedom, the crank angle:
    /// the rod angle `φ = −asin(r sin θ / l)` and the piston position
    /// `s = r cos θ + l cos φ` written out.
    pub struct MinimalSliderCrank {
        coordinates: theta;
        parameters: r, l, j, mr, ms, g;
        let sin_phi = -r*sin(theta)/l;
        let cos_phi = sqrt(1 - sin_phi^2);
        let phi = asin(sin_phi);
        let xa = r*cos(theta);
        let ya = r*sin(theta);
        let xg = xa + l/2*cos_phi;
        let yg = ya + l/2*sin_phi;
        let s = xa + l*cos_phi;
        kinetic: j/2*dot(theta)^2 + mr/2*(dot(xg)^2 + dot(yg)^2) + mr*l^2/24*dot(phi)^2
            + ms/2*dot(s)^2;
        potential: mr*g*yg;
    }
}

/// The closed-form kinematics of a slider-crank with crank `r` and rod `l`
/// (`r < l`): the rod angle and piston position at crank angle `θ`, and
/// their rates at crank rate `θ̇`.
pub fn slider_crank_kinematics(r: f64, l: f64, theta: f64, theta_dot: f64) -> [f64; 4] {
    let (st, ct) = theta.sin_cos();
    let sin_phi = -r * st / l;
    let cos_phi = (1.0 - sin_phi * sin_phi).sqrt();
    let phi = sin_phi.asin();
    // d/dt of l sin φ = −r sin θ and of s = r cos θ + l cos φ.
    let phi_dot = -r * ct * theta_dot / (l * cos_phi);
    let s = r * ct + l * cos_phi;
    let s_dot = -r * st * theta_dot - l * sin_phi * phi_dot;
    [phi, s, phi_dot, s_dot]
}

impl SliderCrank {
    /// A small engine: crank 5 cm, rod 15 cm, flywheel 0.01 kg m², rod
    /// 0.5 kg, piston 0.3 kg, under gravity.
    pub fn engine() -> Self {
        Self::new(0.05, 0.15, 0.01, 0.5, 0.3, 9.81)
    }

    /// The consistent state at crank angle `θ` and rate `θ̇`.
    pub fn state(&self, theta: f64, theta_dot: f64) -> (Vector3<f64>, Vector3<f64>) {
        let [phi, s, phi_dot, s_dot] = slider_crank_kinematics(self.r, self.l, theta, theta_dot);
        (
            Vector3::new(theta, phi, s),
            Vector3::new(theta_dot, phi_dot, s_dot),
        )
    }

    /// The same mechanism in its minimal coordinate.
    pub fn minimal(&self) -> MinimalSliderCrank {
        MinimalSliderCrank::new(self.r, self.l, self.j, self.mr, self.ms, self.g)
    }
}
