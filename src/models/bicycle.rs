//! The Whipple bicycle: four rigid bodies (rear wheel, rear frame with its
//! rider, front frame, front wheel), both wheels rolling without slipping
//! on level ground, written in the language as the full nonlinear model;
//! and the benchmark's linearized lean–steer equations in closed form
//! (Meijaard, Papadopoulos, Ruina and Schwab 2007, Proc. R. Soc. A 463,
//! appendix A), against which it is checked.

use lagrange_runtime::analysis::{AnalysisError, steady_motion_matrices};
use nalgebra::{Matrix2, Matrix4};

use crate::lagrangian;

lagrangian! {
    /// The Whipple bicycle in the benchmark's axes and parameters: `x`
    /// forward, `y` to the right, `z` down, gravity `g` along `+z`; lengths
    /// from the rear contact point in the upright reference configuration.
    ///
    /// Coordinates: the rear contact point `(x, y)`, the rear frame's yaw
    /// `psi`, roll (the lean, to the right) `phi` and pitch `theta`, the
    /// steer angle `delta` about the steer axis (tilted back by `lambda`
    /// from the vertical; to the right), and the wheels' rotations `thR`,
    /// `thF` about their axles. One holonomic constraint (the front wheel
    /// touches the ground, which fixes the pitch) and four on the
    /// velocities (neither contact point slips) leave three degrees of
    /// freedom: lean, steer and forward speed.
    ///
    /// Each body's kinetic energy is `½ m |ṙ|² + ½ ωᵀ I ω`, its inertia `I`
    /// given in the body's axes (the wheels' symmetric about their axles,
    /// `I_xx = I_zz`); the bodies' axes are the rear frame's turned by the
    /// yaw, roll and pitch, and for the front the steer.
    pub struct WhippleBicycle {
        coordinates: x, y, psi, phi, theta, delta, thR, thF;
        // The wheelbase, the wheels' radii, every mass and every principal
        // moment positive; the trail, the steer axis's tilt, the positions
        // and the products of inertia of either sign.
        parameters: w > 0, c, lambda, g >= 0,
            rR > 0, mR > 0, IRxx > 0, IRyy > 0,
            xB, zB, mB > 0, IBxx > 0, IByy > 0, IBzz > 0, IBxz,
            xH, zH, mH > 0, IHxx > 0, IHyy > 0, IHzz > 0, IHxz,
            rF > 0, mF > 0, IFxx > 0, IFyy > 0;

        // The rear frame's axes in space: yaw about the vertical, roll about
        // the heading, pitch about the rear axle.
        let bx = rotate_z(psi, rotate_x(phi, rotate_y(theta, vector(1, 0, 0))));
        let by = rotate_z(psi, rotate_x(phi, vector(0, 1, 0)));
        let bz = rotate_z(psi, rotate_x(phi, rotate_y(theta, vector(0, 0, 1))));
        // The front frame's axes: the rear frame's turned by the steer
        // about the steer axis, `Ry(λ) Rz(δ) Ry(−λ)` in the rear frame.
        let hx = rotate_z(psi, rotate_x(phi, rotate_y(theta + lambda, rotate_z(delta, rotate_y(-lambda, vector(1, 0, 0))))));
        let hy = rotate_z(psi, rotate_x(phi, rotate_y(theta + lambda, rotate_z(delta, vector(0, 1, 0)))));
        let hz = rotate_z(psi, rotate_x(phi, rotate_y(theta + lambda, rotate_z(delta, rotate_y(-lambda, vector(0, 0, 1))))));
        let steer_axis = sin(lambda)*bx + cos(lambda)*bz;

        // Angular velocities in space.
        let wB = dot(psi)*vector(0, 0, 1) + dot(phi)*rotate_z(psi, vector(1, 0, 0)) + dot(theta)*by;
        let wH = wB + dot(delta)*steer_axis;
        let wR = wB + dot(thR)*by;
        let wF = wH + dot(thF)*hy;

        // Points: the rear wheel's centre, straight above its contact point
        // in the wheel's plane; the rear frame's mass centre; the steer axis
        // where it meets the ground in the reference configuration (a point
        // of both frames); the front frame's mass centre and the front
        // wheel's centre.
        let lean_down = rotate_z(psi, rotate_x(phi, vector(0, 0, 1)));
        let rear_centre = vector(x, y, 0) - rR*lean_down;
        let rear_mass = rear_centre + (xB*bx + (zB + rR)*bz);
        let steer_point = rear_centre + ((w + c)*bx + rR*bz);
        let front_mass = steer_point + ((xH - w - c)*hx + zH*hz);
        let front_centre = steer_point - (c*hx + rF*hz);
        // The front contact point: from the centre, rF along the steepest
        // downward direction in the wheel's plane.
        let front_down = (vector(0, 0, 1) - hy[2]*hy)/sqrt(1 - hy[2]^2);

        kinetic: mR/2*inner(dot(rear_centre), dot(rear_centre))
            + (IRxx*inner(wR, wR) + (IRyy - IRxx)*inner(wR, by)^2)/2;
        kinetic: mB/2*inner(dot(rear_mass), dot(rear_mass))
            + (IBxx*inner(wB, bx)^2 + IByy*inner(wB, by)^2 + IBzz*inner(wB, bz)^2
               + 2*IBxz*inner(wB, bx)*inner(wB, bz))/2;
        kinetic: mH/2*inner(dot(front_mass), dot(front_mass))
            + (IHxx*inner(wH, hx)^2 + IHyy*inner(wH, hy)^2 + IHzz*inner(wH, hz)^2
               + 2*IHxz*inner(wH, hx)*inner(wH, hz))/2;
        kinetic: mF/2*inner(dot(front_centre), dot(front_centre))
            + (IFxx*inner(wF, wF) + (IFyy - IFxx)*inner(wF, hy)^2)/2;
        potential: -g*(mR*rear_centre[2] + mB*rear_mass[2] + mH*front_mass[2] + mF*front_centre[2]);

        // The velocity of each wheel's material point at its contact.
        let rear_slip = dot(rear_centre) + rR*cross(wR, lean_down);
        let front_slip = dot(front_centre) + rF*cross(wF, front_down);
        constraints:
            ground: front_centre[2] + rF*sqrt(1 - hy[2]^2) = 0,
            rear_forward: rear_slip[0] = 0,
            rear_sideways: rear_slip[1] = 0,
            front_forward: front_slip[0] = 0,
            front_sideways: front_slip[1] = 0;
    }
}

