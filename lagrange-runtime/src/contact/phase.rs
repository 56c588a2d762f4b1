//! The dynamics in one assignment of modes: the touching contacts'
//! forces solved with the accelerations, and the model a run integrates
//! between switches ([`Phase`]), whose forcing includes them.

use nalgebra::{DMatrix, DVector, RealField, SMatrix, SVector};

use super::erased::Erased;
use super::held::HeldSolve;
use super::{ContactForces, ContactLaw, Contacts, Mode};
use crate::dynamics::mass_error;
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::all_finite;
use crate::linalg::mass::{MassFactor, SolveError, factor_mass_matrix, solve_mass_matrix};
use crate::model::Lagrangian;

/// The accelerations and the contact forces at a state.
pub(crate) type Solved<S, const N: usize, const K: usize> = (SVector<S, N>, ContactForces<S, N, K>);

/// One unknown force of a mode: the contact, and whether normal or
/// tangential (a stuck contact's friction, along the slip's first row, or
/// along a slip vector's second).
#[derive(Clone, Copy)]
pub(super) struct Unknown {
    pub(super) contact: usize,
    pub(super) tangential: bool,
    pub(super) second: bool,
}

/// Where the friction of the contacts that slip in a plane
/// ([`Mode::Slipping`]) points: each one's direction `d` when it started
/// to slip (a unit vector of its slip plane; the slip's own direction
/// where it was slipping then, else the direction it sets off in), and
/// `lead`, the settings' `direction_speed`. The friction acts against
/// `v + (max(v·d, 0) + lead − v·d) d`: `d` from rest (where `v/|v|` has
/// none), the slip's own direction where it moves along `d`, turned
/// towards `d` by at most `lead/|v|` where it has turned from it, and
/// continuous through a slip that stops along `d` (whose event is `v·d`
/// falling through zero).
#[derive(Clone, Copy)]
pub(crate) struct Slips<S, const K: usize> {
    pub(crate) directions: [(S, S); K],
    pub(crate) lead: S,
}

impl<S: RealField + Copy, const K: usize> Slips<S, K> {
    /// No contact slipping in a plane.
    pub(crate) fn none(lead: S) -> Self {
        Self {
            directions: [(S::zero(), S::zero()); K],
            lead,
        }
    }

    /// The unit direction of contact `i`'s slip `v` (see the type).
    pub(crate) fn direction(&self, i: usize, v: (S, S)) -> (S, S) {
        let d = self.directions[i];
        let along = v.0 * d.0 + v.1 * d.1;
        let ahead = along.max(S::zero()) + self.lead - along;
        let w = (v.0 + ahead * d.0, v.1 + ahead * d.1);
        let length = (w.0 * w.0 + w.1 * w.1).sqrt();
        if length > S::zero() {
            (w.0 / length, w.1 / length)
        } else {
            d
        }
    }
}

/// The contact terms at a state, evaluated once.
pub(crate) struct Terms<S: RealField + Copy, const N: usize, const K: usize> {
    pub(crate) factor: MassFactor<S, N>,
    pub(crate) forcing: SVector<S, N>,
    pub(crate) g: SMatrix<S, K, N>,
    pub(crate) gamma: SVector<S, K>,
    pub(crate) t: SMatrix<S, K, N>,
    pub(crate) gamma_t: SVector<S, K>,
    /// The slip vectors' second rows, `T₂` and `γ₂`, and both components
    /// of the slips, `v_t` and `v₂`: zero where no contact's friction acts
    /// in a plane.
    pub(crate) t2: SMatrix<S, K, N>,
    pub(crate) gamma_t2: SVector<S, K>,
    pub(crate) slip: SVector<S, K>,
    pub(crate) slip2: SVector<S, K>,
    /// The model's own constraints, held ([`held`](super::held)).
    held: Option<HeldSolve<S, N>>,
}

impl<S: RealField + Copy, const N: usize, const K: usize> Terms<S, N, K> {
    /// `M` factored, `f`, `G`, `γ`, `T`, `γ_t` at `(t, q, q̇)`; `None` where
    /// `M` cannot be factored.
    pub(crate) fn new(
        model: &Erased<'_, S, N, K>,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<Self> {
        let (m, forcing) = model.mass_matrix_and_forcing(t, q, qdot);
        Self::with(model, (t, q, qdot), &m, forcing)
    }

