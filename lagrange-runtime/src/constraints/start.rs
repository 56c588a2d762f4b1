//! A consistent start for a constrained or rolling model, built from the
//! coordinates and velocities a user knows: [`consistent_start`], and for
//! a body in a unit quaternion, [`state_from_body_rates`].

use nalgebra::{DMatrix, DVector, Quaternion, RealField, SVector, UnitQuaternion, Vector3};

use crate::dynamics::projection::{position_tolerance, velocity_tolerance};
use crate::model::Lagrangian;
use crate::model::constraints::{Holonomic, Visitor};
use crate::model::settings::ConstraintSettings;

/// Gauss–Newton iterations before [`StartError::NotConverged`]: it
/// converges quadratically from a guess near the constraints, in two or
/// three.
const MAX_ITERATIONS: usize = 32;

/// Why [`consistent_start`] or [`state_from_body_rates`] built no start.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StartError<S: RealField + Copy, const N: usize> {
    /// A name given is not one of the model's coordinates.
    #[error("`{name}` is not a coordinate of the model (its coordinates: {coordinates})")]
    UnknownCoordinate {
        /// The name given.
        name: String,
        /// The model's coordinates, joined.
        coordinates: String,
    },

    /// The guess or the given values are not all finite.
    #[error("the start has a NaN or infinite value: q = {q:?}, q̇ = {qdot:?}")]
    NonFinite {
        /// Positions.
        q: SVector<S, N>,
        /// Velocities.
        qdot: SVector<S, N>,
    },

    /// Gauss–Newton on the coordinates not held did not bring every
    /// holonomic constraint to rounding level: the held coordinates leave
    /// it no solution near the guess (a quaternion held that is not of
    /// unit norm), or the guess is too far. `q` is the last iterate.
    #[error(
        "the positions could not be projected onto the constraints: after {iterations} \
         Gauss–Newton iterations constraint `{constraint}` is {residual:?} at q = {q:?}"
    )]
    NotConverged {
        /// The last iterate.
        q: SVector<S, N>,
        /// The constraint furthest off, by name.
        constraint: &'static str,
        /// Its value there.
        residual: S,
        /// Iterations done.
        iterations: usize,
    },

    /// The velocity of a coordinate not given is not fixed by the
    /// constraints: give it (or another coordinate it moves with).
    #[error(
        "the velocity of `{coordinate}` is not determined by the constraints and the velocities \
         given: give it"
    )]
    Undetermined {
        /// The coordinate, by name.
        coordinate: &'static str,
    },

    /// The velocities given contradict a constraint: no choice of the
    /// others makes its velocity residual zero.
    #[error(
        "the velocities given contradict constraint `{constraint}`: its velocity residual is \
         {residual:?} at best"
    )]
    Inconsistent {
        /// The constraint, by name.
        constraint: &'static str,
        /// Its velocity residual after the solve.
        residual: S,
    },
}

/// A start on the constraints: `q` moved onto every holonomic constraint
/// with the coordinates named in `held` kept, and `q̇` completed with the
/// velocities named in `given` kept, so that every constraint's velocity
/// residual (holonomic `φ̇ = G q̇ + ∂φ/∂t` and rolling rows alike) is zero
/// to rounding.
///
/// The positions: Gauss–Newton on the coordinates not held, each step the
/// least-squares, least-norm solution of `G_u Δu = −φ` over the holonomic
/// rows, until every `|φ_i|` is within the rounding an integrator accepts
/// as consistent (`100 ε ‖G_i‖₁ ‖q‖∞`). The velocities: the rows of every
/// constraint are linear in `q̇`, so the velocities not given are one
/// least-squares solve at the projected `q`, which must determine each of
/// them ([`StartError::Undetermined`]) and leave every residual at
/// rounding ([`StartError::Inconsistent`]). A model without constraints
/// gets its start back unchanged.
///
/// A slider-crank started from its crank angle and rate:
///
/// ```
/// use lagrange::models::SliderCrank;
/// use lagrange_runtime::constraints::{Holonomic, consistent_start};
/// use lagrange_runtime::nalgebra::Vector3;
///
/// let crank = SliderCrank::new(0.5, 2.0, 1.0, 1.0, 1.0, 9.81);
/// let (exact, exact_rates) = crank.state(0.4, 1.5);
/// // A rough guess for the rod and slider, the crank's angle and rate exact.
/// let guess = Vector3::new(exact[0], exact[1] + 0.05, exact[2] - 0.1);
/// let rates = Vector3::new(exact_rates[0], 0.0, 0.0);
/// let (q, qdot) = consistent_start(&crank, 0.0, &guess, &rates, &["theta"], &["theta"])?;
/// assert!((q - exact).amax() < 1e-12 && (qdot - exact_rates).amax() < 1e-12);
/// assert!(crank.constraints(0.0, &q).amax() < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn consistent_start<L, S, const N: usize>(
    model: &L,
    t: S,
    q: &SVector<S, N>,
    qdot: &SVector<S, N>,
    held: &[&str],
    given: &[&str],
) -> Result<(SVector<S, N>, SVector<S, N>), StartError<S, N>>
where
    L: Lagrangian<N, Scalar = S>,
    S: RealField + Copy,
{
    let index = |names: &[&str]| -> Result<[bool; N], StartError<S, N>> {
        let mut kept = [false; N];
        for name in names {
            let i = L::COORDINATES
                .iter()
                .position(|c| c == name)
                .ok_or_else(|| StartError::UnknownCoordinate {
                    name: name.to_string(),
                    coordinates: L::COORDINATES.join(", "),
                })?;
            kept[i] = true;
        }
        Ok(kept)
    };
    let (held, given) = (index(held)?, index(given)?);
    if !(q.iter().all(|x| x.is_finite()) && qdot.iter().all(|x| x.is_finite())) {
        return Err(StartError::NonFinite { q: *q, qdot: *qdot });
    }
    model
        .visit_constraints(Start {
            t,
            q: *q,
            qdot: *qdot,
            held,
            given,
            names: L::COORDINATES,
        })
        .unwrap_or(Ok((*q, *qdot)))
}

