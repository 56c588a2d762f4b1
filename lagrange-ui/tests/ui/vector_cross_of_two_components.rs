use lagrange::prelude::*;

lagrangian! {
    pub struct Planar {
        coordinates: x, y;
        parameters: m;
        let r = vector(x, y);
        let moment = cross(r, vector(0, 0, 1));
        kinetic: m/2*(dot(x)^2 + dot(y)^2);
        potential: moment[0];
    }
}

fn main() {
    let _ = Planar::<f64>::DOF;
}