impl WhippleBicycle<f64> {
    /// The benchmark bicycle of Meijaard et al. (2007), table 1.
    pub fn benchmark() -> Self {
        Self::from_parameters(WhippleBicycleParameters {
            w: 1.02,
            c: 0.08,
            lambda: std::f64::consts::PI / 10.0,
            g: 9.81,
            rR: 0.3,
            mR: 2.0,
            IRxx: 0.0603,
            IRyy: 0.12,
            xB: 0.3,
            zB: -0.9,
            mB: 85.0,
            IBxx: 9.2,
            IByy: 11.0,
            IBzz: 2.8,
            IBxz: 2.4,
            xH: 0.9,
            zH: -0.7,
            mH: 4.0,
            IHxx: 0.05892,
            IHyy: 0.06,
            IHzz: 0.00708,
            IHxz: -0.00756,
            rF: 0.35,
            mF: 3.0,
            IFxx: 0.1405,
            IFyy: 0.28,
        })
        .expect("the benchmark's parameters lie inside the model's domains")
    }

    /// The state of upright straight running at speed `v`: every angle
    /// zero, the rear contact point at `x0`, the wheels turning at
    /// `−v/rR` and `−v/rF` (positive about their axles, which point to the
    /// right).
    pub fn upright(
        &self,
        x0: f64,
        v: f64,
    ) -> (nalgebra::SVector<f64, 8>, nalgebra::SVector<f64, 8>) {
        let q = nalgebra::SVector::<f64, 8>::from_column_slice(&[
            x0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        ]);
        let qdot = nalgebra::SVector::<f64, 8>::from_column_slice(&[
            v,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            -v / self.rR,
            -v / self.rF,
        ]);
        (q, qdot)
    }

