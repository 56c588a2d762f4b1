//! A thin uniform disk rolling without slipping: two velocity constraints
//! (the contact point of the disk at rest), its steady circles and its
//! upright stability in closed form.

use nalgebra::Vector5;

use crate::lagrangian;

lagrangian! {
    /// A thin uniform disk of mass `m` and radius `r` on the plane `z = 0`:
    /// contact point `(x, y)`, heading `psi` (the rolling direction
    /// `(cos ψ, sin ψ, 0)`), lean `theta` from the vertical, spin `phi`
    /// about its axis. Its centre is `r` above the contact point along the
    /// disk's plane; its angular velocity is `ψ̇ ẑ + θ̇ t̂ + φ̇ â` (`â` the
    /// axis, `â·ẑ = −sin θ`), moments `m r²/4` across the axis and `m r²/2`
    /// along it. Rolling: the disk's point at the contact is at rest,
    /// `(ẋ, ẏ) + r φ̇ (cos ψ, sin ψ) = 0`; the multipliers are the friction
    /// force there.
    ///
    /// ```
    /// use lagrange::models::RollingDisk;
    /// use lagrange::prelude::*;
    ///
    /// let disk = RollingDisk::new(1.5, 0.3, 9.81);
    /// // Leaning 0.5 rad, spinning at −6 rad/s: the precession of steady rolling.
    /// let precession = disk.steady_precession(0.5, -6.0);
    /// let (q0, v0) = disk.state(0.5, 0.0, precession, -6.0);
    /// let run = Dop853::new().rtol(1e-12).atol(1e-12).integrate(&disk, 0.0, q0, v0, &[5.0])?;
    /// assert!((run.last().unwrap().q[3] - 0.5).abs() < 1e-9); // the lean holds
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct RollingDisk {
        coordinates: x, y, psi, theta, phi;
        parameters: m, r, g;
        let cx = x + r*sin(theta)*sin(psi);
        let cy = y - r*sin(theta)*cos(psi);
        let cz = r*cos(theta);
        let axial = dot(phi) - sin(theta)*dot(psi);
        kinetic: m/2*(dot(cx)^2 + dot(cy)^2 + dot(cz)^2)
            + m*r^2/8*(dot(psi)^2 + dot(theta)^2 + dot(phi)^2 - 2*sin(theta)*dot(psi)*dot(phi))
            + m*r^2/8*axial^2;
        potential: m*g*cz;
        constraints:
            roll_x: dot(x) + r*cos(psi)*dot(phi) = 0,
            roll_y: dot(y) + r*sin(psi)*dot(phi) = 0;
    }
}

impl RollingDisk {
    /// A rolling state: contact at the origin heading along `x`, lean
    /// `theta`, lean rate `theta_dot`, heading rate `psi_dot`, spin rate
    /// `phi_dot` (the contact point moving at `−r φ̇` along the heading).
    pub fn state(
        &self,
        theta: f64,
        theta_dot: f64,
        psi_dot: f64,
        phi_dot: f64,
    ) -> (Vector5<f64>, Vector5<f64>) {
        (
            Vector5::new(0.0, 0.0, 0.0, theta, 0.0),
            Vector5::new(-self.r * phi_dot, 0.0, psi_dot, theta_dot, phi_dot),
        )
    }

    /// The heading rate `Ω` of steady rolling at lean `θ` and spin `ω`: the
    /// smaller root of the lean's equation with `θ`, `Ω`, `ω` constant,
    /// `4 g sin θ = 6 Ω ω r cos θ − 5 Ω² r sin θ cos θ` (the classical
    /// thin-disk relation; Routh, Advanced Rigid Dynamics, §244). NaN where
    /// there is no steady motion (the spin too slow for the lean).
    pub fn steady_precession(&self, theta: f64, omega: f64) -> f64 {
        let (s, c) = theta.sin_cos();
        let (qa, qb, qc) = (1.25 * self.r * s * c, -1.5 * omega * self.r * c, self.g * s);
        // a Ω² + b Ω + c = 0, its smaller root without cancellation.
        qc / (-0.5 * (qb + qb.signum() * (qb * qb - 4.0 * qa * qc).sqrt()))
    }
}
