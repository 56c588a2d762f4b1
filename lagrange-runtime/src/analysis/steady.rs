//! Linearization about a steady motion, reduced to the states that matter:
//! [`linearize_steady_motion`]. Built for models with constraints on their
//! velocities (a disk rolling upright, a bicycle running straight), whose
//! reference motion is no equilibrium (the wheels turn) and whose
//! ignorable coordinates (position on the ground, heading, wheel angles)
//! drop out of the small motions.

use nalgebra::{Complex, DMatrix, DVector, RealField, SVector};

use super::{AnalysisError, Derivatives};
use crate::dynamics::acceleration;
use crate::model::Lagrangian;
use crate::model::constraints::{Holonomic, Visitor};
use crate::model::settings::ConstraintSettings;

/// The small motions about a steady motion in the states kept:
/// `δẏ = A δy`, `y` the kept coordinates and velocities, in the order
/// [`states`](Self::states) names them.
///
/// ```
/// use lagrange::models::RollingDisk;
/// use lagrange_runtime::analysis::linearize_steady_motion;
///
/// let (r, g) = (0.3, 9.81);
/// let disk = RollingDisk::new(1.0, r, g);
/// // Upright, rolling straight at 2 m/s (spin −v/r about the axis).
/// let (q, qdot) = disk.state(0.0, 0.0, 0.0, -2.0 / r);
/// let lin = linearize_steady_motion(&disk, 0.0, &q, &qdot, &["theta"], &["theta", "psi"])?;
/// assert_eq!(lin.states, ["theta", "dot(theta)", "dot(psi)"]);
/// // Stable above v² = g r / 3: no eigenvalue with a positive real part.
/// assert!(lin.eigenvalues().iter().all(|s| s.re < 1e-6));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyLinearization<S: RealField + Copy> {
    /// The kept states: a coordinate's name for its deviation, `dot(name)`
    /// for its velocity's.
    pub states: Vec<String>,
    /// `A`, `k × k` for `k` kept states.
    pub state_matrix: DMatrix<S>,
    /// How the derivatives were obtained.
    pub derivatives: Derivatives,
}

impl<S: RealField + Copy> SteadyLinearization<S> {
    /// The eigenvalues of `A`: growth rates and frequencies of the small
    /// motions (zero for a neutral direction kept, such as a heading rate
    /// that settles at another value).
    pub fn eigenvalues(&self) -> DVector<Complex<S>> {
        self.state_matrix.complex_eigenvalues()
    }
}

