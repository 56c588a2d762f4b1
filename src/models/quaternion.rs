//! The state of a rigid body whose orientation is a unit quaternion
//! `q = (w, x, y, z)` (body to space), as [`FreeBody`](super::FreeBody) and
//! [`HeavyTop`](super::HeavyTop) hold it: from a rotation and body rates,
//! and back.

use nalgebra::{Quaternion, UnitQuaternion, Vector3, Vector4};

/// The state `(q, q̇)` at orientation `rotation` turning at body rates
/// `omega`: `q̇ = ½ q (0, ω)`.
pub fn state(rotation: &UnitQuaternion<f64>, omega: &Vector3<f64>) -> (Vector4<f64>, Vector4<f64>) {
    let q = rotation.quaternion();
    let qdot = q * Quaternion::from_imag(*omega) * 0.5;
    (
        Vector4::new(q.w, q.i, q.j, q.k),
        Vector4::new(qdot.w, qdot.i, qdot.j, qdot.k),
    )
}

/// The rotation (body to space) of a state's quaternion, normalized.
pub fn rotation(q: &Vector4<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]))
}

/// The body rates `ω = 2 Im(q̄ q̇)`.
pub fn body_rates(q: &Vector4<f64>, qdot: &Vector4<f64>) -> Vector3<f64> {
    let q = Quaternion::new(q[0], q[1], q[2], q[3]);
    let qdot = Quaternion::new(qdot[0], qdot[1], qdot[2], qdot[3]);
    (q.conjugate() * qdot).imag() * 2.0
}