    /// The benchmark's state matrix for `(φ, δ, φ̇, δ̇)` at speed `v`, from
    /// [`benchmark_matrices`](Self::benchmark_matrices):
    /// `[[0, I], [−M⁻¹(g K0 + v² K2), −v M⁻¹ C1]]`.
    pub fn benchmark_state_matrix(&self, v: f64) -> Matrix4<f64> {
        let [m, c1, k0, k2] = self.benchmark_matrices();
        let minv = m.try_inverse().expect("the benchmark's M is regular");
        let mut a = Matrix4::zeros();
        a.fixed_view_mut::<2, 2>(0, 2)
            .copy_from(&Matrix2::identity());
        a.fixed_view_mut::<2, 2>(2, 0)
            .copy_from(&(-minv * (self.g * k0 + v * v * k2)));
        a.fixed_view_mut::<2, 2>(2, 2)
            .copy_from(&(-minv * (v * c1)));
        a
    }

    /// This model's mass matrix for lean and steer at the upright, from its
    /// own kinetic energy through its constraints: the benchmark's `M`, by
    /// [`steady_motion_matrices`](lagrange_runtime::analysis::steady_motion_matrices)
    /// at rest.
    pub fn lean_steer_mass_matrix(&self) -> Result<Matrix2<f64>, Box<AnalysisError<f64, 8>>> {
        Ok(self.lean_steer_matrices(0.0)?[0])
    }

    /// This model's own `M`, `C1`, `K0` and `K2` for lean and steer, the
    /// benchmark's form of its linearization, from
    /// [`steady_motion_matrices`](lagrange_runtime::analysis::steady_motion_matrices)
    /// at rest (`M`, `g K0`) and at speed `v > 0` (`v C1`, `g K0 + v² K2`);
    /// at `v = 0`, `C1` and `K2` are zero (they are not determined there).
    /// The error is boxed: unboxed, with the bicycle's states in it, it is
    /// 176 bytes, beyond Clippy's `result_large_err`.
    pub fn lean_steer_matrices(
        &self,
        v: f64,
    ) -> Result<[Matrix2<f64>; 4], Box<AnalysisError<f64, 8>>> {
        let two = |a: &nalgebra::DMatrix<f64>| Matrix2::from_iterator(a.iter().copied());
        let at = |v: f64| {
            let (q, qdot) = self.upright(0.0, v);
            steady_motion_matrices(self, 0.0, &q, &qdot, &["phi", "delta"]).map_err(Box::new)
        };
        let rest = at(0.0)?;
        let (m, k0) = (two(&rest.mass), two(&rest.stiffness) / self.g);
        if v == 0.0 {
            return Ok([m, Matrix2::zeros(), k0, Matrix2::zeros()]);
        }
        let moving = at(v)?;
        let c1 = two(&moving.damping) / v;
        let k2 = (two(&moving.stiffness) - two(&rest.stiffness)) / (v * v);
        Ok([m, c1, k0, k2])
    }