/// The linearization of `model` about the motion through `(t, q, q̇)`,
/// reduced to the coordinates `positions` and the velocities `velocities`
/// (by name, from [`Lagrangian::COORDINATES`]).
///
/// The motion must be steady in the kept states: each kept coordinate's
/// velocity and each kept velocity's acceleration zero to `√ε` relative
/// ([`AnalysisError::NotSteady`]); the others may move (a wheel turning,
/// the contact point running along the ground). The deviations are those
/// the constraints allow: `δq` tangent to the holonomic constraints and
/// `δq̇` keeping every constraint's velocity residual at zero to first
/// order, holonomic or on the velocities alike. `A` is the map from the
/// kept states to their rates on that space, `(P J B)(P B)⁺` for the full
/// linearization `J` along a basis `B` of it and the selection `P` of the
/// kept states; it exists where the kept states are independent there and
/// their rates do not depend on the states left out, and
/// [`AnalysisError::NotReducible`] says which fails otherwise (a heading
/// left out whose rate drives the lean, say).
///
/// The derivatives are central differences at two steps, extrapolated
/// ([`Derivatives::Extrapolated`], relative error `≈ ε^(4/5)`, some 1e-12
/// in the bicycle's state matrix): of the constrained acceleration along
/// each basis direction (`4 dim B` saddle solves), and of the constraints'
/// velocity residuals for the basis. Models with constraints on their
/// velocities are what this is for; it takes unconstrained and holonomic
/// models too.
pub fn linearize_steady_motion<L, S, const N: usize>(
    model: &L,
    t: S,
    q: &SVector<S, N>,
    qdot: &SVector<S, N>,
    positions: &[&str],
    velocities: &[&str],
) -> Result<SteadyLinearization<S>, AnalysisError<S, N>>
where
    L: Lagrangian<N, Scalar = S>,
    S: RealField + Copy,
{
    crate::model::ready(model).map_err(|e| AnalysisError::Model(e.into()))?;
    let index = |name: &str| {
        L::COORDINATES
            .iter()
            .position(|c| *c == name)
            .ok_or_else(|| AnalysisError::NotReducible {
                reason: format!(
                    "`{name}` is not a coordinate of the model (its coordinates: {})",
                    L::COORDINATES.join(", ")
                ),
            })
    };
    let mut kept = Vec::new();
    let mut states = Vec::new();
    for name in positions {
        kept.push(index(name)?);
        states.push(name.to_string());
    }
    for name in velocities {
        kept.push(N + index(name)?);
        states.push(format!("dot({name})"));
    }
    let qddot = acceleration(model, t, q, qdot)?;
    // Steady in the kept states: their rates vanish.
    let rate = |i: usize| if i < N { qdot[i] } else { qddot[i - N] };
    let scale = qdot.amax().max(qddot.amax()).max(S::one());
    let tolerance = S::default_epsilon().sqrt() * scale;
    if let Some((k, &i)) = kept
        .iter()
        .enumerate()
        .find(|&(_, &i)| rate(i).abs() > tolerance)
    {
        return Err(AnalysisError::NotSteady {
            t,
            q: *q,
            qdot: *qdot,
            state: states[k].clone(),
            rate: rate(i),
        });
    }
    let basis = match model.visit_constraints(Allowed { t, q, qdot }) {
        Some(basis) => basis,
        None => DMatrix::identity(2 * N, 2 * N),
    };
    // J B along each basis direction, by extrapolated central differences.
    let d = basis.ncols();
    let h = extrapolated_step(q.amax().max(qdot.amax()));
    let mut jb = DMatrix::zeros(2 * N, d);
    for k in 0..d {
        let dq = SVector::<S, N>::from_fn(|i, _| basis[(i, k)]);
        let dv = SVector::<S, N>::from_fn(|i, _| basis[(N + i, k)]);
        let rate = extrapolated(h, |s| {
            acceleration(model, t, &(q + dq * s), &(qdot + dv * s))
        })?;
        for i in 0..N {
            jb[(i, k)] = basis[(N + i, k)];
            jb[(N + i, k)] = rate[i];
        }
    }
    let y = DMatrix::from_fn(kept.len(), d, |r, c| basis[(kept[r], c)]);
    let w = DMatrix::from_fn(kept.len(), d, |r, c| jb[(kept[r], c)]);
    // Yᵀ = Q R (thin, Q orthonormal d × k): the singular values of Y are
    // those of the small square R, and Y⁺ = Q R⁻ᵀ where they are not zero.
    // (Not an SVD of the wide Y itself: nalgebra's returned a wrong
    // pseudo-inverse for the bicycle at one speed, residual 0.13 against
    // 1e-14 at speeds 1e-12 away; `tests/trajectories/bicycle.rs`.)
    let noise = S::default_epsilon().powf(nalgebra::convert(2.0 / 3.0));
    let factors = (kept.len() <= d).then(|| {
        let qr = y.transpose().qr();
        (qr.q(), qr.r())
    });
    let Some((q_thin, r)) = factors.filter(|(_, r)| {
        let singular = r.singular_values();
        singular.min() > noise.sqrt() * singular.max()
    }) else {
        return Err(AnalysisError::NotReducible {
            reason: format!(
                "the kept states ({}) are not independent on the motions the constraints allow",
                states.join(", ")
            ),
        });
    };
    // A = W Y⁺ = (W Q) R⁻ᵀ, so R Aᵀ = (W Q)ᵀ.
    let a = r
        .solve_upper_triangular(&(&w * &q_thin).transpose())
        .ok_or_else(|| AnalysisError::NotReducible {
            reason: "the kept states' selection has no pseudo-inverse".to_string(),
        })?
        .transpose();
    let residual = (&a * &y - &w).amax();
    let size = w.amax().max(S::one());
    let allowed: S = nalgebra::convert::<f64, S>(1e3) * noise * size;
    if residual > allowed {
        return Err(AnalysisError::NotReducible {
            reason: format!(
                "the rates of the kept states ({}) depend on states left out (off by {residual:?}, \
                 beyond {allowed:?}): keep those too",
                states.join(", ")
            ),
        });
    }
    Ok(SteadyLinearization {
        states,
        state_matrix: a,
        derivatives: Derivatives::Extrapolated,
    })
}

/// The reduced mass, damping and stiffness matrices of the small motions
/// about a steady motion in the kept coordinates:
/// `M δq̈ + C δq̇ + K δq = δτ`, `δτ` generalized forces on those
/// coordinates (the bicycle's lean and steer torques), in the order
/// [`coordinates`](Self::coordinates) names them. From
/// [`steady_motion_matrices`].
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyMatrices<S: RealField + Copy> {
    /// The kept coordinates.
    pub coordinates: Vec<String>,
    /// `M`, `k × k`, symmetric.
    pub mass: DMatrix<S>,
    /// `C`: damping and gyroscopic terms (the bicycle's `v C1`).
    pub damping: DMatrix<S>,
    /// `K` (the bicycle's `g K0 + v² K2`).
    pub stiffness: DMatrix<S>,
    /// The linearization they come from, in the coordinates and then
    /// their velocities: `A = [[0, I], [−M⁻¹K, −M⁻¹C]]`.
    pub linearization: SteadyLinearization<S>,
}