    /// The same, with `M` and `f` already evaluated.
    pub(crate) fn with(
        model: &Erased<'_, S, N, K>,
        (t, q, qdot): (S, &SVector<S, N>, &SVector<S, N>),
        m: &SMatrix<S, N, N>,
        forcing: SVector<S, N>,
    ) -> Option<Self> {
        let (factor, held) = match model.held(t, q, qdot, false) {
            None => (factor_mass_matrix(m).ok()?, None),
            Some(held) => {
                let (metric, k) = held.metric(m);
                let factor = factor_mass_matrix(&metric).ok()?;
                let solve = HeldSolve::new(&factor, &held, k)?;
                (factor, Some(solve))
            }
        };
        let (t2, gamma_t2, slip, slip2) = if model.planes() {
            (
                model.second_slip_jacobian(t, q),
                model.second_slip_bias(t, q, qdot),
                model.slip_velocities(t, q, qdot),
                model.second_slip_velocities(t, q, qdot),
            )
        } else {
            (
                SMatrix::zeros(),
                SVector::zeros(),
                SVector::zeros(),
                SVector::zeros(),
            )
        };
        Some(Self {
            factor,
            forcing,
            g: model.gap_jacobian(t, q),
            gamma: model.gap_bias(t, q, qdot),
            t: model.slip_jacobian(t, q),
            gamma_t: model.slip_bias(t, q, qdot),
            t2,
            gamma_t2,
            slip,
            slip2,
            held,
        })
    }

    /// The accelerations a force `b` gives: `M⁻¹ b`, or with the model's
    /// own constraints held, `P b` (no bias: a response).
    pub(crate) fn solve(&self, b: &SVector<S, N>) -> Option<SVector<S, N>> {
        match &self.held {
            None => self.factor.solve(b).ok(),
            Some(held) => held.respond(&self.factor, b),
        }
    }

    /// The accelerations under the forcing `f` alone: `M⁻¹ f`, or with
    /// the model's own constraints held, the constrained accelerations
    /// (with their bias).
    pub(crate) fn free(&self, f: &SVector<S, N>) -> Option<SVector<S, N>> {
        match &self.held {
            None => self.factor.solve(f).ok(),
            Some(held) => held.accelerate(&self.factor, f),
        }
    }
}

/// The generalized force direction of a normal force on contact `i` in
/// mode `mode`: `Gᵢ`, or `Gᵢ ∓ μ_k Tᵢ` while it slides, or
/// `Gᵢ − μ_k (u₁ Tᵢ + u₂ T₂ᵢ)` while it slips in a plane along `u`.
pub(crate) fn normal_direction<S: RealField + Copy, const N: usize, const K: usize>(
    terms: &Terms<S, N, K>,
    i: usize,
    mode: Mode,
    kinetic_friction: S,
    slips: &Slips<S, K>,
) -> SVector<S, N> {
    let g = terms.g.row(i).transpose();
    match mode {
        Mode::Sliding { forward } => {
            let sign = if forward { S::one() } else { -S::one() };
            g - terms.t.row(i).transpose() * (sign * kinetic_friction)
        }
        Mode::Slipping => {
            let u = slips.direction(i, (terms.slip[i], terms.slip2[i]));
            g - (terms.t.row(i).transpose() * u.0 + terms.t2.row(i).transpose() * u.1)
                * kinetic_friction
        }
        _ => g,
    }
}

/// The friction of the sliding contacts with a given normal force (see
/// [`ContactLaw::normal`](super::ContactLaw::normal)), a known force:
/// each one's friction force `∓μ_k N`, and all of them as generalized
/// forces `Σ Tᵢᵀ Fᵢ`.
pub(crate) fn given_friction<S: RealField + Copy, const N: usize, const K: usize>(
    terms: &Terms<S, N, K>,
    laws: &[ContactLaw<S>; K],
    modes: &[Mode; K],
) -> (SVector<S, K>, SVector<S, N>) {
    let mut friction = SVector::<S, K>::zeros();
    let mut generalized = SVector::<S, N>::zeros();
    for i in 0..K {
        if let (Some(normal), Mode::Sliding { forward }) = (laws[i].normal, modes[i]) {
            let f = laws[i].kinetic_friction * normal;
            friction[i] = if forward { -f } else { f };
            generalized += terms.t.row(i).transpose() * friction[i];
        }
    }
    (friction, generalized)
}

