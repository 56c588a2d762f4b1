//! Contacts that open and close, and friction that sticks: unilateral
//! constraints `g(t, q) ≥ 0` and Coulomb friction, along one slip
//! direction or isotropic in a plane, with every switch located as an
//! event.
//!
//! A model with contacts implements [`Contacts<N, K>`]: for each of its `K`
//! contacts a gap `g(t, q)`, non-negative while the bodies are apart, with
//! its Jacobian and the bias of its acceleration (as a holonomic
//! constraint has), optionally a slip velocity `v_t = T(t, q) q̇ + b` along
//! which friction acts, and its [`ContactLaw`]: restitution, static and
//! kinetic friction coefficients; `lagrangian!` writes all of it from a
//! `contacts:` section (`floor: y >= 0 { restitution: e, friction: mu,
//! slip: dot(x) }`). [`integrate`] runs it with any method
//! ([`StepMethod`](crate::integrators::StepMethod)) through the run loops every model runs through,
//! and a [`Scene`] advances it frame by frame with a
//! [`Stepper`](crate::stepper::Stepper) through the same loop: the
//! contacts' state (their [`Mode`]s) is discrete, it changes only at
//! events, where it is data the run owns (each run its own), and between events the model is integrated with the closed
//! contacts as equality constraints and the sliding ones' friction as known
//! forces. The runs see the model through one object-safe interface
//! ([`Erased`]), so they are compiled once per scalar, `N` and `K`, not
//! once per model.
//!
//! # Modes and switches
//!
//! Each contact is [`Open`](Mode::Open) (no force), [`Closed`](Mode::Closed)
//! (touching, frictionless: a normal force `N ≥ 0` keeps `g̈ = 0`),
//! [`Sliding`](Mode::Sliding) (touching and slipping: `N ≥ 0` and the
//! friction force `−μ_k N sign(v_t)`), or [`Stuck`](Mode::Stuck) (touching
//! and not slipping: `N ≥ 0` and a friction force `F` that keeps `v̇_t = 0`,
//! as long as `|F| ≤ μ_s N`). The mode changes where:
//!
//! | event | function, located by the run's event search | then |
//! |---|---|---|
//! | arrival | `g` falling through 0 (an open contact; the function is `g + max(ġ, 0)`, which is `g` while it approaches and positive from a rebound's start on) | an impact, then a new decision |
//! | release | `N` falling through 0 (a touching contact) | the contact opens (and the others are decided again) |
//! | slide stop | `sign(v_t) v_t` falling through 0 (a sliding contact) | stick or slide back, decided |
//! | stick limit | `μ_s N − |F|` falling through 0 (a stuck contact) | it slides, in the direction its friction force was holding |
//!
//! Every switch is located to the events' time tolerance on the step's
//! interpolant (see [`events`](crate::events)), so a contact opens where its
//! normal force reaches zero and a sliding body sticks where its slip
//! velocity does, to that tolerance and the integrator's own error.
//!
//! # Several contacts at once: a complementarity problem
//!
//! Which touching contacts push, and which stick or slide, is not decided
//! contact by contact: at every switch, all touching contacts are decided
//! together by one linear complementarity problem at the level of the
//! accelerations (for each contact `N ≥ 0`, `g̈ ≥ 0`, `N g̈ = 0`; for each
//! sticking candidate the planar friction cone as two complementary pairs
//! and a slip rate, the classic formulation of Trinkle, Pang, Sudarsky and
//! Lo), solved by Lemke's complementary pivoting. Where it has no solution
//! (friction makes the problem inconsistent: Painlevé's paradox), the run
//! ends with [`ContactError::NoConsistentMode`], at that time and state.
//! A contact forced by its own event (a release, a stick limit) takes the
//! mode the event says, and the others are decided around it. A slip rate
//! within `1e-9` of the problem's largest term is no slip (the pivoting
//! leaves rounding there where forces are not determined). A touching
//! contact that the solution leaves without force but on the surface (its
//! normal acceleration nil, to `1e-9` of the largest) touches still:
//! where loads are not determined (four corners of a face), the pivoting
//! loads some of them, and the others, left open at a zero gap, could not
//! be watched (their arrival cannot arm) while the body turned through
//! them.
//!
//! # Friction against a given normal force: brakes and joints
//!
//! A contact whose law gives its normal force ([`ContactLaw::normal`],
//! `contacts: brake: { normal: F, friction: mu, slip: r*dot(theta) }` in
//! the language) has no gap: it always touches with that normal force, and
//! only its friction switches. It slides with the known force `−μ_k N
//! sign(v_t)` (added to the forcing, not an unknown), and sticks with a
//! friction force solved in the same complementarity problem as the other
//! contacts' (the cone's two pairs and slip rate, with `N` known), released
//! where it reaches `μ_s N`. It takes no part in impacts (a finite force
//! gives no impulse), and a stuck one that an impact sets slipping slides.
//! This is Coulomb friction in a joint: a bearing or a brake on a
//! coordinate, whose slip velocity is the joint's rate times the radius the
//! friction acts at.
//!
//! # Impacts
//!
//! A contact arriving with `ġ < 0` makes all touching contacts collide at
//! once. The impulse `P` is the plastic one, decided by the same
//! complementarity at the level of velocities (no contact approaching after
//! it, friction impulses within the cone `μ_k P_n`), and the velocity after
//! the impact is `v⁻ + (1 + e) M⁻¹ Dᵀ P`: Poisson's restitution applied to
//! the whole impulse, friction included. This law **cannot gain energy**
//! for `0 ≤ e ≤ 1`: with `d` the plastic velocity change, complementarity
//! gives `(v⁻ + d)ᵀ M d ≤ 0`, and so the kinetic energy changes by
//! `(1 + e) [v⁻ᵀ M d + (1 + e)/2 dᵀ M d] ≤ (1 + e)(e − 1)/2 dᵀ M d ≤ 0`.
//! (Newton's restitution on the normal velocity alone can gain energy when
//! friction acts; with this law a contact that stuck during the impact
//! rebounds tangentially by `−e` too.) Where contacts of different
//! restitution collide together, the smallest `e` applies, for which the
//! proof holds. Each impact is recorded as a [`Switch`] with its impulses
//! and the kinetic energy it took.
//!
//! # Impacts that accumulate
//!
//! A ball bouncing with `e < 1` makes infinitely many bounces before a
//! finite time. Here a rebound that cannot be resolved is cut off, a
//! persistent contact instead of a
//! [`Zeno`](crate::error::IntegrationError::Zeno) error (the run's own
//! Zeno guard is off). A rebound is unresolved when its flight would be
//! shorter than the settings'
//! [`shortest_flight`](ContactSettings::shortest_flight) (its normal
//! velocity over its acceleration back, `2 ġ⁺ / |g̈|`), or its apex
//! `ġ⁺² / (2 |g̈|)` below the rounding of the gap's value (`64 ε Σⱼ |Gᵢⱼ
//! qⱼ|`: a bounce no evaluation of `g` could see, which grows with the
//! coordinates' distance from the origin). Such a rebound is not made
//! plastic where it stands: the contact flies it out, watched not by its
//! gap (which cannot see it) but by the time its rebounds would have
//! accumulated at, `2 ġ⁺ / (|g̈| (1 − e))` later (their flights `2 ġ⁺ eᵏ
//! / |g̈|` summed at a constant acceleration), and settles there
//! ([`Cause::Settled`]): plastic, the contact closed for good. The time of
//! rest therefore does not depend on where the cut fell, nor on the
//! coordinates' origin or scale: a ball released 1 m above a floor at 0,
//! 0.1 or 1 m rests within 6.3e-10 s of `t₁ (1 + e)/(1 − e)`, in metres or
//! millimetres, and one at 1000 m within 2.0e-8 s (its bounces are
//! located to the rounding of a height of 1000 m). While it flies out,
//! its arrival still fires where it goes deeper than its flight would
//! take it by the gap tolerance (a method's error on the flight), and
//! settles it there; an impact of another contact meanwhile decides it
//! with the others. A rebound below the velocity tolerance closes the
//! contact at once (at most `2 v_tol / (|g̈| (1 − e))` early), and so does
//! a short elastic one (`e = 1` never accumulates).
//!
//! # Forces that are not determined: friction inside every cone
//!
//! Touching contacts whose rows are dependent leave some of their forces
//! undetermined: a crate standing on two rough corners needs only the sum
//! of their friction forces, and a ladder stuck against a rough wall on a
//! rough floor has four unknown forces and three equations of
//! equilibrium, so friction at the wall can take weight off the floor.
//! The accelerations are determined, and every distribution `λ₀ + Z z`
//! along the null space `Z` of the forces' responses (`M⁻¹ Dᵀ Z = 0`)
//! gives them; any of those whose friction lies inside every cone (`|Fᵢ|
//! ≤ μ_s Nᵢ`, `Nᵢ ≥ 0`) is a valid answer of rigid-body mechanics, and the
//! body must hold as long as one exists and break away exactly when none
//! does. The minimum-norm forces are not such a choice: they share a
//! crate's friction evenly, leaving the less loaded corner outside its
//! cone first, and for a ladder standing unpushed they give the wall no
//! normal force at all (and so, under the share below, no friction), so
//! the floor carries what the wall could have.
//!
//! The choice is made in two steps. First the minimum-norm normal forces
//! and friction shared in proportion to each contact's cone, `μ_s N` (the
//! least `Σ N² + Σ F² N_ref / (μ_s N)`, `N_ref` the largest normal force
//! of a stuck contact): where the shared friction's only constraint is its
//! sum (contacts of one body against one flat surface: a crate, a box's
//! corners), every share is then the same fraction of its cone, the least
//! use of the cones there is. Then the use of the cones, `ρ = maxᵢ |Fᵢ| /
//! (μ_s Nᵢ)`, is compared with the least possible over the null space,
//! `ρ*` (an admissible distribution exists exactly where `ρ* ≤ 1`), found
//! by bisection on the feasibility of the convex set `S(ρ)`: `|Fᵢ| ≤ ρ
//! μ_s Nᵢ`, `Nᵢ ≥ 0` in the null-space coordinates (two half-spaces per
//! cone along one slip direction, a second-order cone per disc of
//! friction in a plane, one half-space per normal force; a
//! one-dimensional null space exactly, as intervals, a larger one by
//! Lemke's method on the dual of a projection onto it). The
//! share is kept where its use is at most `ρ_t = (1 + ρ*)/2` (`ρ*` itself
//! beyond 1), and otherwise replaced by its projection onto `S(ρ_t)`: the
//! nearest forces that use no cone more than halfway between the least
//! possible use and the limit.
//!
//! - **Admissible**: every stuck contact keeps a margin `μ_s N − |F| ≥ (1
//!   − ρ*) μ_s N / 2`, positive while an admissible distribution exists;
//!   it reaches zero, at the contacts that limit the body, exactly where
//!   none remains, so the stick limit's event (`μ_s N − |F|` through zero)
//!   is located there and only there. A stick limit slides every stuck
//!   contact that is at its limit then (within `1e-9` of it, relative),
//!   not one of them: a ladder's two ends, a crate's two corners.
//! - **Unique and continuous**: where several admissible distributions
//!   exist, the one taken is the nearest to the proportional share among
//!   those that use no cone beyond `ρ_t`, a projection onto a convex set,
//!   so one; it moves continuously with the state wherever that set has an
//!   interior (the projection of a share on its boundary is the share), so
//!   the event sees a continuous margin. Where the cones could squeeze the
//!   body without limit (a ladder wedged, `μ_w μ_f ≥ 1`) the forces stay
//!   the nearest to the share, bounded. The normal forces the body does not
//!   need to redistribute stay the smallest that hold it.
//! - **Discs, by a barrier method**: a disc `|Fᵢ| ≤ ρ μ_s Nᵢ` (friction
//!   in a plane, `Fᵢ` two components) makes `S(ρ)` a second-order cone
//!   program's set, convex still. Each test of it is the barrier method's
//!   phase one (Boyd and Vandenberghe, *Convex Optimization*, §11.3, 11.4):
//!   the least slack `s` that holds every bound and disc `|Fᵢ| ≤ ρ μ_s Nᵢ +
//!   s`, with the cone's barrier `−log((ρ μ_s Nᵢ + s)² − |Fᵢ|²)`, Newton's
//!   method, and the duality gap brought below `1e-13` of the largest
//!   force: a point with `s < 0` is inside, and a centred `s` beyond the gap
//!   proves the set empty. The projection is the same method on `|z|²/2`
//!   from that point, so the forces taken lie strictly inside every disc.
//!   With discs the bisection stops at `1e-6` of `1 − ρ*` where that is
//!   above rounding: the margin left is `(1 − ρ*)/2` of each cone to that
//!   share, and `ρ*` is exact where it matters, as it reaches 1. The disc
//!   itself, to that gap, is what a breakaway must be exact against: a
//!   pyramid of `n` sides inscribed in it holds `cos(π/n)` of it along the
//!   middle of a side (99.5 % at 32 sides), and could break a body away up
//!   to that share of its load early, one circumscribed as late, with
//!   forces outside the disc: far beyond the events' time tolerance.
//! - **Cost**: nothing beyond the share where its use is at most a half,
//!   one singular value decomposition of the responses and one feasibility
//!   test where it qualifies all the same (a crate, a die's face: its
//!   forces are the share's bit for bit), and where it does not, about 50
//!   feasibility tests of the bisection and one projection, each a pass
//!   over the bounds for a one-dimensional null space, a Lemke solve for a
//!   larger one; with discs, about 20 to 50 barrier solves of the null
//!   space's few dimensions, each some tens of Newton steps. It is paid
//!   only in solves whose rows are dependent.