    /// The benchmark's linearized lean–steer equations about upright
    /// straight running at speed `v`,
    /// `M q̈ + v C1 q̇ + (g K0 + v² K2) q = 0` for `q = (φ, δ)`, in closed
    /// form from the parameters (Meijaard et al. 2007, appendix A):
    /// `[M, C1, K0, K2]`.
    pub fn benchmark_matrices(&self) -> [Matrix2<f64>; 4] {
        let (w, c, lambda) = (self.w, self.c, self.lambda);
        let (r_r, m_r, i_rxx, i_ryy) = (self.rR, self.mR, self.IRxx, self.IRyy);
        let (x_b, z_b, m_b) = (self.xB, self.zB, self.mB);
        let (i_bxx, i_bzz, i_bxz) = (self.IBxx, self.IBzz, self.IBxz);
        let (x_h, z_h, m_h) = (self.xH, self.zH, self.mH);
        let (i_hxx, i_hzz, i_hxz) = (self.IHxx, self.IHzz, self.IHxz);
        let (r_f, m_f, i_fxx, i_fyy) = (self.rF, self.mF, self.IFxx, self.IFyy);
        let (sl, cl) = lambda.sin_cos();
        // The whole bicycle: mass, mass centre, inertia about the rear
        // contact point (wheels symmetric: I_zz = I_xx).
        let m_t = m_r + m_b + m_h + m_f;
        let x_t = (x_b * m_b + x_h * m_h + w * m_f) / m_t;
        let z_t = (-r_r * m_r + z_b * m_b + z_h * m_h - r_f * m_f) / m_t;
        let i_txx = i_rxx
            + i_bxx
            + i_hxx
            + i_fxx
            + m_r * r_r * r_r
            + m_b * z_b * z_b
            + m_h * z_h * z_h
            + m_f * r_f * r_f;
        let i_txz = i_bxz + i_hxz - m_b * x_b * z_b - m_h * x_h * z_h + m_f * w * r_f;
        let i_tzz = i_rxx + i_bzz + i_hzz + i_fxx + m_b * x_b * x_b + m_h * x_h * x_h + m_f * w * w;
        // The front assembly (front frame and wheel): mass, mass centre,
        // inertia about its mass centre, and about the steer axis.
        let m_a = m_h + m_f;
        let x_a = (x_h * m_h + w * m_f) / m_a;
        let z_a = (z_h * m_h - r_f * m_f) / m_a;
        let i_axx = i_hxx + i_fxx + m_h * (z_h - z_a).powi(2) + m_f * (r_f + z_a).powi(2);
        let i_axz = i_hxz - m_h * (x_h - x_a) * (z_h - z_a) + m_f * (w - x_a) * (r_f + z_a);
        let i_azz = i_hzz + i_fxx + m_h * (x_h - x_a).powi(2) + m_f * (w - x_a).powi(2);
        // The perpendicular distance of the front assembly's mass centre
        // ahead of the steer axis, and its inertias about the axis.
        let u_a = (x_a - w - c) * cl - z_a * sl;
        let i_all = m_a * u_a * u_a + i_axx * sl * sl + 2.0 * i_axz * sl * cl + i_azz * cl * cl;
        let i_alx = -m_a * u_a * z_a + i_axx * sl + i_axz * cl;
        let i_alz = m_a * u_a * x_a + i_axz * sl + i_azz * cl;
        // The steer axis' trail ratio, and the wheels' gyroscopic
        // coefficients.
        let mu = c / w * cl;
        let s_r = i_ryy / r_r;
        let s_f = i_fyy / r_f;
        let s_t = s_r + s_f;
        let s_a = m_a * u_a + mu * m_t * x_t;
        let m = Matrix2::new(
            i_txx,
            i_alx + mu * i_txz,
            i_alx + mu * i_txz,
            i_all + 2.0 * mu * i_alz + mu * mu * i_tzz,
        );
        let k0 = Matrix2::new(m_t * z_t, -s_a, -s_a, -s_a * sl);
        let k2 = Matrix2::new(
            0.0,
            (s_t - m_t * z_t) / w * cl,
            0.0,
            (s_a + s_f * sl) / w * cl,
        );
        let c1 = Matrix2::new(
            0.0,
            mu * s_t + s_f * cl + i_txz / w * cl - mu * m_t * z_t,
            -(mu * s_t + s_f * cl),
            i_alz / w * cl + mu * (s_a + i_tzz / w * cl),
        );
        [m, c1, k0, k2]
    }
}
