//! A contact run: the start decided, the switches wired as events of the
//! run loops every model runs through, and the forces of every sample.

use nalgebra::{ComplexField, RealField, SVector};

use super::decide::{Accumulation, Impulse, impact, modes, project, record, touching};
use super::erased::Erased;
use super::phase::{Phase, Slips, Terms, accelerations};
use super::{Cause, ContactError, ContactForces, ContactSettings, Contacts, Mode, Switch};
use crate::driver::invalid;
use crate::driver::run::integrate_segments;
use crate::dynamics::start::StartOnManifold;
use crate::error::{IntegrationError, ResetFailure};
use crate::events::{Event, Events, RunData};
use crate::integrators::StepMethod;
use crate::model::Lagrangian;
use crate::stepper::Stepper;
use crate::trajectory::{State, Stats, Trajectory};

/// A contact run's result: its trajectory, every switch, and the contact
/// forces and modes at every sample.
#[derive(Debug, Clone)]
pub struct ContactTrajectory<S: RealField + Copy, const N: usize, const K: usize> {
    trajectory: Trajectory<S, N>,
    switches: Vec<Switch<S, N>>,
    modes: Vec<[Mode; K]>,
    forces: Vec<ContactForces<S, N, K>>,
}

impl<S: RealField + Copy, const N: usize, const K: usize> ContactTrajectory<S, N, K> {
    /// The samples (with the run's events: every switch's event record).
    pub fn trajectory(&self) -> &Trajectory<S, N> {
        &self.trajectory
    }

    /// Every switch in time order: impacts (with their impulses and the
    /// energy they took), contacts opening, sticking, slipping.
    pub fn switches(&self) -> &[Switch<S, N>] {
        &self.switches
    }

    /// The contacts' modes at each sample (at a sample on a switch's time,
    /// the modes before it).
    pub fn modes(&self) -> &[[Mode; K]] {
        &self.modes
    }

    /// The contact forces at each sample.
    pub fn forces(&self) -> &[ContactForces<S, N, K>] {
        &self.forces
    }

    /// The trajectory apart from the rest.
    pub fn into_trajectory(self) -> Trajectory<S, N> {
        self.trajectory
    }
}

/// A failed contact run: what went wrong, and everything up to it.
#[derive(Debug, Clone)]
pub struct ContactFailure<S: RealField + Copy, const N: usize, const K: usize> {
    /// What went wrong, where, and in which state.
    pub error: ContactError<S, N>,
    /// The samples, switches and forces before the failure.
    pub trajectory: ContactTrajectory<S, N, K>,
}

impl<S: RealField + Copy, const N: usize, const K: usize> core::fmt::Display
    for ContactFailure<S, N, K>
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "{} (after {} samples and {} switches)",
            self.error,
            self.trajectory.trajectory.len(),
            self.trajectory.switches.len()
        )
    }
}

impl<S: RealField + Copy, const N: usize, const K: usize> std::error::Error
    for ContactFailure<S, N, K>
{
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// What [`integrate`] returns.
pub type ContactResult<S, const N: usize, const K: usize> =
    Result<ContactTrajectory<S, N, K>, Box<ContactFailure<S, N, K>>>;

/// Integrates a model with contacts from `(t0, q0, q̇0)` through `times`
/// with `method`: the contacts' modes decided at the start and at every
/// switch, each switch located as an event of the method's run loop (see the
/// [module documentation](super)).
///
/// ```
/// use lagrange_runtime::contact::{self, ContactLaw, ContactSettings, Contacts, Mode};
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
/// use lagrange_runtime::prelude::*;
///
/// /// A ball in one dimension, `z̈ = −g`, above a floor at `z = 0`.
/// struct Ball;
/// impl Lagrangian<1> for Ball {
///     type Scalar = f64;
///     const COORDINATES: [&'static str; 1] = ["z"];
///     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
///         SMatrix::<f64, 1, 1>::new(1.0)
///     }
///     fn forcing(&self, _t: f64, _q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
///         Vector1::new(-9.81)
///     }
///     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
///         0.5 * qd[0] * qd[0]
///     }
///     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
///         9.81 * q[0]
///     }
/// }
/// impl Contacts<1, 1> for Ball {
///     const CONTACTS: [&'static str; 1] = ["floor"];
///     fn gaps(&self, _t: f64, q: &SVector<f64, 1>) -> SVector<f64, 1> { *q }
///     fn gap_jacobian(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
///         SMatrix::<f64, 1, 1>::new(1.0)
///     }
///     fn gap_velocities(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> SVector<f64, 1> { *qd }
///     fn gap_bias(&self, _t: f64, _q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
///         Vector1::new(0.0)
///     }
///     fn contact_laws(&self) -> [ContactLaw<f64>; 1] { [ContactLaw::frictionless(0.5)] }
/// }
///
/// // Dropped from 1 m with restitution 1/2: the bounces accumulate and the
/// // ball comes to rest at t₁ (1 + e)/(1 − e) = 3 t₁, then lies on the floor.
/// let run = contact::integrate(
///     &Dop853::new().rtol(1e-12).atol(1e-12), &Ball, 0.0,
///     Vector1::new(1.0), Vector1::new(0.0), &[2.0], ContactSettings::default(),
/// )?;
/// let t1 = (2.0 / 9.81f64).sqrt();
/// let rest = run.switches().last().unwrap();
/// assert_eq!(rest.to, Mode::Closed);
/// assert!((rest.t - 3.0 * t1).abs() < 1e-9);
/// assert!((run.forces()[0].normal[0] - 9.81).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn integrate<I, L, const N: usize, const K: usize>(
    method: &I,
    model: &L,
    t0: L::Scalar,
    q0: SVector<L::Scalar, N>,
    qdot0: SVector<L::Scalar, N>,
    times: &[L::Scalar],
    settings: ContactSettings<L::Scalar>,
) -> ContactResult<L::Scalar, N, K>
where
    I: StepMethod<L::Scalar>,
    L: Contacts<N, K> + Sync,
{
    match Scene::new(model, t0, q0, qdot0, settings) {
        Ok(scene) => scene.integrate(method, times),
        Err(error) => Err(Box::new(ContactFailure {
            error,
            trajectory: ContactTrajectory {
                trajectory: Trajectory::with_capacity(0),
                switches: Vec::new(),
                modes: Vec::new(),
                forces: Vec::new(),
            },
        })),
    }
}

