//! The four-bar linkage: the simplest closed loop with one degree of
//! freedom, three moving links in three angles closed by two loop
//! constraints. As a crank-rocker (Grashof: the shortest link, the crank,
//! turns fully) it runs for ever; as a parallelogram it has a change point
//! where every pin is on one line and the loop constraints lose rank.
//! `MinimalFourBar` is the crank-rocker with its loop eliminated by hand.

use nalgebra::Vector3;

use crate::lagrangian;

lagrangian! {
    /// Ground pivots at the origin and at `(d, 0)`; a crank of length `a`
    /// (angle `theta1`), a coupler `b` (`theta2`) and a rocker `c`
    /// (`theta3`, about `(d, 0)`), all angles from the x axis. The links are
    /// uniform rods of masses `m1`, `m2`, `m3`, the crank also drives a
    /// flywheel of inertia `j`; gravity `g` along −y.
    pub struct FourBar {
        coordinates: theta1, theta2, theta3;
        parameters: a, b, c, d, m1, m2, m3, j, g;
        let xa = a*cos(theta1);
        let ya = a*sin(theta1);
        let x2 = xa + b/2*cos(theta2);
        let y2 = ya + b/2*sin(theta2);
        kinetic: (j + m1*a^2/3)/2*dot(theta1)^2
            + m2/2*(dot(x2)^2 + dot(y2)^2) + m2*b^2/24*dot(theta2)^2
            + m3*c^2/6*dot(theta3)^2;
        potential: g*(m1*ya/2 + m2*y2 + m3*c/2*sin(theta3));
        constraints:
            loop_x: xa + b*cos(theta2) = d + c*cos(theta3),
            loop_y: ya + b*sin(theta2) = c*sin(theta3);
    }
}

lagrangian! {
    /// The same crank-rocker in its one minimal coordinate, the crank angle
    /// `theta1`: the coupler's far end `B = (bx, by)` is where the circles
    /// of radius `b` about the crank pin and `c` about `(d, 0)` meet, on
    /// the branch [`FourBar::state`] takes, eliminated by hand. The
    /// coupler's centre is the midpoint of its pins, and its rate and the
    /// rocker's follow from the pins' velocities (`b θ̇2 = |Ḃ − Ȧ|`,
    /// `c θ̇3 = |Ḃ|`), so no angle but the crank's is needed. For the cost
    /// of a constraint against the elimination
    /// (`cargo bench -p lagrange-studies --bench constraints`), and
    /// checked against [`FourBar`] along a run.
    pub struct MinimalFourBar {
        coordinates: theta1;
        parameters: a, b, c, d, m1, m2, m3, j, g;
        let xa = a*cos(theta1);
        let ya = a*sin(theta1);
        let dx = d - xa;
        let dy = -ya;
        let e2 = dx^2 + dy^2;
        let e = sqrt(e2);
        let along = (b^2 - c^2 + e2)/(2*e);
        let half = sqrt(b^2 - along^2);
        let bx = xa + (along*dx + half*ya)/e;
        let by = ya + (along*dy + half*dx)/e;
        let x2 = (xa + bx)/2;
        let y2 = (ya + by)/2;
        kinetic: (j + m1*a^2/3)/2*dot(theta1)^2
            + m2/2*(dot(x2)^2 + dot(y2)^2)
            + m2/24*((dot(bx) - dot(xa))^2 + (dot(by) - dot(ya))^2)
            + m3/6*(dot(bx)^2 + dot(by)^2);
        potential: g*(m1*ya/2 + m2*y2 + m3*by/2);
    }
}

impl FourBar {
    /// A crank-rocker: crank 0.2 m, coupler 0.7 m, rocker 0.5 m, ground
    /// 0.6 m (Grashof: 0.2 + 0.7 ≤ 0.5 + 0.6, the crank shortest), steel-ish
    /// rods of 1 kg per metre, a 0.02 kg m² flywheel, under gravity.
    pub fn crank_rocker() -> Self {
        Self::new(0.2, 0.7, 0.5, 0.6, 0.2, 0.7, 0.5, 0.02, 9.81)
    }

    /// A parallelogram linkage (`a = c`, `b = d`): at `θ1 = 0` all four
    /// pins lie on the x axis, a change point where the loop constraints
    /// have rank one.
    pub fn parallelogram() -> Self {
        Self::new(0.3, 0.6, 0.3, 0.6, 0.3, 0.6, 0.3, 0.0, 9.81)
    }

    /// The same linkage in its one minimal coordinate, the crank angle, on
    /// the branch [`state`](Self::state) takes.
    pub fn minimal(&self) -> MinimalFourBar {
        let Self {
            a,
            b,
            c,
            d,
            m1,
            m2,
            m3,
            j,
            g,
            ..
        } = *self;
        MinimalFourBar::new(a, b, c, d, m1, m2, m3, j, g)
    }

    /// The consistent state at crank angle `θ1` and rate `θ̇1`, in the
    /// assembly with the coupler above the line from the crank pin to the
    /// rocker pivot (the open branch of a crank-rocker): the coupler's far
    /// end is where the circles of radius `b` about the crank pin and `c`
    /// about `(d, 0)` meet. `None` where they do not meet.
    pub fn state(&self, theta1: f64, theta1_dot: f64) -> Option<(Vector3<f64>, Vector3<f64>)> {
        let (a, b, c, d) = (self.a, self.b, self.c, self.d);
        let (pin_x, pin_y) = (a * theta1.cos(), a * theta1.sin());
        let (dx, dy) = (d - pin_x, -pin_y);
        let e = dx.hypot(dy);
        // Distance from the crank pin along the line to the rocker pivot
        // to the chord through the two intersections, and half the chord.
        let along = (b * b - c * c + e * e) / (2.0 * e);
        let half = (b * b - along * along).sqrt();
        if !half.is_finite() {
            return None;
        }
        let (ux, uy) = (dx / e, dy / e);
        let (bx, by) = (
            pin_x + along * ux - half * uy,
            pin_y + along * uy + half * ux,
        );
        let theta2 = (by - pin_y).atan2(bx - pin_x);
        let theta3 = by.atan2(bx - d);
        // Rates from G q̇ = 0 with θ̇1 given: a 2 × 2 solve for θ̇2, θ̇3.
        //   −b sin θ2 θ̇2 + c sin θ3 θ̇3 =  a sin θ1 θ̇1
        //    b cos θ2 θ̇2 − c cos θ3 θ̇3 = −a cos θ1 θ̇1
        let (s1, c1) = theta1.sin_cos();
        let (s2, c2) = theta2.sin_cos();
        let (s3, c3) = theta3.sin_cos();
        let det = b * c * (s2 * c3 - s3 * c2);
        let (r1, r2) = (a * s1 * theta1_dot, -a * c1 * theta1_dot);
        let theta2_dot = (-c * c3 * r1 - c * s3 * r2) / det;
        let theta3_dot = (-b * c2 * r1 - b * s2 * r2) / det;
        Some((
            Vector3::new(theta1, theta2, theta3),
            Vector3::new(theta1_dot, theta2_dot, theta3_dot),
        ))
    }
}