/// The reduced mass, damping and stiffness matrices of `model` about the
/// steady motion through `(t, q, q̇)`, in the coordinates `coordinates` (by
/// name): `M δq̈ + C δq̇ + K δq = δτ` for generalized forces `δτ` on them,
/// for any model, with rolling (velocity) constraints or holonomic ones or
/// none.
///
/// `M` is the inverse of the kept coordinates' compliance through the
/// constraints: a generalized force on the kept coordinates, applied
/// through the saddle-point system `[[M, Gᵀ], [G, 0]]` at `q` (every
/// constraint's row, rolling ones included, so a mass matrix singular off
/// the constraints is fine), accelerates them by `M⁻¹ δτ`; the coordinates
/// left out (a wheel, the position on the ground) move as the constraints
/// and their own freedom make them, not held. That is one `(N + C)` LU
/// solve, exact to rounding. `C` and `K` are then `−M` times the lower
/// blocks of [`linearize_steady_motion`]'s state matrix with the same
/// coordinates kept as positions and as velocities, and carry its error
/// (extrapolated differences, some 1e-12 relative for the bicycle) and its
/// refusals ([`AnalysisError::NotSteady`], [`AnalysisError::NotReducible`]).
/// A kept coordinate that no generalized force can move on its own (its
/// compliance singular) is [`AnalysisError::NotReducible`].
///
/// The Whipple bicycle's benchmark matrices at 5 m/s:
///
/// ```
/// use lagrange::models::WhippleBicycle;
/// use lagrange_runtime::analysis::steady_motion_matrices;
///
/// let bike = WhippleBicycle::benchmark();
/// let [m, c1, k0, k2] = bike.benchmark_matrices();
/// let (v, g) = (5.0, bike.g);
/// let (q, qdot) = bike.upright(0.0, v);
/// let ours = steady_motion_matrices(&bike, 0.0, &q, &qdot, &["phi", "delta"])?;
/// let close = |a: &lagrange_runtime::nalgebra::DMatrix<f64>, b: lagrange_runtime::nalgebra::Matrix2<f64>| {
///     a.iter().zip(b.iter()).all(|(x, y)| (x - y).abs() < 1e-10 * b.amax())
/// };
/// assert!(close(&ours.mass, m));
/// assert!(close(&ours.damping, c1 * v));
/// assert!(close(&ours.stiffness, k0 * g + k2 * (v * v)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn steady_motion_matrices<L, S, const N: usize>(
    model: &L,
    t: S,
    q: &SVector<S, N>,
    qdot: &SVector<S, N>,
    coordinates: &[&str],
) -> Result<SteadyMatrices<S>, AnalysisError<S, N>>
where
    L: Lagrangian<N, Scalar = S>,
    S: RealField + Copy,
{
    let linearization = linearize_steady_motion(model, t, q, qdot, coordinates, coordinates)?;
    let k = coordinates.len();
    let index: Vec<usize> = coordinates
        .iter()
        .map(|name| {
            L::COORDINATES
                .iter()
                .position(|c| c == name)
                .expect("linearize_steady_motion has checked the names")
        })
        .collect();
    let g = model
        .visit_constraints(Jacobian { t, q })
        .unwrap_or_else(|| DMatrix::zeros(0, N));
    let c = g.nrows();
    let mass = model.mass_matrix(t, q);
    let saddle = DMatrix::from_fn(N + c, N + c, |i, j| match (i < N, j < N) {
        (true, true) => mass[(i, j)],
        (true, false) => g[(j - N, i)],
        (false, true) => g[(i - N, j)],
        (false, false) => S::zero(),
    });
    let forces = DMatrix::from_fn(
        N + c,
        k,
        |i, j| {
            if i == index[j] { S::one() } else { S::zero() }
        },
    );
    let not_reducible = || AnalysisError::NotReducible {
        reason: format!(
            "no generalized force on the kept coordinates ({}) moves each of them on its own \
             through the constraints: their compliance is singular",
            coordinates.join(", ")
        ),
    };
    let response = saddle.lu().solve(&forces).ok_or_else(not_reducible)?;
    let compliance = DMatrix::from_fn(k, k, |i, j| response[(index[i], j)]);
    if !compliance.iter().all(|x| x.is_finite()) {
        return Err(not_reducible());
    }
    let reduced = compliance.try_inverse().ok_or_else(not_reducible)?;
    // Symmetric in exact arithmetic; its rounding made symmetric.
    let half: S = nalgebra::convert(0.5);
    let reduced = (&reduced + reduced.transpose()) * half;
    let a = &linearization.state_matrix;
    let stiffness = -(&reduced * a.view((k, 0), (k, k)));
    let damping = -(&reduced * a.view((k, k), (k, k)));
    Ok(SteadyMatrices {
        coordinates: coordinates.iter().map(|c| c.to_string()).collect(),
        mass: reduced,
        damping,
        stiffness,
        linearization,
    })
}