/// The whole state of a model whose orientation is a unit quaternion
/// (body to space, its components the coordinates named in `quaternion`,
/// `w` first), turning at body rates `omega`: the coordinates named in
/// `positions` and the velocities named in `velocities` set, every other
/// coordinate zero, the quaternion's rates `q̇ = ½ q (0, ω)`, then
/// [`consistent_start`] with all of those kept, so that the velocities
/// left (a rolling ball's centre) are those the constraints allow.
///
/// A ball rolling on the table, from its body rates:
///
/// ```
/// use lagrange::models::RollingBall;
/// use lagrange_runtime::constraints::state_from_body_rates;
/// use lagrange_runtime::nalgebra::{UnitQuaternion, Vector3, Vector6};
///
/// let ball = RollingBall::new(1.0, 0.1);
/// let turned = UnitQuaternion::from_euler_angles(0.3, -0.2, 0.1);
/// let (q, qdot): (Vector6<f64>, Vector6<f64>) = state_from_body_rates(
///     &ball, 0.0, &[("x", 1.0)], &[], ["w", "a", "b", "c"], &turned, &Vector3::new(2.0, -1.0, 0.5),
/// )?;
/// // Rolling: the centre moves at r ω × the vertical, ω in space.
/// let omega = turned * Vector3::new(2.0, -1.0, 0.5);
/// assert!((qdot[0] - 0.1 * omega[1]).abs() < 1e-14 && (qdot[1] + 0.1 * omega[0]).abs() < 1e-14);
/// assert_eq!(q[0], 1.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn state_from_body_rates<L, S, const N: usize>(
    model: &L,
    t: S,
    positions: &[(&str, S)],
    velocities: &[(&str, S)],
    quaternion: [&str; 4],
    rotation: &UnitQuaternion<S>,
    omega: &Vector3<S>,
) -> Result<(SVector<S, N>, SVector<S, N>), StartError<S, N>>
where
    L: Lagrangian<N, Scalar = S>,
    S: RealField + Copy,
{
    let at = |name: &str| {
        L::COORDINATES
            .iter()
            .position(|c| *c == name)
            .ok_or_else(|| StartError::UnknownCoordinate {
                name: name.to_string(),
                coordinates: L::COORDINATES.join(", "),
            })
    };
    let (mut q, mut qdot) = (SVector::<S, N>::zeros(), SVector::<S, N>::zeros());
    for &(name, value) in positions {
        q[at(name)?] = value;
    }
    for &(name, value) in velocities {
        qdot[at(name)?] = value;
    }
    let turn = rotation.quaternion();
    let half: S = nalgebra::convert(0.5);
    let rate = turn * Quaternion::from_imag(*omega) * half;
    for (k, name) in quaternion.iter().enumerate() {
        let i = at(name)?;
        (q[i], qdot[i]) = match k {
            0 => (turn.w, rate.w),
            1 => (turn.i, rate.i),
            2 => (turn.j, rate.j),
            _ => (turn.k, rate.k),
        };
    }
    let held: Vec<&str> = positions.iter().map(|p| p.0).chain(quaternion).collect();
    let given: Vec<&str> = velocities.iter().map(|v| v.0).chain(quaternion).collect();
    consistent_start(model, t, &q, &qdot, &held, &given)
}