//! # Friction in a plane: a slip vector and a disc of forces
//!
//! A contact in 3D slips in the plane of the surface: its slip is a
//! vector `(v_t, v₂)`, the contact point's velocity along two orthogonal
//! unit tangents (the rows of [`Contacts::slip_jacobian`] and
//! [`Contacts::second_slip_jacobian`]; `slip: vector(u, v)` in the
//! language, [`ContactLaw::in_plane`]), and friction is isotropic in it:
//!
//! - **slipping** ([`Mode::Slipping`]): `F = −μ_k N v/|v|`, against the
//!   slip, turning with it as the bodies move (the normal force's
//!   direction `G − μ_k (u₁ T + u₂ T₂)` changes with the state; `u` leans
//!   on the direction the slip set off in below
//!   [`direction_speed`](ContactSettings::direction_speed), where `v/|v|`
//!   has no direction at rest);
//! - **stuck**: two friction unknowns keep `v̇_t = v̇₂ = 0`, held while
//!   `|F| ≤ μ_s N`, the disc, watched exactly (the stick limit's event is
//!   `μ_s N − |F|`); at the limit it sets off against its friction there;
//! - **slide stop**: `v·d` through zero, `d` the direction it set off in
//!   (a slip that turns by a right angle without stopping makes a switch
//!   that finds it slipping still, and goes on along its new direction).
//!
//! The decisions at switches and the impulses of impacts are the same
//! complementarity problems, the disc standing in as the regular polygon
//! of 32 sides inscribed in it (one `β` per side's direction, a pyramid in
//! the cone's terms): every decided force lies inside the disc, but a
//! slipping impact's friction impulse, or a decision within `1 −
//! cos(π/32)` (0.48 %) of the limit, sees at most 99.5 % of it (the
//! tests measure 0.9952 along the middle of a side). A second-order cone
//! solve would give the disc itself; it is not built for the decisions.
//! Where friction is statically indeterminate between switches, the
//! forces are chosen inside every disc as above, against the disc itself
//! (by a barrier method, not a polygon).
//!
//! # Guards
//!
//! - Switches that undo each other (a decision that opens a contact whose
//!   next decision closes it again, at the same time) stop the run after
//!   64 in a row at one time: [`ContactError::Chattering`], at that time
//!   and state.
//! - A contact that was touching counts as touching at the next decision
//!   even where the integration let its gap drift beyond the gap
//!   tolerance; the projection after the decision takes the drift back.
//! - A switch that cannot be decided (no consistent mode, dependent
//!   contacts, chattering) fails its event's reset: the run ends with
//!   [`IntegrationError::ResetFailed`](crate::error::IntegrationError::ResetFailed)
//!   and the trajectory so far, its [`ResetFailure`](crate::error::ResetFailure)
//!   saying which; forces that are not determined between switches end it
//!   with [`UndeterminedContactForces`](crate::error::IntegrationError::UndeterminedContactForces).
//!   [`integrate`] reports both as the [`ContactError`] they are.
//!
//! # What the contacts need, and what they do not support yet
//!
//! - The model's own constraints (`constraints:`: a body in a unit
//!   quaternion, a closed loop, rolling) are held with the contacts: every
//!   solve of the run is the constrained one (its responses to a force
//!   keep the constraints, and so does every impulse), the start is put
//!   on them as in any constrained run (projected, or refused, as the
//!   model's `InitialConditions` say), and each switch projects the state
//!   back onto them with the touching contacts. Between switches they
//!   drift by the method's error, as a closed contact's gap does: there
//!   is no projection after each step (the model's drift setting is not
//!   read). See `held.rs`.
//! - Friction in a plane (below) is the disc's between switches, but its
//!   decisions and impacts see a polygon of 32 sides.
//! - The variational integrator is refused (its step needs the model's
//!   momenta, which a run with contact forces solved from the state does
//!   not offer: `InvalidInput::ModelLacks`).
//! - Friction against a given normal force (a brake, a bearing under a
//!   known load: [`ContactLaw::normal`]) takes that force as constant: a
//!   normal force that depends on the state is a contact's reaction, and
//!   needs the gap it keeps (friction from a joint's own reaction, the
//!   multiplier of one of the model's constraints, is not supported). It
//!   acts along one slip velocity (a joint's), not in a plane.
//! - The drift of a closed contact between switches is the integrator's
//!   error (`g̈ = 0` holds exactly, `g` and `ġ` only as well as the steps
//!   keep them); at every switch the state is projected back onto the
//!   closed contacts (`g = 0`, `ġ = 0`, `v_t = 0` for stuck ones).