/// The accelerations and contact forces in `modes`: `M q̈ = f + Dᵀ λ` with
/// `g̈ᵢ = 0` for every touching contact and `v̇_t = 0` for every stuck one.
/// `None` where the system is singular.
pub(crate) fn accelerations<S: RealField + Copy, const N: usize, const K: usize>(
    model: &Erased<'_, S, N, K>,
    modes: &[Mode; K],
    terms: &Terms<S, N, K>,
    slips: &Slips<S, K>,
) -> Option<Solved<S, N, K>> {
    let laws = model.contact_laws();
    let (known_friction, known) = given_friction(terms, &laws, modes);
    let free = terms.free(&(terms.forcing + known))?;
    let mut forces = ContactForces::zero();
    for (i, law) in laws.iter().enumerate() {
        if let Some(normal) = law.normal {
            forces.normal[i] = normal;
            forces.friction[i] = known_friction[i];
        }
    }
    forces.generalized = known;
    let mut unknowns = Vec::new();
    for (i, mode) in modes.iter().enumerate() {
        if mode.touching() && laws[i].normal.is_none() {
            unknowns.push(Unknown {
                contact: i,
                tangential: false,
                second: false,
            });
        }
        if *mode == Mode::Stuck {
            unknowns.push(Unknown {
                contact: i,
                tangential: true,
                second: false,
            });
            if laws[i].in_plane {
                unknowns.push(Unknown {
                    contact: i,
                    tangential: true,
                    second: true,
                });
            }
        }
    }
    if unknowns.is_empty() {
        return Some((free, forces));
    }
    let m = unknowns.len();
    let mut directions = Vec::with_capacity(m);
    let mut responses = Vec::with_capacity(m);
    for u in &unknowns {
        let d = if u.second {
            terms.t2.row(u.contact).transpose()
        } else if u.tangential {
            terms.t.row(u.contact).transpose()
        } else {
            normal_direction(
                terms,
                u.contact,
                modes[u.contact],
                laws[u.contact].kinetic_friction,
                slips,
            )
        };
        responses.push(terms.solve(&d)?);
        directions.push(d);
    }
    let row = |u: &Unknown| {
        if u.second {
            (terms.t2.row(u.contact), terms.gamma_t2[u.contact])
        } else if u.tangential {
            (terms.t.row(u.contact), terms.gamma_t[u.contact])
        } else {
            (terms.g.row(u.contact), terms.gamma[u.contact])
        }
    };
    let mut a = DMatrix::zeros(m, m);
    let mut b = DVector::zeros(m);
    for (r, u) in unknowns.iter().enumerate() {
        let (w, bias) = row(u);
        for (c, response) in responses.iter().enumerate() {
            a[(r, c)] = w.dot(&response.transpose());
        }
        b[r] = -(w.dot(&free.transpose()) + bias);
    }
    let (lambda, rank) = least_solve(a.clone(), &b)?;
    let lambda = if rank < m && unknowns.iter().any(|u| u.tangential) {
        let shared = share_friction(a, &b, lambda, &unknowns, &laws)?;
        let columns = DMatrix::from_fn(N, m, |r, c| responses[c][r]);
        super::admissible::admissible(&columns, shared, &unknowns, &laws)
    } else {
        lambda
    };
    let mut qddot = free;
    let mut force = known;
    for c in 0..m {
        qddot += responses[c] * lambda[c];
        force += directions[c] * lambda[c];
    }
    for (c, u) in unknowns.iter().enumerate() {
        if u.second {
            forces.second_friction[u.contact] = lambda[c];
        } else if u.tangential {
            forces.friction[u.contact] = lambda[c];
        } else {
            forces.normal[u.contact] = lambda[c];
            let friction = laws[u.contact].kinetic_friction * lambda[c];
            match modes[u.contact] {
                Mode::Sliding { forward } => {
                    forces.friction[u.contact] = if forward { -friction } else { friction };
                }
                Mode::Slipping => {
                    let i = u.contact;
                    let u = slips.direction(i, (terms.slip[i], terms.slip2[i]));
                    forces.friction[i] = -friction * u.0;
                    forces.second_friction[i] = -friction * u.1;
                }
                _ => {}
            }
        }
    }
    forces.generalized = force;
    Some((qddot, forces))
}