/// A model with contacts at its start, ready to run: the start checked
/// and decided (an impact where a touching contact approaches, the modes),
/// and the switches wired as events. [`integrate`](Scene::integrate) runs
/// it through sample times, as [`integrate`](super::integrate) does;
/// [`stepper`](Scene::stepper) makes a [`Stepper`] that advances it frame
/// by frame through the same loop, its switches located in the frame they
/// fall in.
///
/// A scene holds its start; each run (an `integrate`, a stepper) starts
/// from it and owns its modes and switches from then on, as plain data of
/// the run: several runs of one scene, in turn or side by side, do not
/// touch each other.
///
/// ```
/// use lagrange_runtime::contact::{Cause, ContactLaw, ContactSettings, Contacts, Scene};
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
/// use lagrange_runtime::prelude::*;
/// # struct Ball;
/// # impl Lagrangian<1> for Ball {
/// #     type Scalar = f64;
/// #     const COORDINATES: [&'static str; 1] = ["z"];
/// #     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> { SMatrix::<f64, 1, 1>::new(1.0) }
/// #     fn forcing(&self, _t: f64, _q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> { Vector1::new(-9.81) }
/// #     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 { 0.5 * qd[0] * qd[0] }
/// #     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 { 9.81 * q[0] }
/// # }
/// # impl Contacts<1, 1> for Ball {
/// #     const CONTACTS: [&'static str; 1] = ["floor"];
/// #     fn gaps(&self, _t: f64, q: &SVector<f64, 1>) -> SVector<f64, 1> { *q }
/// #     fn gap_jacobian(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> { SMatrix::<f64, 1, 1>::new(1.0) }
/// #     fn gap_velocities(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> SVector<f64, 1> { *qd }
/// #     fn gap_bias(&self, _t: f64, _q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> { Vector1::new(0.0) }
/// #     fn contact_laws(&self) -> [ContactLaw<f64>; 1] { [ContactLaw::frictionless(0.5)] }
/// # }
/// // The ball dropped from 1 m, frame by frame at 60 Hz.
/// let scene = Scene::new(&Ball, 0.0, Vector1::new(1.0), Vector1::new(0.0), ContactSettings::default())?;
/// let mut stepper = scene.stepper(Dopri5::new().rtol(1e-10).atol(1e-10))?;
/// let mut first_bounce_frame = None;
/// for frame in 1..=60 {
///     stepper.advance(1.0 / 60.0)?;
///     if first_bounce_frame.is_none() && !stepper.events().is_empty() {
///         first_bounce_frame = Some(frame);
///     }
/// }
/// // It lands at √(2/g) = 0.4515 s: in the 28th frame, (0.45, 0.4667].
/// assert_eq!(first_bounce_frame, Some(28));
/// assert_eq!(stepper.switches()[0].cause, Cause::Impact);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Scene<'a, S: RealField + Copy, const N: usize, const K: usize> {
    model: Erased<'a, S, N, K>,
    settings: ContactSettings<S>,
    events: Events<'a, S, N>,
    t0: S,
    /// The state after the start's decision.
    start: (SVector<S, N>, SVector<S, N>),
    start_modes: [Mode; K],
    start_directions: [(S, S); K],
    start_switches: Vec<Switch<S, N>>,
}