/// `G = ∂φ/∂q` of every constraint (rolling rows included), `C × N`.
struct Jacobian<'a, S, const N: usize> {
    t: S,
    q: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Jacobian<'_, S, N> {
    type Output = DMatrix<S>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> DMatrix<S>
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let g = model.constraint_jacobian(self.t, self.q);
        DMatrix::from_fn(C, N, |i, j| g[(i, j)])
    }
}

/// A basis (`2N × D`) of the deviations `(δq, δq̇)` the constraints allow:
/// the null space of the rows `[G_i, 0]` of the holonomic constraints and
/// `[∂φ̇_i/∂q, G_i]` of every constraint (`φ̇_i` the velocity residual, of a
/// velocity constraint too).
struct Allowed<'a, S, const N: usize> {
    t: S,
    q: &'a SVector<S, N>,
    qdot: &'a SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Allowed<'_, S, N> {
    type Output = DMatrix<S>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> DMatrix<S>
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let (t, q, qdot) = (self.t, self.q, self.qdot);
        let g = model.constraint_jacobian(t, q);
        let on_velocities = model.velocity_constraint_rows();
        let holonomic: Vec<usize> = (0..C).filter(|&i| !on_velocities[i]).collect();
        let rows = holonomic.len() + C;
        let mut k = DMatrix::zeros(rows, 2 * N);
        for (r, &i) in holonomic.iter().enumerate() {
            for j in 0..N {
                k[(r, j)] = g[(i, j)];
            }
        }
        let h = extrapolated_step(q.amax());
        for j in 0..N {
            let mut direction = SVector::<S, N>::zeros();
            direction[j] = S::one();
            let derivative = extrapolated(h, |s| {
                Ok::<_, ()>(model.constraint_velocities(t, &(q + direction * s), qdot))
            })
            .unwrap_or_else(|()| unreachable!("the closure cannot fail"));
            for i in 0..C {
                k[(holonomic.len() + i, j)] = derivative[i];
                k[(holonomic.len() + i, N + j)] = g[(i, j)];
            }
        }
        null_space(&k)
    }
}

/// An orthonormal basis of the null space of `k` (`r × n`, full row rank:
/// the saddle solve at the state has checked `G`), from one Householder QR
/// of `[kᵀ | I]`, as the tangent basis of
/// [`linearize_on_manifold`](super::linearize_on_manifold) is built.
fn null_space<S: RealField + Copy>(k: &DMatrix<S>) -> DMatrix<S> {
    let (r, n) = k.shape();
    let wide = DMatrix::from_fn(n, r + n, |i, j| {
        if j < r {
            k[(j, i)]
        } else if i == j - r {
            S::one()
        } else {
            S::zero()
        }
    });
    let q = wide.qr().q();
    q.columns(r, n - r).into_owned()
}

/// The step of [`extrapolated`] for arguments of size `x`: `ε^(1/5)`, where
/// its truncation error (`h⁴`) and its rounding (`ε/h`) balance.
fn extrapolated_step<S: RealField + Copy>(x: S) -> S {
    let fifth: S = nalgebra::convert(0.2);
    S::default_epsilon().powf(fifth) * S::one().max(x.abs())
}

/// The derivative at `s = 0` of `f(s)`, from central differences at steps
/// `h` and `h/2` combined so that their `h²` errors cancel (Richardson):
/// `(4 D(h/2) − D(h)) / 3`, relative error about `ε^(4/5)` (3e-13 in `f64`)
/// against central differences' `ε^(2/3)` (4e-11), for four evaluations
/// instead of two.
fn extrapolated<S, V, E>(h: S, mut f: impl FnMut(S) -> Result<V, E>) -> Result<V, E>
where
    S: RealField + Copy,
    V: std::ops::Sub<Output = V> + std::ops::Mul<S, Output = V>,
{
    let two: S = nalgebra::convert(2.0);
    let whole = (f(h)? - f(-h)?) * (S::one() / (two * h));
    let half = (f(h / two)? - f(-h / two)?) * (S::one() / h);
    let four: S = nalgebra::convert(4.0);
    let third: S = nalgebra::convert(1.0 / 3.0);
    Ok((half * four - whole) * third)
}