use core::fmt;

use nalgebra::{RealField, SMatrix, SVector};

use crate::model::Lagrangian;

mod admissible;
mod decide;
mod erased;
mod held;
mod lcp;
mod phase;
mod run;

pub use erased::Erased;
pub use phase::Phase;
pub use run::{ContactFailure, ContactResult, ContactTrajectory, Scene, integrate};

/// A model with `K` unilateral contacts on its `N` coordinates: gaps
/// `g(t, q) ≥ 0` and, where friction acts, slip velocities `v_t`.
///
/// `lagrangian!` implements it for every model with a `contacts:` section
/// (the language guide's "Contacts"), deriving the gap terms as a holonomic
/// constraint's (see [`Holonomic`](crate::model::constraints::Holonomic))
/// and the slip terms as a velocity constraint's; it may be written by
/// hand too.
pub trait Contacts<const N: usize, const K: usize>: Lagrangian<N> {
    /// Names of the contacts, for switches and errors.
    const CONTACTS: [&'static str; K];

    /// The gaps `g(t, q)`: positive apart, zero touching.
    fn gaps(&self, t: Self::Scalar, q: &SVector<Self::Scalar, N>) -> SVector<Self::Scalar, K>;

    /// `G(t, q) = ∂g/∂q`, `K × N`: the normal forces act along its rows.
    fn gap_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, K, N>;

    /// `ġ = G q̇ + ∂g/∂t`.
    fn gap_velocities(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, K>;

    /// `γ` with `g̈ = G q̈ + γ`.
    fn gap_bias(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, K>;

    /// `T(t, q)`, `K × N`, with the slip velocities `v_t = T q̇ + b(t, q)`:
    /// friction acts along its rows. Zero rows (the default) for
    /// frictionless contacts.
    fn slip_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, K, N> {
        let _ = (t, q);
        SMatrix::zeros()
    }

    /// The slip velocities `v_t = T q̇ + b`.
    fn slip_velocities(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, K> {
        let _ = (t, q, qdot);
        SVector::zeros()
    }

    /// `γ_t` with `v̇_t = T q̈ + γ_t`.
    fn slip_bias(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, K> {
        let _ = (t, q, qdot);
        SVector::zeros()
    }

    /// `T₂(t, q)`, `K × N`: the second rows of the slip vectors of the
    /// contacts whose friction acts in a plane ([`ContactLaw::in_plane`]),
    /// `v₂ = T₂ q̇ + b₂`, the contact point's velocity along a second unit
    /// tangent of the surface, orthogonal to the first. Zero rows (the
    /// default) for the others.
    fn second_slip_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, K, N> {
        let _ = (t, q);
        SMatrix::zeros()
    }

    /// The slip vectors' second components `v₂ = T₂ q̇ + b₂`.
    fn second_slip_velocities(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, K> {
        let _ = (t, q, qdot);
        SVector::zeros()
    }

    /// `γ₂` with `v̇₂ = T₂ q̈ + γ₂`.
    fn second_slip_bias(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SVector<Self::Scalar, K> {
        let _ = (t, q, qdot);
        SVector::zeros()
    }

    /// Each contact's restitution and friction.
    fn contact_laws(&self) -> [ContactLaw<Self::Scalar>; K];
}

/// What happens at one contact: its impacts and its friction.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactLaw<S> {
    /// Poisson's coefficient of restitution, `0 ≤ e ≤ 1` (0: plastic).
    pub restitution: S,
    /// The static friction coefficient `μ_s ≥ μ_k`: a stuck contact holds
    /// while `|F| ≤ μ_s N`.
    pub static_friction: S,
    /// The kinetic friction coefficient `μ_k ≥ 0`: a sliding contact feels
    /// `μ_k N` against its slip.
    pub kinetic_friction: S,
    /// A given normal force `N ≥ 0`, for friction that acts against a
    /// known load instead of a contact's reaction (a brake pad pressed by a
    /// known force, a bearing under a known load: friction in a joint).
    /// Such a contact has no gap (its rows of `g`, `G`, `ġ` and `γ` are not
    /// used): it always touches, never strikes, and only its friction
    /// switches, between sliding and stuck. `None`: the normal force is the
    /// reaction that keeps the gap non-negative.
    pub normal: Option<S>,
    /// Whether friction acts in a plane: the slip is a vector `(v_t, v₂)`
    /// (the contact point's velocity along two orthogonal unit tangents
    /// of the surface, the rows of [`Contacts::slip_jacobian`] and
    /// [`Contacts::second_slip_jacobian`]), and friction is isotropic in
    /// it: `−μ_k N v/|v|` while it slips, turning with the slip, and any
    /// force of length at most `μ_s N` while it sticks (the friction
    /// cone, a disc). `false`: along the one slip direction (planar).
    /// `lagrangian!` sets it for `slip: vector(u, v)`.
    pub in_plane: bool,
}

impl<S: RealField + Copy> ContactLaw<S> {
    /// A frictionless contact with restitution `e`.
    pub fn frictionless(restitution: S) -> Self {
        Self {
            restitution,
            static_friction: S::zero(),
            kinetic_friction: S::zero(),
            normal: None,
            in_plane: false,
        }
    }

    /// Friction against a given normal force `normal` (see
    /// [`normal`](Self::normal)), with static friction `μ_s` and kinetic
    /// friction `μ_k`; no gap, no impacts.
    pub fn given_normal(normal: S, static_friction: S, kinetic_friction: S) -> Self {
        Self {
            restitution: S::zero(),
            static_friction,
            kinetic_friction,
            normal: Some(normal),
            in_plane: false,
        }
    }

    /// With Coulomb friction `μ` (static and kinetic alike).
    pub fn with_friction(self, mu: S) -> Self {
        Self {
            static_friction: mu,
            kinetic_friction: mu,
            ..self
        }
    }

    /// With static friction `μ_s` and kinetic friction `μ_k`.
    pub fn with_static_and_kinetic(self, static_friction: S, kinetic_friction: S) -> Self {
        Self {
            static_friction,
            kinetic_friction,
            ..self
        }
    }

    /// With friction in the plane of a slip vector (see
    /// [`in_plane`](Self::in_plane)).
    pub fn in_plane(self) -> Self {
        Self {
            in_plane: true,
            ..self
        }
    }

    fn has_friction(&self) -> bool {
        self.static_friction > S::zero() || self.kinetic_friction > S::zero()
    }
}

/// The state of one contact between switches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Mode {
    /// Apart, or touching without force: no force.
    Open,
    /// Touching, frictionless: a normal force keeps `g̈ = 0`.
    Closed,
    /// Touching and slipping, `v_t` of the sign given (`true`: positive):
    /// kinetic friction against it.
    Sliding {
        /// Whether the slip velocity is positive.
        forward: bool,
    },
    /// Touching, not slipping: a friction force keeps `v̇_t = 0`.
    Stuck,
    /// Touching and slipping in the plane of its slip vector (a contact
    /// whose friction acts in a plane, [`ContactLaw::in_plane`]): kinetic
    /// friction against the slip, whose direction turns as the bodies
    /// move.
    Slipping,
}

impl Mode {
    /// Whether the contact carries a normal force.
    pub fn touching(self) -> bool {
        !matches!(self, Self::Open)
    }
}

/// Why a contact's mode changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Cause {
    /// The mode decided at the start of the run.
    Start,
    /// An impact: this contact arrived, or collided together with one
    /// that did.
    Impact,
    /// Its normal force reached zero.
    Release,
    /// Its slip velocity reached zero.
    SlideStopped,
    /// Its friction force reached `μ_s N`.
    StickLimit,
    /// Decided again together with another contact's switch.
    Coupled,
    /// Rebounds too short to resolve (see [impacts that
    /// accumulate](self#impacts-that-accumulate)) accumulated: the impact
    /// made plastic where they would have, the contact closed for good.
    Settled,
}

/// One switch of one contact: when, from which mode to which, and what it
/// took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Switch<S: RealField + Copy, const N: usize> {
    /// The time of the switch.
    pub t: S,
    /// The contact's index in [`Contacts::CONTACTS`].
    pub contact: usize,
    /// The contact's name.
    pub name: &'static str,
    /// Its mode before.
    pub from: Mode,
    /// Its mode after.
    pub to: Mode,
    /// Why.
    pub cause: Cause,
    /// At an impact: the normal and tangential impulses on this contact
    /// (restitution included), the tangential one along the slip's first
    /// row; zero otherwise.
    pub impulse: (S, S),
    /// At an impact: the tangential impulse along the second row of a
    /// slip vector ([`ContactLaw::in_plane`]); zero otherwise.
    pub second_impulse: S,
    /// At a switch to [`Mode::Slipping`]: the unit direction, in the slip
    /// plane's two components, of the slip the contact sets off in (its
    /// friction acts against it, and turns with the slip from then on);
    /// zero otherwise.
    pub slip_direction: (S, S),
    /// At an impact: the kinetic energy the whole impact took, recorded on
    /// every contact's switch of that impact (count it once per impact);
    /// zero otherwise.
    pub energy_lost: S,
    /// The positions after the switch (projected onto the touching
    /// contacts).
    pub q: SVector<S, N>,
    /// The velocities after the switch.
    pub qdot: SVector<S, N>,
}

/// The contact forces at a state: each contact's normal force `N` (along
/// its row of `G`) and friction force `F` (along its row of `T`), zero for
/// open ones.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactForces<S: RealField + Copy, const N: usize, const K: usize> {
    /// The normal forces, non-negative.
    pub normal: SVector<S, K>,
    /// The friction forces along the slip directions (a slip vector's
    /// first rows).
    pub friction: SVector<S, K>,
    /// The friction forces along the slip vectors' second rows (zero for
    /// a slip along one direction).
    pub second_friction: SVector<S, K>,
    /// All of them as generalized forces, `Gᵀ N + Tᵀ F + T₂ᵀ F₂`: what they
    /// add to the model's `f`.
    pub generalized: SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize, const K: usize> ContactForces<S, N, K> {
    pub(crate) fn zero() -> Self {
        Self {
            normal: SVector::zeros(),
            friction: SVector::zeros(),
            second_friction: SVector::zeros(),
            generalized: SVector::zeros(),
        }
    }
}

/// How a contact run decides what touches, and what counts as too short to
/// resolve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSettings<S> {
    /// A gap at most this is touching (and below its negative the start
    /// is refused as penetrating). By default `1e-9`, in the gap's units.
    pub gap_tolerance: S,
    /// A gap rate or slip velocity within this of zero is at rest. By
    /// default `1e-9`, in the gaps' units per unit time.
    pub velocity_tolerance: S,
    /// A rebound whose flight would be shorter than this is flown out to
    /// where its rebounds accumulate, and settles there (see [impacts
    /// that accumulate](self#impacts-that-accumulate)). By default
    /// `1e-10`, in the model's time units.
    pub shortest_flight: S,
    /// The slip speed below which the friction of a contact slipping in
    /// a plane ([`ContactLaw::in_plane`]) leans on the direction its slip
    /// set off in, `d`: it acts against `v + s d` (`s` this speed, `v`
    /// the slip), not `v/|v|`, which has no direction at rest. A slip that
    /// keeps its direction (from rest along `d`, or turning at no point)
    /// feels exactly Coulomb's friction; one that turns, friction turned
    /// towards `d` by at most `s/|v|` radians. It bounds the stiffness of
    /// the slip's turning, `μ N / (m |v|)` for Coulomb's law, at `μ N /
    /// (m s)`: a slip setting off with no acceleration (`μ_s = μ_k`) would
    /// otherwise take steps as short as `|v| / (μ g)`. By default `1e-6`,
    /// in the slips' units per unit time.
    pub direction_speed: S,
}

impl<S: RealField + Copy> Default for ContactSettings<S> {
    fn default() -> Self {
        let c = nalgebra::convert::<f64, S>;
        Self {
            gap_tolerance: c(1e-9),
            velocity_tolerance: c(1e-9),
            shortest_flight: c(1e-10),
            direction_speed: c(1e-6),
        }
    }
}

/// A contact run's own failures, each at a time and state.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactError<S: RealField + Copy, const N: usize> {
    /// The run loop's own failure (a step size underflow, a NaN, …).
    Integration(crate::error::IntegrationError<S, N>),
    /// No assignment of modes satisfies the contact conditions: the
    /// complementarity problem has no solution (Lemke's method ended on a
    /// ray, or cycled). With friction, Painlevé's paradox.
    NoConsistentMode {
        /// Time.
        t: S,
        /// Positions.
        q: SVector<S, N>,
        /// Velocities.
        qdot: SVector<S, N>,
        /// Whether at an impact (velocity level) or between them.
        at_impact: bool,
    },
    /// The touching contacts' forces are not determined: their rows of `G`
    /// (and of `T` for stuck ones) are dependent in the metric of `M`, or
    /// `M` itself is singular, or the model's own constraints are
    /// dependent.
    DependentContacts {
        /// Time.
        t: S,
        /// Positions.
        q: SVector<S, N>,
        /// Velocities.
        qdot: SVector<S, N>,
    },
    /// The contacts' modes undo each other: more than 64 switches in a row
    /// at the same time, without time passing.
    Chattering {
        /// Time.
        t: S,
        /// Positions.
        q: SVector<S, N>,
        /// Velocities.
        qdot: SVector<S, N>,
        /// How many switches fell on `t`.
        switches: usize,
    },
    /// The start is inside a contact: a gap below minus the gap tolerance.
    Penetrating {
        /// The contact.
        contact: &'static str,
        /// Its gap.
        gap: S,
    },
    /// A setting or law out of range.
    InvalidSetting {
        /// Which.
        setting: &'static str,
        /// Its value.
        value: S,
        /// What it must be.
        requirement: &'static str,
    },
}

impl<S: RealField + Copy, const N: usize> fmt::Display for ContactError<S, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use crate::error::Row;
        match self {
            Self::Integration(e) => write!(f, "{e}"),
            Self::NoConsistentMode {
                t,
                q,
                qdot,
                at_impact,
            } => {
                write!(
                    f,
                    "no consistent contact mode {} at t = {t:?} (q = {}, q̇ = {}): the complementarity \
                 problem of the touching contacts has no solution (with friction, Painlevé's \
                 paradox)",
                    if *at_impact {
                        "for the impact"
                    } else {
                        "between impacts"
                    },
                    Row(q),
                    Row(qdot)
                )
            }
            Self::DependentContacts { t, q, qdot } => write!(
                f,
                "the touching contacts' forces are not determined at t = {t:?} (q = {}, q̇ = {}): \
                 their directions are dependent, or M is singular, or the model's own constraints \
                 are dependent",
                Row(q),
                Row(qdot)
            ),
            Self::Chattering {
                t,
                q,
                qdot,
                switches,
            } => write!(
                f,
                "the contacts switched {switches} times at t = {t:?} (q = {}, q̇ = {}) without time \
                 passing: their modes undo each other",
                Row(q),
                Row(qdot)
            ),
            Self::Penetrating { contact, gap } => write!(
                f,
                "the start is inside contact `{contact}`: its gap is {gap:?}, below minus the gap \
                 tolerance"
            ),
            Self::InvalidSetting {
                setting,
                value,
                requirement,
            } => write!(
                f,
                "contact setting `{setting}` is {value:?}; it must be {requirement}"
            ),
        }
    }
}

impl<S: RealField + Copy, const N: usize> std::error::Error for ContactError<S, N> {}