impl<'a, S: RealField + Copy, const N: usize, const K: usize> Scene<'a, S, N, K> {
    /// `model` at `(t0, q0, q̇0)`: the settings and laws checked, the start
    /// refused if it penetrates a contact, an impact where a touching
    /// contact approaches, and the modes decided.
    pub fn new<L>(
        model: &'a L,
        t0: S,
        q0: SVector<S, N>,
        qdot0: SVector<S, N>,
        settings: ContactSettings<S>,
    ) -> Result<Self, ContactError<S, N>>
    where
        L: Contacts<N, K, Scalar = S> + Sync,
    {
        validate(model, &settings)?;
        crate::model::ready(model).map_err(|invalid| {
            ContactError::Integration(IntegrationError::InvalidInput(invalid))
        })?;
        if !t0.is_finite() {
            let invalid = crate::error::InvalidInput::NonFiniteStartTime { t0 };
            return Err(ContactError::Integration(IntegrationError::InvalidInput(
                invalid,
            )));
        }
        for (i, coordinate) in L::COORDINATES.into_iter().enumerate() {
            let invalid = if !q0[i].is_finite() {
                crate::error::InvalidInput::NonFiniteInitialPosition {
                    coordinate,
                    value: q0[i],
                }
            } else if !qdot0[i].is_finite() {
                crate::error::InvalidInput::NonFiniteInitialVelocity {
                    coordinate,
                    value: qdot0[i],
                }
            } else {
                continue;
            };
            return Err(ContactError::Integration(IntegrationError::InvalidInput(
                invalid,
            )));
        }
        // A model with constraints of its own starts on them, as every
        // constrained run does: `(q0, q̇0)` projected, or refused, as the
        // model's settings say (the constraints' `InitialConditions`).
        let (q0, qdot0) = match model.visit_constraints(StartOnManifold {
            t0,
            q0,
            qdot0,
            stats: &mut Stats::default(),
        }) {
            None => (q0, qdot0),
            Some(Ok(start)) => start,
            Some(Err(error)) => return Err(ContactError::Integration(error)),
        };
        let gaps = model.gaps(t0, &q0);
        let laws = model.contact_laws();
        for i in 0..K {
            if laws[i].normal.is_none() && gaps[i] < -settings.gap_tolerance {
                return Err(ContactError::Penetrating {
                    contact: L::CONTACTS[i],
                    gap: gaps[i],
                });
            }
        }
        // The start: an impact if a touching contact approaches, then the
        // modes decided.
        let erased = Erased::new(model);
        let mut start_switches = Vec::new();
        let mut accumulating = [None; K];
        let (start, start_modes, start_directions) = decide_switch(
            &erased,
            &settings,
            t0,
            (q0, qdot0),
            (&[Mode::Open; K], &[None; K], &[(S::zero(), S::zero()); K]),
            (Cause::Start, false),
            (&mut start_switches, &mut accumulating),
        )?;
        let first = ContactRun {
            modes: start_modes,
            directions: start_directions,
            switches: start_switches.clone(),
            streak: (t0, 0),
            accumulating,
        };
        let events = events(erased, settings, first);
        Ok(Self {
            model: erased,
            settings,
            events,
            t0,
            start,
            start_modes,
            start_directions,
            start_switches,
        })
    }

    /// Integrates the scene from its start through `times` with `method`
    /// (see [`integrate`](super::integrate)). Each run is the run's own:
    /// its modes and switches are data of the run, not of the scene.
    pub fn integrate<M: StepMethod<S>>(&self, method: &M, times: &[S]) -> ContactResult<S, N, K> {
        let (q0, qdot0) = self.start;
        let mut data = self.events.fresh_data();
        let run = match method.walker::<N>() {
            Ok(walker) => integrate_segments(
                walker,
                &self.first_phase(),
                (self.t0, q0, qdot0),
                times,
                &self.events,
                next_phase,
                Some(&mut data),
            ),
            Err(error) => Err(invalid(error)),
        };
        let switches = match data.downcast::<ContactRun<S, N, K>>() {
            Ok(run) => run.switches,
            Err(_) => self.start_switches.clone(),
        };
        let model = &self.model;
        match run {
            Ok(trajectory) => Ok(results(model, trajectory, switches, self.first_phase())),
            Err(failure) => Err(Box::new(ContactFailure {
                error: contact_error(failure.error),
                trajectory: results(model, failure.trajectory, switches, self.first_phase()),
            })),
        }
    }

