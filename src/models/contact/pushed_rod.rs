//! A rod lying on two rough supports of a table, pushed in the table's
//! plane off its centre of mass: friction in two discs that must share a
//! load and a turning moment between them, statically indeterminate.

use crate::lagrangian;

lagrangian! {
    /// A thin rod of mass `m` (moment of inertia `j` about its centre of
    /// mass, across it; none about its own axis) lying on a table on two
    /// point supports of its axis, at `a1` behind its centre of mass and
    /// `a2` ahead of it, each rough (`mu`) with friction in the table's
    /// plane. Its centre is `(x, y, z)`, its axis at yaw `theta` and pitch
    /// `phi`. It is pushed at the point `c` ahead of its centre by a force
    /// in the table's plane at angle `a` from the x axis, `P = p0 +
    /// rate t`.
    ///
    /// While both supports stick, their friction is statically
    /// indeterminate: four unknowns (each support's friction in the plane)
    /// and three equations of equilibrium in the plane, so friction along
    /// the rod can move between them, and must where the moment across it
    /// loads one support more than its share of the weight.
    ///
    /// ```
    /// use lagrange::models::PushedRod;
    ///
    /// let (m, g, mu) = (1.0, 9.81, 0.5);
    /// let a = 30f64.to_radians();
    /// let rod = PushedRod::new(m, 0.1, 0.6, 0.4, 0.3, g, mu, a, 0.0, 0.0);
    /// let p = rod.breakaway_push();
    /// // Below the puck's μ m g: the moment takes some of the discs.
    /// assert!(p < mu * m * g && rod.holds(0.999 * p) && !rod.holds(1.001 * p));
    /// // Friction shared in proportion to the loads would leave a disc
    /// // before it.
    /// assert!(rod.proportional_use(0.95 * p) > 1.0);
    /// ```
    pub struct PushedRod {
        coordinates: x, y, z, theta, phi;
        parameters: m, j, a1, a2, c, g, mu, a, p0, rate;
        let ax = cos(phi)*cos(theta);
        let ay = cos(phi)*sin(theta);
        let back_x = x - a1*ax;
        let back_y = y - a1*ay;
        let front_x = x + a2*ax;
        let front_y = y + a2*ay;
        let push_x = x + c*ax;
        let push_y = y + c*ay;
        kinetic: m/2*(dot(x)^2 + dot(y)^2 + dot(z)^2) + j/2*(dot(phi)^2 + cos(phi)^2*dot(theta)^2);
        potential: m*g*z;
        forces: push_x = (p0 + rate*t)*cos(a), push_y = (p0 + rate*t)*sin(a);
        contacts: back: z + a1*sin(phi) >= 0 { friction: mu, slip: vector(dot(back_x), dot(back_y)) },
                  front: z - a2*sin(phi) >= 0 { friction: mu, slip: vector(dot(front_x), dot(front_y)) };
    }
}

impl PushedRod<f64> {
    /// The supports' loads at rest, `(m g a2, m g a1) / (a1 + a2)`: the
    /// weight shared by the lever rule (the push, in the table's plane at
    /// the height of the supports, takes no part).
    pub fn loads(&self) -> (f64, f64) {
        let (weight, span) = (self.m * self.g, self.a1 + self.a2);
        (weight * self.a2 / span, weight * self.a1 / span)
    }

    /// The friction across the rod (the table's `y` for a rod along `x`)
    /// that each support must carry, for a push of size `p` at rest along
    /// `x`: the push's component across, `p sin a`, shared so that the
    /// moment about the centre of mass is nil (`−a1 F₁ + a2 F₂ + c p sin a
    /// = 0`), `−p sin a (a2 − c, a1 + c) / (a1 + a2)`: the support nearer
    /// the push carries more. Only the friction along the rod is shared
    /// freely.
    pub fn across(&self, p: f64) -> (f64, f64) {
        let (span, across) = (self.a1 + self.a2, p * self.a.sin());
        (
            -across * (self.a2 - self.c) / span,
            -across * (self.a1 + self.c) / span,
        )
    }

    /// Whether some friction within both discs holds the rod at rest
    /// along `x` under a push of size `p`: the friction along the rod, of
    /// sum `−p cos a`, shared in any way, fits within what the discs leave
    /// once the friction across is carried, `Σ √((μ Nᵢ)² − Fᵢ²)` (each
    /// `|Fᵢ| ≤ μ Nᵢ` across first).
    pub fn holds(&self, p: f64) -> bool {
        let (n, f) = (self.loads(), self.across(p));
        let room = |n: f64, f: f64| {
            let cap = self.mu * n;
            (f.abs() <= cap).then(|| (cap * cap - f * f).sqrt())
        };
        match (room(n.0, f.0), room(n.1, f.1)) {
            (Some(r0), Some(r1)) => (p * self.a.cos()).abs() <= r0 + r1,
            _ => false,
        }
    }

    /// The push at which it breaks away, pushed from rest along `x`: the
    /// largest `p` that [`holds`](Self::holds), by bisection to rounding
    /// (below `μ m g`, which no distribution can carry).
    pub fn breakaway_push(&self) -> f64 {
        let (mut lo, mut hi) = (0.0, self.mu * self.m * self.g * (1.0 + 1e-12));
        while hi - lo > 1e-15 * hi {
            let mid = 0.5 * (lo + hi);
            if self.holds(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The largest use of the two discs, `maxᵢ |Fᵢ| / (μ Nᵢ)`, by friction
    /// shared in proportion to the discs, under a push of size `p` at
    /// rest: along the rod, each support's share of `−p cos a` in
    /// proportion to its load; across it, what the moment requires. Above
    /// 1 before [`breakaway_push`](Self::breakaway_push) wherever the push
    /// is off the centre of mass across the rod (`c ≠ 0`, `sin a ≠ 0`).
    pub fn proportional_use(&self, p: f64) -> f64 {
        let (n, f) = (self.loads(), self.across(p));
        let along = -p * self.a.cos() / (n.0 + n.1);
        let use_of = |n: f64, f: f64| (along * n).hypot(f) / (self.mu * n);
        use_of(n.0, f.0).max(use_of(n.1, f.1))
    }
}