/// The visit that does [`consistent_start`]'s work with the model's `C`
/// known; the linear algebra in `DMatrix`, sized at run time.
struct Start<S: RealField + Copy, const N: usize> {
    t: S,
    q: SVector<S, N>,
    qdot: SVector<S, N>,
    held: [bool; N],
    given: [bool; N],
    names: [&'static str; N],
}

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Start<S, N> {
    type Output = Result<(SVector<S, N>, SVector<S, N>), StartError<S, N>>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let Self {
            t,
            mut q,
            mut qdot,
            held,
            given,
            names,
        } = self;
        let rows = model.velocity_constraint_rows();
        let holonomic: Vec<usize> = (0..C).filter(|&i| !rows[i]).collect();
        let moved: Vec<usize> = (0..N).filter(|&j| !held[j]).collect();
        // Positions: Gauss–Newton on the coordinates not held.
        let mut iterations = 0;
        loop {
            let phi = model.constraints(t, &q);
            let g = model.constraint_jacobian(t, &q);
            let tolerance = position_tolerance(&g, &q);
            let worst = holonomic
                .iter()
                .copied()
                .filter(|&i| off(phi[i], tolerance[i]))
                .max_by(|&i, &j| {
                    phi[i]
                        .abs()
                        .partial_cmp(&phi[j].abs())
                        .unwrap_or(core::cmp::Ordering::Greater)
                });
            let Some(worst) = worst else { break };
            if iterations == MAX_ITERATIONS || moved.is_empty() {
                return Err(StartError::NotConverged {
                    q,
                    constraint: H::CONSTRAINTS[worst],
                    residual: phi[worst],
                    iterations,
                });
            }
            let jacobian = DMatrix::from_fn(holonomic.len(), moved.len(), |r, c| {
                g[(holonomic[r], moved[c])]
            });
            let rhs = DVector::from_fn(holonomic.len(), |r, _| -phi[holonomic[r]]);
            let step = least_squares(&jacobian, &rhs).0;
            let next = {
                let mut next = q;
                for (c, &j) in moved.iter().enumerate() {
                    next[j] += step[c];
                }
                next
            };
            if !next.iter().all(|x| x.is_finite()) {
                return Err(StartError::NotConverged {
                    q,
                    constraint: H::CONSTRAINTS[worst],
                    residual: phi[worst],
                    iterations,
                });
            }
            q = next;
            iterations += 1;
        }
        // Velocities: every row is affine in q̇; solve for those not given.
        let unknown: Vec<usize> = (0..N).filter(|&j| !given[j]).collect();
        for &j in &unknown {
            qdot[j] = S::zero();
        }
        let g = model.constraint_jacobian(t, &q);
        if !unknown.is_empty() {
            let offset = model.constraint_velocities(t, &q, &qdot);
            let jacobian = DMatrix::from_fn(C, unknown.len(), |r, c| g[(r, unknown[c])]);
            let rhs = DVector::from_fn(C, |r, _| -offset[r]);
            let (solution, undetermined) = least_squares(&jacobian, &rhs);
            if let Some(c) = undetermined {
                return Err(StartError::Undetermined {
                    coordinate: names[unknown[c]],
                });
            }
            for (c, &j) in unknown.iter().enumerate() {
                qdot[j] = solution[c];
            }
        }
        let residual = model.constraint_velocities(t, &q, &qdot);
        let tolerance = velocity_tolerance(model, t, &q, &g, &qdot);
        if let Some(i) = (0..C)
            .filter(|&i| off(residual[i], tolerance[i]))
            .max_by(|&i, &j| {
                residual[i]
                    .abs()
                    .partial_cmp(&residual[j].abs())
                    .unwrap_or(core::cmp::Ordering::Greater)
            })
        {
            return Err(StartError::Inconsistent {
                constraint: H::CONSTRAINTS[i],
                residual: residual[i],
            });
        }
        Ok((q, qdot))
    }
}

/// A residual beyond its tolerance, or not a number.
fn off<S: RealField + Copy>(residual: S, tolerance: S) -> bool {
    !residual.is_finite() || residual.abs() > tolerance
}

/// The least-squares, least-norm solution of `a x = b`, from the SVD of
/// `a` with singular values below `√ε` of the largest dropped; and the
/// column whose unknown is least determined where some are not (the
/// largest entry of a right singular vector of a dropped or missing
/// singular value).
fn least_squares<S: RealField + Copy>(
    a: &DMatrix<S>,
    b: &DVector<S>,
) -> (DVector<S>, Option<usize>) {
    let (rows, columns) = a.shape();
    if rows == 0 || columns == 0 {
        return (DVector::zeros(columns), (columns > 0).then_some(0));
    }
    let svd = a.clone().svd(true, true);
    let largest = svd.singular_values.max();
    let cut = S::default_epsilon().sqrt() * largest;
    let v_t = svd.v_t.as_ref().expect("asked for");
    let u = svd.u.as_ref().expect("asked for");
    let mut x = DVector::zeros(columns);
    let mut kept = 0;
    for k in 0..svd.singular_values.len() {
        let sigma = svd.singular_values[k];
        if sigma > cut && largest > S::zero() {
            kept += 1;
            let coefficient = u.column(k).dot(b) / sigma;
            x += v_t.row(k).transpose() * coefficient;
        }
    }
    let undetermined = (kept < columns).then(|| {
        // A direction no row sees: orthogonal to the kept rows of Vᵀ.
        let mut worst = (0, S::zero());
        for j in 0..columns {
            let seen: S = (0..svd.singular_values.len())
                .filter(|&k| svd.singular_values[k] > cut)
                .map(|k| v_t[(k, j)] * v_t[(k, j)])
                .fold(S::zero(), |s, x| s + x);
            let unseen = S::one() - seen;
            if unseen > worst.1 {
                worst = (j, unseen);
            }
        }
        worst.0
    });
    (x, undetermined)
}
