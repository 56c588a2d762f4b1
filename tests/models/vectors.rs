//! The vector notation (`docs/language.md`, "Vectors and rotations"): each
//! function against nalgebra's rotations, and rigid bodies written with
//! vectors against the same bodies written out by components
//! (`lagrange::models`).

use lagrange::models::{FreeBody, HeavyTop, quaternion};
use lagrange::nalgebra::{Rotation3, SVector, UnitQuaternion, Vector1, Vector3, Vector4};
use lagrange::prelude::*;
use rand::{Rng, SeedableRng};

lagrangian! {
    /// Every vector function at once, of three angles and a quaternion;
    /// the `let`s are what the tests compare.
    pub struct Kinematics {
        coordinates: a, b, c, q[4];
        parameters: m;
        let v = vector(1, -2, 3);
        let turned_x = rotate_x(a, v);
        let turned_y = rotate_y(b, v);
        let turned_z = rotate_z(c, v);
        let turned = rotate(q, v);
        let w_body = body_rates(q);
        let w_space = space_rates(q);
        let product = turned_x.cross(turned_y);
        let scalar = inner(turned_x, turned_y);
        let length = norm(turned);
        let combined = turned_x + 2*turned_y - turned_z/4 - -v;
        let velocity = dot(turned_x);
        let moments = sum(i in 0..3, (i + 1)*rotate_z(i*c, v));
        kinetic: m/2*(dot(a)^2 + dot(b)^2 + dot(c)^2 + inner(dot(q), dot(q)));
        potential: 0;
    }
}

/// The `let` named `name` of `Kinematics` at a state, a vector of `D`.
fn lets<const D: usize>(
    q: &SVector<f64, 7>,
    qdot: &SVector<f64, 7>,
    name: &str,
) -> SVector<f64, D> {
    let values = Kinematics::new(1.0).lets(0.0, q, qdot);
    let names = Kinematics::<f64>::LETS;
    SVector::from_fn(|i, _| {
        let element = if D == 1 {
            name.to_string()
        } else {
            format!("{name}[{i}]")
        };
        let k = names
            .iter()
            .position(|n| *n == element)
            .unwrap_or_else(|| panic!("no `let` {element}"));
        values[k]
    })
}

/// A random state: three angles, a unit quaternion, rates of order one.
fn random_state(rng: &mut impl Rng) -> (SVector<f64, 7>, SVector<f64, 7>) {
    let mut q = SVector::<f64, 7>::from_fn(|_, _| rng.gen_range(-2.0..2.0));
    let norm = q.fixed_rows::<4>(3).norm();
    q.fixed_rows_mut::<4>(3).unscale_mut(norm);
    let qdot = SVector::<f64, 7>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
    (q, qdot)
}

/// Each vector function against nalgebra at random states. The values are
/// of order 10 (|v| ≈ 3.7, rates of order 1): 1e-13 is a few roundings.
#[test]
fn every_vector_function_matches_nalgebra() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let v = Vector3::new(1.0, -2.0, 3.0);
    for _ in 0..20 {
        let (q, qdot) = random_state(&mut rng);
        let (a, b, c) = (q[0], q[1], q[2]);
        let quat = Vector4::new(q[3], q[4], q[5], q[6]);
        let quat_dot = Vector4::new(qdot[3], qdot[4], qdot[5], qdot[6]);
        let rx = Rotation3::from_axis_angle(&Vector3::x_axis(), a) * v;
        let ry = Rotation3::from_axis_angle(&Vector3::y_axis(), b) * v;
        let rz = Rotation3::from_axis_angle(&Vector3::z_axis(), c) * v;
        let r = quaternion::rotation(&quat);
        let w_body = quaternion::body_rates(&quat, &quat_dot);
        // d/dt (Rx(a) v) = ȧ x̂ × (Rx(a) v).
        let velocity = qdot[0] * Vector3::x().cross(&rx);
        let moments = (0..3)
            .map(|i| {
                (i + 1) as f64 * (Rotation3::from_axis_angle(&Vector3::z_axis(), i as f64 * c) * v)
            })
            .sum::<Vector3<f64>>();
        let expected: [(&str, Vector3<f64>); 9] = [
            ("turned_x", rx),
            ("turned_y", ry),
            ("turned_z", rz),
            ("turned", r * v),
            ("w_body", w_body),
            ("w_space", r * w_body),
            ("product", rx.cross(&ry)),
            ("combined", rx + 2.0 * ry - rz / 4.0 + v),
            ("velocity", velocity),
        ];
        for (name, want) in expected {
            let got = lets::<3>(&q, &qdot, name);
            assert!((got - want).norm() < 1e-13, "{name}: {got} against {want}");
        }
        assert!((lets::<3>(&q, &qdot, "moments") - moments).norm() < 1e-13);
        assert!((lets::<1>(&q, &qdot, "scalar")[0] - rx.dot(&ry)).abs() < 1e-13);
        assert!((lets::<1>(&q, &qdot, "length")[0] - v.norm()).abs() < 1e-13);
    }
    assert_eq!(&Kinematics::<f64>::LETS[..3], &["v[0]", "v[1]", "v[2]"]);
}