    /// A [`Stepper`] that advances the scene frame by frame with `method`,
    /// from the scene's start, watching the switches:
    /// [`Stepper::events`] lists the switches' events of each call,
    /// [`Stepper::switches`] all the switches of its run so far,
    /// [`Stepper::modes`] the modes now. Each stepper's run is its own:
    /// two steppers of one scene, or a stepper and an
    /// [`integrate`](Self::integrate), do not touch each other's modes.
    /// A switch that cannot be decided ends the stepper's call with
    /// [`IntegrationError::ResetFailed`], its reason a
    /// [`ResetFailure`](crate::error::ResetFailure) (no consistent mode,
    /// dependent contacts, chattering); forces that are not determined
    /// between switches, with
    /// [`IntegrationError::UndeterminedContactForces`].
    pub fn stepper<M: StepMethod<S>>(
        &self,
        method: M,
    ) -> Result<Stepper<'_, Phase<'a, S, N, K>, M, N>, ContactError<S, N>> {
        let (q0, qdot0) = self.start;
        Stepper::new(self.first_phase(), method, self.t0, q0, qdot0)
            .and_then(|stepper| stepper.with_events(&self.events))
            .map(|stepper| stepper.with_segments(next_phase))
            .map_err(ContactError::Integration)
    }

    /// The model in the start's modes: what every run begins with.
    fn first_phase(&self) -> Phase<'a, S, N, K> {
        Phase {
            model: self.model,
            modes: self.start_modes,
            slips: Slips {
                directions: self.start_directions,
                lead: self.settings.direction_speed,
            },
        }
    }

    /// The switches decided at the start (an impact where a touching
    /// contact approached, the modes), in order: every run's first. A
    /// run's own are in its [`ContactTrajectory::switches`] or its
    /// stepper's [`Stepper::switches`].
    pub fn start_switches(&self) -> &[Switch<S, N>] {
        &self.start_switches
    }

    /// The contacts' modes decided at the start: every run's first.
    pub fn start_modes(&self) -> [Mode; K] {
        self.start_modes
    }

    /// The settings the scene runs with.
    pub fn settings(&self) -> &ContactSettings<S> {
        &self.settings
    }
}

/// What a contact run carries from switch to switch: the data its
/// switches' events read and their resets change (`Events::keeping`),
/// owned by the run.
#[derive(Clone)]
pub(crate) struct ContactRun<S: RealField + Copy, const N: usize, const K: usize> {
    /// The contacts' modes now.
    modes: [Mode; K],
    /// Where the friction of each contact slipping in a plane points
    /// (`Slips::directions`).
    directions: [(S, S); K],
    /// Every switch so far, the start's first.
    switches: Vec<Switch<S, N>>,
    /// The time of the last switch and how many switches in a row fell on
    /// it: the guard against modes that undo each other.
    streak: (S, usize),
    /// The open contacts flying out a rebound too short to resolve, to
    /// settle where their rebounds accumulate.
    accumulating: [Option<Accumulation<S>>; K],
}

impl<S: RealField + Copy, const N: usize, const K: usize> ContactRun<S, N, K> {
    /// The slip directions now, leaned on below `lead` (the settings'
    /// `direction_speed`).
    fn slips(&self, lead: S) -> Slips<S, K> {
        Slips {
            directions: self.directions,
            lead,
        }
    }
}

/// The phase a run goes on with after a switch: the model in the run's
/// new modes.
fn next_phase<'a, S: RealField + Copy, const N: usize, const K: usize>(
    phase: &Phase<'a, S, N, K>,
    data: &RunData,
) -> Option<Phase<'a, S, N, K>> {
    let run = data.downcast_ref::<ContactRun<S, N, K>>()?;
    Some(Phase {
        model: phase.model,
        modes: run.modes,
        slips: Slips {
            directions: run.directions,
            lead: phase.slips.lead,
        },
    })
}

