//! A bob whirled on a string too slowly: the string goes slack, the bob
//! flies, and the string snaps taut again.

use crate::lagrangian;

lagrangian! {
    /// A bob of mass `m` on a string of length `l` tied at the origin, in
    /// Cartesian coordinates `(x, y)`, `y` up, under gravity `g`. The
    /// string pulls but cannot push: the gap `l − √(x² + y²) ≥ 0`, whose
    /// force is the tension; it snaps taut plastically (an inextensible
    /// string).
    pub struct BobOnString {
        coordinates: x, y;
        parameters: m, g, l;
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: m*g*y;
        contacts: string: sqrt(x^2 + y^2) <= l;
    }
}

impl BobOnString<f64> {
    /// At the bottom, moving at `v0` to the right.
    pub fn whirled(&self, v0: f64) -> ([f64; 2], [f64; 2]) {
        ([0.0, -self.l], [v0, 0.0])
    }

    /// The angle from the bottom where the string goes slack, for `2 g l <
    /// v₀² < 5 g l`: the tension `m (v²/l + g cos φ)` vanishes with `v² =
    /// v₀² − 2 g l (1 − cos φ)`, at `cos φ = (2 g l − v₀²) / (3 g l)`.
    pub fn slack_angle(&self, v0: f64) -> f64 {
        let gl = self.g * self.l;
        ((2.0 * gl - v0 * v0) / (3.0 * gl)).acos()
    }
}