lagrangian! {
    /// `lagrange::models::FreeBody`, written with vectors.
    pub struct VectorBody {
        coordinates: q[4];
        parameters: i1, i2, i3;
        let omega = body_rates(q);
        kinetic: (i1*omega[0]^2 + i2*omega[1]^2 + i3*omega[2]^2)/2;
        potential: 0;
        constraints: unit: inner(q, q) = 1;
    }
}

lagrangian! {
    /// `lagrange::models::HeavyTop`, written with vectors: the height of
    /// the mass centre is that of the rotated axis.
    pub struct VectorTop {
        coordinates: q[4];
        parameters: a, c, m, g, l;
        let omega = body_rates(q);
        let centre = rotate(q, vector(0, 0, l));
        kinetic: (a*(omega[0]^2 + omega[1]^2) + c*omega[2]^2)/2;
        potential: m*g*centre[2];
        constraints: unit: inner(q, q) = 1;
    }
}

/// The same kinetic energy written with vectors gives the same `M` and
/// `f` as written out, to rounding (entries of order 10 at these rates).
/// The top's potential differs off the unit sphere (`l (1 − 2x² − 2y²)`
/// against `l (w² − x² − y² + z²)`), so its `f` may differ there along the
/// constraint's normal `q` only, which the multiplier absorbs: the part of
/// the difference tangent to the sphere is rounding.
#[test]
fn rigid_bodies_written_with_vectors_equal_the_written_out_ones() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    let (body, written_body) = (VectorBody::new(1.0, 2.0, 3.0), FreeBody::new(1.0, 2.0, 3.0));
    let (top, written_top) = (
        VectorTop::new(1.0, 0.5, 2.0, 9.81, 0.3),
        HeavyTop::new(1.0, 0.5, 2.0, 9.81, 0.3),
    );
    for _ in 0..20 {
        let rotation = UnitQuaternion::from_euler_angles(
            rng.gen_range(-3.0..3.0),
            rng.gen_range(-1.5..1.5),
            rng.gen_range(-3.0..3.0),
        );
        let omega = Vector3::from_fn(|_, _| rng.gen_range(-3.0..3.0));
        let (q, qdot) = quaternion::state(&rotation, &omega);
        let scale = 1.0 + omega.norm_squared();
        let m = (body.mass_matrix(0.0, &q) - written_body.mass_matrix(0.0, &q)).norm();
        let f = (body.forcing(0.0, &q, &qdot) - written_body.forcing(0.0, &q, &qdot)).norm();
        assert!(
            m < 1e-13 && f < 1e-13 * scale,
            "free body: |ΔM| = {m:e}, |Δf| = {f:e}"
        );
        let m = (top.mass_matrix(0.0, &q) - written_top.mass_matrix(0.0, &q)).norm();
        let df = top.forcing(0.0, &q, &qdot) - written_top.forcing(0.0, &q, &qdot);
        let tangent = df - q * q.dot(&df);
        assert!(
            m < 1e-13 && tangent.norm() < 1e-13 * scale,
            "top: |ΔM| = {m:e}, tangent |Δf| = {:e}",
            tangent.norm()
        );
    }
}

lagrangian! {
    /// An arm of length l turning about z, pushed at its tip by a force F
    /// along y in space: the generalized force is F l cos θ.
    pub struct PushedArm {
        coordinates: theta;
        parameters: m, l, F;
        let tip = rotate_z(theta, vector(l, 0, 0));
        kinetic: m/2*inner(dot(tip), dot(tip));
        potential: 0;
        forces: tip = vector(0, F, 0);
    }
}

/// A force along a vector position is its virtual work, `Fᵀ ∂r/∂q`.
#[test]
fn a_force_along_a_vector_does_its_virtual_work() {
    let arm = PushedArm::new(2.0, 0.5, 3.0);
    for theta in [0.0f64, 0.3, 1.2, 2.5] {
        let q = Vector1::new(theta);
        assert!((arm.mass_matrix(0.0, &q)[0] - 2.0 * 0.25f64).abs() < 1e-15);
        let f = arm.forcing(0.0, &q, &Vector1::new(0.7))[0];
        assert!(
            (f - 3.0 * 0.5 * theta.cos()).abs() < 1e-15,
            "θ = {theta}: f = {f}"
        );
    }
}