/// The minimum-norm least-squares solution of `A x = b`, by singular
/// values, consistent or not: a projection's correction, where rows that
/// are dependent (two corners of a cube's edge, both stuck, slip alike
/// along it) carry residuals that differ by the integration's drift, and
/// the best correction in the least-squares sense is the one to take.
/// `None` where a value is not finite.
pub(crate) fn least_squares<S: RealField + Copy>(
    a: DMatrix<S>,
    b: &DVector<S>,
) -> Option<DVector<S>> {
    if !a.iter().chain(b.iter()).all(|x| x.is_finite()) {
        return None;
    }
    let scale = a.iter().fold(S::zero(), |m, x| m.max(x.abs()));
    let eps = nalgebra::convert::<f64, S>(1e-12) * scale;
    let x = a.svd(true, true).solve(b, eps).ok()?;
    crate::linalg::all_finite(x.as_slice()).then_some(x)
}

/// The minimum-norm solution of `A x = b`, by singular values, and the
/// rank of `A` it found: touching contacts whose rows are dependent (two
/// corners of a box flat on the floor, both stuck) leave their forces
/// undetermined but the accelerations not, and this takes the smallest
/// forces that give them. `None` where no `x` satisfies the equations to
/// rounding (a system that is inconsistent, not merely redundant) or a
/// value is not finite.
///
/// nalgebra's SVD can be inaccurate beside a repeated singular value: on
/// the system of a rod stuck on two rough supports (`A = D M⁻¹ Dᵀ` of rank
/// 5, singular values 5.320465 twice, 2, 1.8795 twice and 0) it returns
/// 5.32067 and 5.32047 for the pair, and `U Σ Vᵀ` is 4e-2 from `A`, while
/// its null vector is right to rounding. Its solution there leaves a
/// residual of up to 3e-2 of `|b|`; taken as it is, where it passed the
/// check, it made the rod creep by 1e-10 m and its steps a thousand times
/// smaller (the error estimate reading the residual's noise). So a
/// solution whose residual is beyond rounding ([`ROUNDING`] of the
/// system's size, in ε) is refined with the same factors, `x += A⁺ (b − A x)`:
/// each round divides the residual by about 1e4 there, and the
/// corrections lie in the span of the right singular vectors, so that the
/// solution stays the minimum-norm one. A first solution within rounding
/// (an accurate SVD's) is taken as it is; after [`REFINEMENTS`] rounds,
/// the best solution is taken if its residual is within `1e-8` of the
/// system's size (a system whose refinement stalls above rounding), and
/// the system is inconsistent otherwise.
fn least_solve<S: RealField + Copy>(a: DMatrix<S>, b: &DVector<S>) -> Option<(DVector<S>, usize)> {
    if !a.iter().chain(b.iter()).all(|x| x.is_finite()) {
        return None;
    }
    let scale = a.iter().fold(S::zero(), |m, x| m.max(x.abs()));
    let c = nalgebra::convert::<f64, S>;
    let svd = a.clone().svd(true, true);
    let eps = c(1e-12) * scale;
    let rank = svd.singular_values.iter().filter(|&&v| v > eps).count();
    let mut x = svd.solve(b, eps).ok()?;
    let mut best: Option<(DVector<S>, S, S)> = None;
    for round in 0..=REFINEMENTS {
        if !crate::linalg::all_finite(x.as_slice()) {
            break;
        }
        let residual = b - &a * &x;
        let size = b.norm().max(scale * x.norm());
        let r = residual.norm();
        if r <= c(ROUNDING) * S::default_epsilon() * size {
            return Some((x, rank));
        }
        if best.as_ref().is_some_and(|(_, best_r, _)| *best_r <= r) {
            // The refinement no longer gains.
            break;
        }
        best = Some((x.clone(), r, size));
        if round == REFINEMENTS {
            break;
        }
        match svd.solve(&residual, eps) {
            Ok(dx) => x += dx,
            Err(_) => break,
        }
    }
    best.and_then(|(x, r, size)| (r <= c(1e-8) * size).then_some((x, rank)))
}