/// Four events per contact, each a switch when it crosses zero falling:
/// its arrival, its release, its slide stopping and its stick limit (see
/// [the table](super#modes-and-switches)); each a constant one while the
/// contact's mode does not watch it. Each run starts from `first`.
fn events<'a, S: RealField + Copy, const N: usize, const K: usize>(
    model: Erased<'a, S, N, K>,
    settings: ContactSettings<S>,
    first: ContactRun<S, N, K>,
) -> Events<'a, S, N> {
    // The run's Zeno guard is off: impacts that accumulate settle into a
    // persistent contact instead (`shortest_flight`).
    let mut events = Events::new()
        .min_separation(nalgebra::zero())
        .keeping(first);
    let one = nalgebra::one::<S>;
    let lead = settings.direction_speed;
    for i in 0..K {
        let name = model.names[i];
        let switch = |cause: Cause| {
            move |run: &mut ContactRun<S, N, K>, t, q: &SVector<S, N>, qdot: &SVector<S, N>| {
                switch(model, &settings, run, (i, cause), t, (*q, *qdot))
            }
        };
        // The gap, looking one time unit ahead while it opens: `g + max(ġ,
        // 0)` equals `g` while the contact approaches, so it crosses zero
        // where the contact arrives, and it is positive from the start of
        // a rebound on, when `g` itself is zero: a bounce shorter than a
        // step is not lost to an unarmed start.
        let arrival = move |run: &ContactRun<S, N, K>,
                            t,
                            q: &SVector<S, N>,
                            qdot: &SVector<S, N>| match run.modes[i] {
            Mode::Open => {
                let gap = model.gaps(t, q)[i];
                let rate = model.gap_velocities(t, q, qdot)[i];
                match run.accumulating[i] {
                    // Its rebounds accumulate: through zero where they do,
                    // or where it goes in deeper than their flight by the
                    // gap tolerance.
                    Some(accumulation) => (accumulation.at - t).min(accumulation.ahead(
                        gap,
                        rate,
                        settings.gap_tolerance,
                    )),
                    None => gap + rate.max(nalgebra::zero()),
                }
            }
            _ => one(),
        };
        // A given normal force never releases.
        let given = model.contact_laws()[i].normal.is_some();
        let release =
            move |run: &ContactRun<S, N, K>, t, q: &SVector<S, N>, qdot: &SVector<S, N>| {
                if run.modes[i].touching() && !given {
                    let phase = Phase {
                        model,
                        modes: run.modes,
                        slips: run.slips(lead),
                    };
                    phase.solve(t, q, qdot).map_or(nan(), |(_, f)| f.normal[i])
                } else {
                    one()
                }
            };
        let slide_stop = move |run: &ContactRun<S, N, K>,
                               t,
                               q: &SVector<S, N>,
                               qdot: &SVector<S, N>| match run.modes[i] {
            Mode::Sliding { forward } => {
                let v = model.slip_velocities(t, q, qdot)[i];
                if forward { v } else { -v }
            }
            // Along the direction it set off in: through zero where it
            // stops, and where it has turned by a right angle (a switch
            // that finds it slipping still, and goes on along its new
            // direction).
            Mode::Slipping => {
                let d = run.directions[i];
                model.slip_velocities(t, q, qdot)[i] * d.0
                    + model.second_slip_velocities(t, q, qdot)[i] * d.1
            }
            _ => one(),
        };
        let mu_s = model.contact_laws()[i].static_friction;
        let in_plane = model.contact_laws()[i].in_plane;
        let stick_limit = move |run: &ContactRun<S, N, K>,
                                t,
                                q: &SVector<S, N>,
                                qdot: &SVector<S, N>| match run.modes[i] {
            Mode::Stuck => {
                let phase = Phase {
                    model,
                    modes: run.modes,
                    slips: run.slips(lead),
                };
                phase.solve(t, q, qdot).map_or(nan(), |(_, f)| {
                    mu_s * f.normal[i] - friction_size(&f, i, in_plane)
                })
            }
            _ => one(),
        };
        events = events
            .with(
                Event::keeping(name, arrival)
                    .falling()
                    .try_reset_keeping(switch(Cause::Impact)),
            )
            .with(
                Event::keeping(name, release)
                    .falling()
                    .try_reset_keeping(switch(Cause::Release)),
            )
            .with(
                Event::keeping(name, slide_stop)
                    .falling()
                    .try_reset_keeping(switch(Cause::SlideStopped)),
            )
            .with(
                Event::keeping(name, stick_limit)
                    .falling()
                    .try_reset_keeping(switch(Cause::StickLimit)),
            );
    }
    events
}

/// How close to its cone's limit, relative to it, a stuck contact slides
/// with one whose stick limit was reached: friction shared in proportion
/// to the cones reaches every limit at one time, located to rounding
/// (`1e-9`, the velocity tolerance's share, well above the rounding of
/// the forces' solve and well below any margin a contact that keeps its
/// hold has at that time).
const AT_THE_LIMIT: f64 = 1e-9;

/// The most switches in a row at one time before the run is stopped as
/// chattering: a scene's simultaneous switches are a few per contact.
const MAX_SWITCHES_AT_ONCE: usize = 64;

/// The size of contact `i`'s friction force: its one component, or the
/// length of the two of a slip vector's.
fn friction_size<S: RealField + Copy, const N: usize, const K: usize>(
    f: &ContactForces<S, N, K>,
    i: usize,
    in_plane: bool,
) -> S {
    if in_plane {
        (f.friction[i] * f.friction[i] + f.second_friction[i] * f.second_friction[i]).sqrt()
    } else {
        f.friction[i].abs()
    }
}

