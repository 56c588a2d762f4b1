//! A ladder leaning against a rough wall on a rough floor: held below its
//! friction angle, sliding beyond it, and pushed until it slips.

use crate::lagrangian;

lagrangian! {
    /// A uniform ladder of mass `m` and length `l` (its moment of inertia
    /// `m l²/12` about its centre) leaning against a rough wall (`x = 0`,
    /// friction `mu_w`) on a rough floor (`y = 0`, friction `mu_f`), static
    /// and kinetic alike, in the coordinates of its centre `(x, y)` and its
    /// angle `theta` from the wall: its top `(x − l/2 sin θ, y + l/2 cos
    /// θ)` against the wall, its foot `(x + l/2 sin θ, y − l/2 cos θ)` on
    /// the floor. A horizontal push `P = p0 + rate t` at its centre acts
    /// away from the wall (towards it where negative).
    ///
    /// While both ends stick, its forces are statically indeterminate:
    /// four unknowns (each end's normal force and friction) and three
    /// equations of equilibrium, so load can move between the wall's
    /// friction and the floor's normal force.
    ///
    /// ```
    /// use lagrange::contact::{self, ContactSettings, Mode};
    /// use lagrange::models::RoughLadder;
    /// use lagrange::nalgebra::SVector;
    /// use lagrange::prelude::*;
    ///
    /// let ladder = RoughLadder::new(10.0, 4.0, 9.81, 0.5, 0.5, 0.0, 0.0);
    /// // Held iff tan θ ≤ 2 μ_f / (1 − μ_f μ_w) = 4/3.
    /// let theta = 1.2f64.atan();
    /// assert!(ladder.holds(theta));
    /// let (q, v) = ladder.at_rest(theta);
    /// let run = contact::integrate(
    ///     &Dop853::new().rtol(1e-10).atol(1e-10),
    ///     &ladder,
    ///     0.0,
    ///     SVector::from(q),
    ///     SVector::from(v),
    ///     &[1.0],
    ///     ContactSettings::default(),
    /// )
    /// .unwrap();
    /// assert_eq!(run.modes()[0], [Mode::Stuck; 2]);
    /// ```
    pub struct RoughLadder {
        coordinates: x, y, theta;
        parameters: m, l, g, mu_w, mu_f, p0, rate;
        let top_x = x - l/2*sin(theta);
        let top_y = y + l/2*cos(theta);
        let foot_x = x + l/2*sin(theta);
        let foot_y = y - l/2*cos(theta);
        kinetic: m/2*(dot(x)^2 + dot(y)^2) + m*l^2/24*dot(theta)^2;
        potential: m*g*y;
        forces: x = p0 + rate*t;
        contacts:
            wall: top_x >= 0 { friction: mu_w, slip: dot(top_y) },
            floor: foot_y >= 0 { friction: mu_f, slip: dot(foot_x) };
    }
}

impl RoughLadder<f64> {
    /// At rest at angle `theta` from the wall, touching both.
    pub fn at_rest(&self, theta: f64) -> ([f64; 3], [f64; 3]) {
        let h = self.l / 2.0;
        ([h * theta.sin(), h * theta.cos(), theta], [0.0; 3])
    }

    /// Whether the ladder stands, unpushed, at angle `theta` from the
    /// wall: `tan θ ≤ 2 μ_f / (1 − μ_f μ_w)` where `μ_f μ_w < 1`, always
    /// where `μ_f μ_w ≥ 1`. At the limit both ends slip together: with
    /// `F_f = μ_f N_f` (towards the wall) and `F_w = μ_w N_w` (up), the
    /// balance of forces `N_w = F_f`, `N_f + F_w = m g` gives `N_f = m g /
    /// (1 + μ_f μ_w)`, and the moments about the foot, `m g (l/2) sin θ =
    /// N_w l cos θ + F_w l sin θ`, the angle.
    pub fn holds(&self, theta: f64) -> bool {
        let product = self.mu_f * self.mu_w;
        product >= 1.0 || theta.tan() <= 2.0 * self.mu_f / (1.0 - product)
    }

    /// The push away from the wall (`P > 0`) at which the ladder standing
    /// at `theta` slips, its foot out and its top down: `P = m g (2 μ_f −
    /// tan θ (1 − μ_f μ_w)) / (1 − μ_f μ_w + 2 μ_w tan θ)` (both ends at
    /// their limits, `F_f = −μ_f N_f`, `F_w = μ_w N_w`, with the push in
    /// the balance). It holds where the wall still pushes then, `N_w = (μ_f
    /// m g − P) / (1 + μ_f μ_w) > 0`, that is where `tan θ > μ_f`.
    pub fn slipping_push(&self, theta: f64) -> f64 {
        let (t, product) = (theta.tan(), self.mu_f * self.mu_w);
        self.m * self.g * (2.0 * self.mu_f - t * (1.0 - product))
            / (1.0 - product + 2.0 * self.mu_w * t)
    }

    /// The push towards the wall (`P < 0`) at which the ladder standing
    /// at `theta` slips the other way, its foot in and its top up: `P = m
    /// g (2 μ_f + tan θ (1 − μ_f μ_w)) / (μ_f μ_w − 1 + 2 μ_w tan θ)` (both
    /// ends at their limits the other way, `F_f = μ_f N_f`, `F_w = −μ_w
    /// N_w`). `None` where that is not negative (`1 − μ_f μ_w ≤ 2 μ_w tan
    /// θ`): pushed towards the wall, the ladder jams.
    pub fn climbing_push(&self, theta: f64) -> Option<f64> {
        let (t, product) = (theta.tan(), self.mu_f * self.mu_w);
        let denominator = product - 1.0 + 2.0 * self.mu_w * t;
        (denominator < 0.0)
            .then(|| self.m * self.g * (2.0 * self.mu_f + t * (1.0 - product)) / denominator)
    }
}