/// The residual, in units of the scalar's ε and relative to the system's
/// size (`max(|b|, max|A| |x|)`), that [`least_solve`] takes as rounding:
/// a backward-stable solve of a system of a few dozen unknowns leaves
/// some `n ε`, and 450 ε (1e-13 in `f64`) leaves room for the systems of
/// many contacts.
const ROUNDING: f64 = 450.0;

/// The rounds of refinement [`least_solve`] takes at most after its first
/// solution: the rod's systems needed 3 to reach rounding.
const REFINEMENTS: usize = 4;

/// The forces of touching contacts whose rows are dependent, with stuck
/// friction among them: only some combinations of them are determined
/// (the friction two corners of a crate flat on a floor carry together),
/// and the minimum-norm forces share that friction evenly, which can leave
/// a less loaded contact outside its cone while an admissible share
/// exists. Here the friction is shared in proportion to each contact's
/// cone, `μ_s N`: the forces of least `Σ N² + Σ F² N_ref / (μ_s N)`
/// (`N_ref` the largest normal force of a stuck contact, so that the sum
/// is one of forces squared in any units; a brake's is its given force), the minimum-norm solution in those scaled
/// unknowns, with the normal forces of the minimum-norm solution `first`.
/// Where the shared friction's only constraint is its sum (stuck contacts
/// on one body against one flat surface: a crate, a box's corners), each
/// share is then the same fraction of its cone: every share lies inside
/// its cone exactly while the sum lies within the sum of the cones, and
/// all reach their limits together, where the body breaks away.
fn share_friction<S: RealField + Copy>(
    a: DMatrix<S>,
    b: &DVector<S>,
    first: DVector<S>,
    unknowns: &[Unknown],
    laws: &[super::ContactLaw<S>],
) -> Option<DVector<S>> {
    // A stuck contact's normal force: given by its law (a brake), or an
    // unknown of the first solution.
    let normal_of = |contact: usize| {
        let unknown = || {
            unknowns
                .iter()
                .position(|u| u.contact == contact && !u.tangential)
                .map_or(S::zero(), |k| first[k])
        };
        laws[contact].normal.unwrap_or_else(unknown).max(S::zero())
    };
    let reference = unknowns
        .iter()
        .filter(|u| u.tangential)
        .fold(S::zero(), |m, u| m.max(normal_of(u.contact)));
    if reference <= S::zero() {
        return Some(first);
    }
    let scales = DVector::from_iterator(
        unknowns.len(),
        unknowns.iter().map(|u| {
            if u.tangential {
                let capacity = laws[u.contact].static_friction * normal_of(u.contact);
                (capacity / reference).sqrt()
            } else {
                S::one()
            }
        }),
    );
    let scaled = a * DMatrix::from_diagonal(&scales);
    let (u, _) = least_solve(scaled, b)?;
    Some(u.component_mul(&scales))
}

/// The model a run integrates between switches: the contact model with the
/// touching contacts' forces in its forcing, in its modes.
///
/// A [`Scene`](super::Scene)'s [`Stepper`](crate::stepper::Stepper) steps
/// it; it is not built by hand. It is plain data: the modes are the run's
/// (kept with its switches as the data its events read and their resets
/// change), and the run builds the phase anew from them at each switch.
/// It is the same type for every model with the same scalar, `N` and `K`
/// (the model behind [`Erased`]), so the loops that run it are compiled
/// once for all of them; its `COORDINATES` are blank (the model's own are
/// the model's).
#[derive(Clone, Copy)]
pub struct Phase<'a, S: RealField + Copy, const N: usize, const K: usize> {
    pub(crate) model: Erased<'a, S, N, K>,
    pub(crate) modes: [Mode; K],
    pub(crate) slips: Slips<S, K>,
}