fn nan<S: RealField + Copy>() -> S {
    S::zero() / S::zero()
}

/// The settings and laws out of range, before any work.
fn validate<L, const N: usize, const K: usize>(
    model: &L,
    settings: &ContactSettings<L::Scalar>,
) -> Result<(), ContactError<L::Scalar, N>>
where
    L: Contacts<N, K>,
{
    let bad = |setting, value, requirement| {
        Err(ContactError::InvalidSetting {
            setting,
            value,
            requirement,
        })
    };
    let zero = nalgebra::zero::<L::Scalar>();
    for (setting, value) in [
        ("gap_tolerance", settings.gap_tolerance),
        ("velocity_tolerance", settings.velocity_tolerance),
        ("shortest_flight", settings.shortest_flight),
        ("direction_speed", settings.direction_speed),
    ] {
        if !(value.is_finite() && value >= zero) {
            return bad(setting, value, "non-negative and finite");
        }
    }
    for law in model.contact_laws() {
        if !(law.restitution >= zero && law.restitution <= nalgebra::one::<L::Scalar>()) {
            return bad("restitution", law.restitution, "between 0 and 1");
        }
        if !(law.kinetic_friction.is_finite() && law.kinetic_friction >= zero) {
            return bad(
                "kinetic_friction",
                law.kinetic_friction,
                "non-negative and finite",
            );
        }
        if !(law.static_friction.is_finite() && law.static_friction >= law.kinetic_friction) {
            return bad(
                "static_friction",
                law.static_friction,
                "finite and at least the kinetic friction",
            );
        }
        if let Some(normal) = law.normal {
            if !(normal.is_finite() && normal >= zero) {
                return bad("normal", normal, "non-negative and finite");
            }
            if law.in_plane {
                return bad(
                    "in_plane",
                    normal,
                    "false for a contact with a given normal force (its friction acts along one \
                     slip velocity, a joint's)",
                );
            }
        }
    }
    Ok(())
}

/// The decision at a switch: an impact where a touching contact approaches
/// (for an arrival and at the start), the modes decided, the state
/// projected onto them, and the switches recorded.
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
fn decide_switch<S: RealField + Copy, const N: usize, const K: usize>(
    model: &Erased<'_, S, N, K>,
    settings: &ContactSettings<S>,
    t: S,
    (q, mut qdot): (SVector<S, N>, SVector<S, N>),
    (from, forced, hints): (&[Mode; K], &[Option<Mode>; K], &[(S, S); K]),
    (cause, settle): (Cause, bool),
    (switches, accumulating): (&mut Vec<Switch<S, N>>, &mut [Option<Accumulation<S>>; K]),
) -> Result<(State<S, N>, [Mode; K], [(S, S); K]), ContactError<S, N>> {
    let mut impulses = None;
    let mut energy_lost = nalgebra::zero::<S>();
    let mut settled = false;
    let mut short = [None; K];
    // An impact wherever a touching contact approaches: at an arrival,
    // at the start, and after any other switch that leaves one doing so;
    // plastic where `settle` (a contact's rebounds accumulated).
    if let Some((after, impulse, plastic, cut)) =
        impact(model, settings, (t, &q, &qdot), from, settle)?
    {
        energy_lost = model.kinetic_energy(t, &q, &qdot) - model.kinetic_energy(t, &q, &after);
        qdot = after;
        impulses = Some(impulse);
        settled = plastic;
        short = cut;
    }
    // The contacts an impact struck are decided by their rates after it,
    // not held; so are those with a given normal force, whose slip the
    // impact may have set going (a stuck one sticks again only if its
    // slip velocity is at rest).
    let laws = model.contact_laws();
    let held: [Mode; K] = core::array::from_fn(|i| match impulses {
        Some(p) if p[i].0 != nalgebra::zero::<S>() || laws[i].normal.is_some() => Mode::Open,
        _ => from[i],
    });
    // Where the friction of a contact slipping in a plane points: its
    // slip's direction where it slips, else the direction it is forced to
    // set off in (`hints`: against its friction at its stick limit).
    let slip = model.slip_velocities(t, &q, &qdot);
    let slip2 = model.second_slip_velocities(t, &q, &qdot);
    // A slip at rest (within the velocity tolerance) has no direction of
    // its own: its rounding would give one at random.
    let unit = |i: usize| {
        let length = (slip[i] * slip[i] + slip2[i] * slip2[i]).sqrt();
        (length > settings.velocity_tolerance).then(|| (slip[i] / length, slip2[i] / length))
    };
    let mut directions: [(S, S); K] = core::array::from_fn(|i| {
        if laws[i].in_plane {
            unit(i).unwrap_or(hints[i])
        } else {
            (S::zero(), S::zero())
        }
    });
    let slips = Slips {
        directions,
        lead: settings.direction_speed,
    };
    let (to, from_rest) = modes(model, settings, (t, &q, &qdot), (&held, forced, &slips))?;
    // A contact that sets off from rest: the direction the decision gave
    // it (against its friction there), or the one it was forced in.
    for i in (0..K).filter(|&i| to[i] == Mode::Slipping) {
        let speed = (slip[i] * slip[i] + slip2[i] * slip2[i]).sqrt();
        if speed <= settings.velocity_tolerance && from_rest[i] != (S::zero(), S::zero()) {
            directions[i] = from_rest[i];
        }
    }
    // A rebound below the velocity tolerance closes the contact too: the
    // impact settled it.
    let settled_at =
        |i: usize| settled || (to[i].touching() && laws[i].restitution > nalgebra::zero::<S>());
    let state =
        project(model, &to, t, (q, qdot)).ok_or(ContactError::DependentContacts { t, q, qdot })?;
    // A struck contact flies out its short rebound if it leaves; every
    // other keeps flying its own out while it is open.
    for i in 0..K {
        let struck = impulses.is_some_and(|p: [Impulse<S>; K]| p[i].0 != nalgebra::zero::<S>());
        if struck || to[i] != Mode::Open {
            accumulating[i] = short[i].filter(|_| to[i] == Mode::Open);
        }
    }
    let touch = touching(model, settings, (t, &q), from);
    record(
        switches,
        &model.names,
        (t, state.0, state.1),
        (from, &to, &directions),
        |i| {
            let struck = impulses.is_some_and(|p: [Impulse<S>; K]| p[i].0 != nalgebra::zero::<S>());
            match cause {
                _ if struck && settled_at(i) => Cause::Settled,
                _ if struck => Cause::Impact,
                Cause::Start => Cause::Start,
                _ if forced[i].is_some() => cause,
                Cause::SlideStopped if touch[i] && from[i] != to[i] => cause,
                _ => Cause::Coupled,
            }
        },
        impulses.as_ref(),
        energy_lost,
    );
    Ok((state, to, directions))
}

/// An event's reset: the switch of contact `i` for `cause` decided, the
/// run's modes changed and the switch recorded, the state after it; why
/// not, where it cannot be decided.
fn switch<S: RealField + Copy, const N: usize, const K: usize>(
    model: Erased<'_, S, N, K>,
    settings: &ContactSettings<S>,
    run: &mut ContactRun<S, N, K>,
    (i, cause): (usize, Cause),
    t: S,
    state: (SVector<S, N>, SVector<S, N>),
) -> Result<State<S, N>, ResetFailure> {
    let from = run.modes;
    run.streak = if run.streak.1 > 0 && run.streak.0 == t {
        (t, run.streak.1 + 1)
    } else {
        (t, 1)
    };
    if run.streak.1 > MAX_SWITCHES_AT_ONCE {
        return Err(ResetFailure::Chattering {
            switches: run.streak.1,
        });
    }
    let mut forced = [None; K];
    let mut hints = [(S::zero(), S::zero()); K];
    match cause {
        Cause::Release => forced[i] = Some(Mode::Open),
        Cause::StickLimit => {
            // It slides the way its friction force was holding it from, and
            // so does every stuck contact at its cone's limit with it: the
            // contacts that share a friction reach their limits together
            // (see `phase::share_friction`), and the one that slides first
            // leaves the others more to carry, not less. Decided one by
            // one, the others would be held at a limit they cannot keep.
            // A contact whose friction acts in a plane sets off against
            // its friction force there.
            let phase = Phase {
                model,
                modes: from,
                slips: run.slips(settings.direction_speed),
            };
            let forces = phase.solve(t, &state.0, &state.1).map(|(_, f)| f);
            let laws = model.contact_laws();
            let mut slides = |j: usize| {
                if laws[j].in_plane {
                    if let Some(f) = &forces {
                        let size = friction_size(f, j, true);
                        if size > S::zero() {
                            hints[j] = (-f.friction[j] / size, -f.second_friction[j] / size);
                        }
                    }
                    return Some(Mode::Slipping);
                }
                let forward = forces
                    .as_ref()
                    .is_some_and(|f| f.friction[j] < nalgebra::zero::<S>());
                Some(Mode::Sliding { forward })
            };
            forced[i] = slides(i);
            if let Some(f) = &forces.clone() {
                let tolerance = nalgebra::convert::<f64, S>(AT_THE_LIMIT);
                for j in (0..K).filter(|&j| j != i && from[j] == Mode::Stuck) {
                    let capacity = laws[j].static_friction * f.normal[j];
                    if capacity - friction_size(f, j, laws[j].in_plane) <= tolerance * capacity {
                        forced[j] = slides(j);
                    }
                }
            }
        }
        _ => {}
    }
    // An arrival of a contact whose rebounds accumulate settles it: where
    // they do, or earlier where it went in deeper than their flight by the
    // gap tolerance (a method whose error on the flight is larger; an
    // impact elsewhere that drives it in is decided at that impact).
    let settle = cause == Cause::Impact && run.accumulating[i].is_some();
    // Its flight is over either way: from here its gap is watched again
    // (were nothing to approach after all, its watch would not be left
    // past its time, where it could never cross zero again).
    if settle {
        run.accumulating[i] = None;
    }
    let (state, to, directions) = decide_switch(
        &model,
        settings,
        t,
        state,
        (&from, &forced, &hints),
        (cause, settle),
        (&mut run.switches, &mut run.accumulating),
    )
    .map_err(|error| match error {
        ContactError::NoConsistentMode { at_impact, .. } => {
            ResetFailure::NoConsistentMode { at_impact }
        }
        ContactError::DependentContacts { .. } => ResetFailure::DependentContacts,
        error => ResetFailure::refused(error.to_string()),
    })?;
    run.modes = to;
    run.directions = directions;
    Ok(state)
}