impl<S: RealField + Copy, const N: usize, const K: usize> Phase<'_, S, N, K> {
    /// The accelerations and forces at a state in the current modes;
    /// `None` where they are not determined.
    pub(crate) fn solve(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<Solved<S, N, K>> {
        let (m, f) = self.model.mass_matrix_and_forcing(t, q, qdot);
        self.solve_with(t, q, qdot, &m, f)
    }

    /// [`solve`](Self::solve) with `M` and `f` already evaluated.
    fn solve_with(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
        m: &SMatrix<S, N, N>,
        f: SVector<S, N>,
    ) -> Option<Solved<S, N, K>> {
        Terms::with(&self.model, (t, q, qdot), m, f)
            .and_then(|terms| accelerations(&self.model, &self.modes, &terms, &self.slips))
    }
}

// Every method written out (the lint holds it so): a capability added to
// the contract is passed on here, or said not to be.
#[warn(clippy::missing_trait_methods)]
impl<S: RealField + Copy, const N: usize, const K: usize> Lagrangian<N> for Phase<'_, S, N, K> {
    type Scalar = S;
    const COORDINATES: [&'static str; N] = [""; N];
    const SOLVES_ACCELERATIONS: bool = true;

    fn mass_matrix(&self, t: S, q: &SVector<S, N>) -> SMatrix<S, N, N> {
        self.model.mass_matrix(t, q)
    }

    fn forcing(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> SVector<S, N> {
        self.mass_matrix_and_forcing(t, q, qdot).1
    }

    /// `M`, and `f` with the contact forces `Dᵀ λ` added (NaN where they
    /// are not determined; a run reads [`accelerations`](Self::accelerations),
    /// which says so).
    fn mass_matrix_and_forcing(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> (SMatrix<S, N, N>, SVector<S, N>) {
        let (m, f) = self.model.mass_matrix_and_forcing(t, q, qdot);
        let f = match self.solve_with(t, q, qdot, &m, f) {
            // With the model's own constraints held, their forces too:
            // `M q̈` itself.
            Some((qddot, _)) if self.model.constrained() => m * qddot,
            Some((_, forces)) => f + forces.generalized,
            None => SVector::repeat(S::zero() / S::zero()),
        };
        (m, f)
    }

    /// `M q̈ = f + Dᵀ λ` solved as for any model (the same arithmetic as
    /// from [`mass_matrix_and_forcing`](Self::mass_matrix_and_forcing)),
    /// or why not: the contact forces not determined
    /// ([`UndeterminedContactForces`](IntegrationError::UndeterminedContactForces)),
    /// a non-finite `M` or `f`, a singular `M`.
    fn accelerations(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<Result<SVector<S, N>, IntegrationError<S, N>>> {
        let (m, f) = self.model.mass_matrix_and_forcing(t, q, qdot);
        let non_finite = |value| IntegrationError::NonFiniteState {
            t,
            q: *q,
            qdot: *qdot,
            value: self.model.blame(value, t, q, qdot),
        };
        if !all_finite(m.as_slice()) {
            return Some(Err(non_finite(NonFiniteValue::MassMatrix)));
        }
        if !all_finite(f.as_slice()) {
            return Some(Err(non_finite(NonFiniteValue::Forcing)));
        }
        let Some((qddot, forces)) = self.solve_with(t, q, qdot, &m, f) else {
            return Some(Err(IntegrationError::UndeterminedContactForces {
                t,
                q: *q,
                qdot: *qdot,
            }));
        };
        if self.model.constrained() {
            // The constrained solve's own `q̈` (its multipliers are not
            // in `forces`); `M` may be singular by itself (a quaternion).
            return Some(if all_finite(qddot.as_slice()) {
                Ok(qddot)
            } else {
                Err(non_finite(NonFiniteValue::Constraints))
            });
        }
        Some(
            solve_mass_matrix(&m, &(f + forces.generalized)).map_err(|error| match error {
                SolveError::NonFiniteForcing => non_finite(NonFiniteValue::Forcing),
                error => mass_error(error, t, q, qdot),
            }),
        )
    }

    fn kinetic_energy(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> S {
        self.model.kinetic_energy(t, q, qdot)
    }

    fn potential_energy(&self, t: S, q: &SVector<S, N>) -> S {
        self.model.potential_energy(t, q)
    }

    fn energy(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> S {
        self.kinetic_energy(t, q, qdot) + self.potential_energy(t, q)
    }

    fn parameters_are_finite(&self) -> bool {
        self.model.parameters_are_finite()
    }

    /// None: the model's Jacobians leave out the contacts' forces, which
    /// move with the state; the implicit methods take differences of the
    /// phase's accelerations.
    fn residual_jacobians(
        &self,
        _: S,
        _: &SVector<S, N>,
        _: &SVector<S, N>,
        _: &SVector<S, N>,
    ) -> Option<(SMatrix<S, N, N>, SMatrix<S, N, N>)> {
        None
    }

    // The erased model's, which says why each is absent.

    fn momentum(&self, t: S, q: &SVector<S, N>, qdot: &SVector<S, N>) -> Option<SVector<S, N>> {
        self.model.momentum(t, q, qdot)
    }
    fn lagrangian_gradient(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        self.model.lagrangian_gradient(t, q, qdot)
    }
    fn nonconservative_forces(
        &self,
        t: S,
        q: &SVector<S, N>,
        qdot: &SVector<S, N>,
    ) -> Option<SVector<S, N>> {
        self.model.nonconservative_forces(t, q, qdot)
    }
    fn visit_constraints<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: crate::model::constraints::Visitor<S, N>,
    {
        self.model.visit_constraints(visitor)
    }
    fn visit_lets<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: crate::model::lets::Visitor<S, N>,
    {
        self.model.visit_lets(visitor)
    }

    /// None: the model's inputs are checked by
    /// [`Scene::new`](super::Scene::new), and a non-finite value blamed on
    /// them in [`accelerations`](Self::accelerations).
    fn visit_inputs<V>(&self, _: V) -> Option<V::Output>
    where
        V: crate::model::inputs::Visitor<S, N>,
    {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The system of a rod stuck on two rough supports
    /// (`models::PushedRod` in a run, traced where it stopped before the
    /// refinement): `A = D M⁻¹ Dᵀ` of rank 5, its two slip rows along the
    /// rod the same (unknowns 1 and 4), on which nalgebra's SVD is
    /// inaccurate (its solution's residual 2.9e-2 of the system).
    #[test]
    fn a_consistent_system_next_to_a_repeated_singular_value_is_solved_to_rounding() {
        #[rustfmt::skip]
        let a = DMatrix::<f64>::from_column_slice(6, 6, &[
            4.6, 1.2350581153541956e-16, 1.4020478685747425e-33, -1.4000000000000004,
            -8.23372076902797e-17, -9.346985790498283e-34, 1.2350581153541954e-16, 1.0,
            -4.086748845354183e-17, -8.23372076902797e-17, 1.0, 2.7244992302361224e-17,
            1.4020478685747423e-33, -4.086748845354184e-17, 4.6, -9.346985790498283e-34,
            2.7244992302361224e-17, -1.4000000000000004, -1.4, -8.23372076902797e-17,
            -9.346985790498283e-34, 2.6, 5.4891471793519805e-17, 6.231323860332189e-34,
            -8.23372076902797e-17, 1.0, 2.7244992302361224e-17, 5.4891471793519805e-17, 1.0,
            -1.816332820157415e-17, -9.346985790498282e-34, 2.7244992302361224e-17, -1.4,
            6.231323860332189e-34, -1.816332820157415e-17, 2.6,
        ]);
        #[rustfmt::skip]
        let b = DVector::<f64>::from_column_slice(&[
            9.81, -3.6226625668113366, 1.6732361665053639, 9.81, -3.6226625668113366,
            -4.601399457889752,
        ]);
        let one_shot = a.clone().svd(true, true).solve(&b, 1e-12 * 4.6).unwrap();
        println!("one SVD solve: residual {:e}", (&a * &one_shot - &b).norm());
        let (x, rank) = least_solve(a.clone(), &b).expect("consistent");
        assert_eq!(rank, 5);
        let size = b.norm().max(4.6 * x.norm());
        let residual = (&a * &x - &b).norm();
        println!("refined: residual {residual:e} of a system of size {size}");
        // Within what the refinement stops at (450 ε of the size).
        assert!(residual <= ROUNDING * f64::EPSILON * size, "{residual:e}");
        // The minimum-norm solution: nothing along the null space, which
        // moves the friction along the rod between the supports (x₁ − x₄).
        assert!((x[1] - x[4]).abs() < 1e-12 * x.norm(), "{x}");
    }
}