/// A contact scene's stepper: its run's switches and modes, and the
/// contact forces at its state.
impl<S, M, const N: usize, const K: usize> Stepper<'_, Phase<'_, S, N, K>, M, N>
where
    S: RealField + Copy,
    M: StepMethod<S>,
{
    /// Every switch of this stepper's run so far, in time order (the
    /// start's first).
    pub fn switches(&self) -> &[Switch<S, N>] {
        self.data::<ContactRun<S, N, K>>()
            .map_or(&[], |run| &run.switches)
    }

    /// The contacts' modes now.
    pub fn modes(&self) -> [Mode; K] {
        self.model().modes
    }

    /// The contact forces at the stepper's state in its modes; `None`
    /// where they are not determined.
    pub fn forces(&self) -> Option<ContactForces<S, N, K>> {
        self.model()
            .solve(self.t(), self.q(), self.qdot())
            .map(|(_, forces)| forces)
    }
}

/// A contact run's failure as a [`ContactError`]: a switch that could not
/// be decided, or forces not determined, as the contacts name them; any
/// other failure as the run loop's.
fn contact_error<S: RealField + Copy, const N: usize>(
    error: IntegrationError<S, N>,
) -> ContactError<S, N> {
    match error {
        IntegrationError::ResetFailed {
            event,
            t,
            q,
            qdot,
            reason,
        } => match *reason {
            ResetFailure::NoConsistentMode { at_impact } => ContactError::NoConsistentMode {
                t,
                q,
                qdot,
                at_impact,
            },
            ResetFailure::DependentContacts => ContactError::DependentContacts { t, q, qdot },
            ResetFailure::Chattering { switches } => ContactError::Chattering {
                t,
                q,
                qdot,
                switches,
            },
            reason => ContactError::Integration(IntegrationError::ResetFailed {
                event,
                t,
                q,
                qdot,
                reason: Box::new(reason),
            }),
        },
        IntegrationError::UndeterminedContactForces { t, q, qdot } => {
            ContactError::DependentContacts { t, q, qdot }
        }
        error => ContactError::Integration(error),
    }
}

/// The modes and forces at every sample, the modes (and the slip
/// directions) replayed from the switches, from the `start` phase's.
fn results<S: RealField + Copy, const N: usize, const K: usize>(
    model: &Erased<'_, S, N, K>,
    trajectory: Trajectory<S, N>,
    switches: Vec<Switch<S, N>>,
    start: Phase<'_, S, N, K>,
) -> ContactTrajectory<S, N, K> {
    let (mut current, mut slips) = (start.modes, start.slips);
    let mut next = 0;
    let mut modes = Vec::with_capacity(trajectory.len());
    let mut forces = Vec::with_capacity(trajectory.len());
    for sample in trajectory.iter() {
        while next < switches.len() && switches[next].t < sample.t {
            let switch = &switches[next];
            current[switch.contact] = switch.to;
            if switch.to == Mode::Slipping {
                slips.directions[switch.contact] = switch.slip_direction;
            }
            next += 1;
        }
        modes.push(current);
        let solved = Terms::new(model, sample.t, &sample.q, &sample.qdot)
            .and_then(|terms| accelerations(model, &current, &terms, &slips));
        forces.push(solved.map_or_else(
            || ContactForces {
                normal: SVector::repeat(nan()),
                friction: SVector::repeat(nan()),
                second_friction: SVector::repeat(nan()),
                generalized: SVector::repeat(nan()),
            },
            |(_, f)| f,
        ));
    }
    ContactTrajectory {
        trajectory,
        switches,
        modes,
        forces,
    }
}
