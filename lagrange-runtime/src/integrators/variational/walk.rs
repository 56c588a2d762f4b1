//! The variational kind's run loop, resumable: steps in `(q, p)`, each
//! interval between stops (sample times, a stepper's frame ends) cut into
//! equal steps no longer than `h`, as the fixed-step loop cuts them.

use nalgebra::{RealField, SVector};

use super::augmented::Weight;
use super::newton::{DiscreteEulerLagrange, StepFailure};
use super::rattle::StartForce;
use super::velocity::{VelocityHistory, velocity, with_velocity};
use super::{Variational, lacks, out_of_budget};
use crate::driver::Interval;
use crate::driver::run::{Advanced, Flow, Fresh, Run, Walk};
use crate::error::{IntegrationError, InvalidInput, NonFiniteValue};
use crate::linalg::all_finite;
use crate::linalg::mass::positive_semidefinite;
use crate::model::Lagrangian;
use crate::model::constraints::{
    has_velocity_constraints, is_constrained, mass_regular_on_constraints_only,
};

/// The variational method's work between steps: the state in `(q, p)`, the
/// history of midpoint velocities (the Newton guesses), and the constraint
/// force carried to the next step's guess.
///
/// Between stops the state is `(q, p)`; the run's `(q, q̇)` is brought up
/// to date at every stop (one conversion, counted in `rhs_evals`) and, while
/// events are watched, at every step. A failure inside an interval leaves
/// the run at its last stop (or watched step).
pub struct VariationalWalk<S: RealField + Copy, const N: usize> {
    method: Variational<S>,
    /// `h` bounded by the events' `max_step`, for the current segment.
    h: S,
    t: S,
    q: SVector<S, N>,
    p: SVector<S, N>,
    velocities: VelocityHistory<S, N>,
    /// `q̇` at the current step's start, kept while events are watched.
    qdot_now: SVector<S, N>,
    constrained: bool,
    force: SVector<S, N>,
}

impl<S: RealField + Copy, const N: usize> VariationalWalk<S, N> {
    pub(super) fn new(method: Variational<S>) -> Self {
        let zero = SVector::zeros();
        Self {
            method,
            h: method.h,
            t: S::zero(),
            q: zero,
            p: zero,
            velocities: VelocityHistory::new(S::zero(), zero, None),
            qdot_now: zero,
            constrained: false,
            force: zero,
        }
    }

    /// A start from the run's state: `p` from `q̇` (a model without the
    /// three methods refused before the first step), the mass matrix
    /// checked, the constraint force's first guess.
    fn start<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        run: &mut Run<'_, S, N>,
        model: &L,
    ) -> Result<(), IntegrationError<S, N>> {
        let (t0, q0, qdot0) = (run.t, run.q, run.qdot);
        self.h = run.rec.bound_step(self.method.h);
        run.rec.resolve_events(self.h);
        // Refuse a model without the three methods before the first step.
        let p0 = model.momentum(t0, &q0, &qdot0);
        let gradient = model.lagrangian_gradient(t0, &q0, &qdot0);
        let forces = model.nonconservative_forces(t0, &q0, &qdot0);
        let (Some(p0), Some(_), Some(_)) = (p0, gradient, forces) else {
            let needs = match (p0, gradient) {
                (None, _) => "momentum",
                (_, None) => "lagrangian_gradient",
                _ => "nonconservative_forces",
            };
            return Err(lacks(needs).into());
        };
        if has_velocity_constraints(model) {
            let method = "Variational";
            return Err(InvalidInput::VelocityConstraints { method }.into());
        }
        run.rec.stats.rhs_evals += 1;
        if !all_finite(p0.as_slice()) {
            let value = NonFiniteValue::Momentum;
            let (q, qdot) = (q0, qdot0);
            return Err(IntegrationError::NonFiniteState {
                t: t0,
                q,
                qdot,
                value,
            });
        }

        // The steps never solve with M, so a kinetic energy that is negative
        // for some velocities would otherwise go unnoticed until the first
        // sample: report the modelling error at the first state, as the
        // other methods do from their first evaluation. (A singular M, a
        // chart's pole, is integrated through.)
        let m0 = model.mass_matrix(t0, &q0);
        if crate::linalg::all_finite(m0.as_slice()) && !positive_semidefinite(&m0) {
            let (q, qdot) = (q0, qdot0);
            return Err(IntegrationError::IndefiniteMassMatrix { t: t0, q, qdot });
        }

        // A mass matrix regular only with the constraints: the step
        // integrates `L + (k/2)|φ̇|²`, `k` fixed here (`augmented.rs`).
        let augment = if mass_regular_on_constraints_only(model) {
            model.visit_constraints(Weight { t: t0, q: &q0 })
        } else {
            None
        };
        (self.t, self.q, self.p) = (t0, q0, p0);
        self.velocities = VelocityHistory::new(t0, qdot0, augment);
        self.qdot_now = qdot0;
        // A constrained model takes the RATTLE step (`constrained.rs`),
        // which carries the constraint force `Gᵀ λ` from step to step as
        // the next one's guess, starting from the continuous one.
        self.constrained = is_constrained(model);
        let start = StartForce {
            t: t0,
            q: &q0,
            qdot: &qdot0,
        };
        self.force = match model.visit_constraints(start) {
            None => SVector::zeros(),
            Some(result) => result?,
        };
        Ok(())
    }
}

impl<S: RealField + Copy, const N: usize> Walk<S, N> for VariationalWalk<S, N> {
    fn advance<L: Lagrangian<N, Scalar = S>>(
        &mut self,
        run: &mut Run<'_, S, N>,
        model: &L,
        target: S,
    ) -> Result<Advanced, IntegrationError<S, N>> {
        let method = self.method;
        let max_steps = method.max_steps;
        loop {
            if run.t >= target {
                return Ok(Advanced::Reached);
            }
            if run.fresh != Fresh::No {
                run.arm()?;
                self.start(run, model)?;
                run.fresh = Fresh::No;
            }
            let stop = run
                .rec
                .pending()
                .filter(|&ts| ts < target)
                .unwrap_or(target);
            let (t, q, p) = (self.t, self.q, self.p);
            let interval = Interval::new(t, stop, self.h);
            if interval.underflows() {
                let underflow = |qdot| IntegrationError::StepSizeUnderflow {
                    t,
                    h: interval.step,
                    q,
                    qdot,
                };
                let state = (t, q, p);
                return Err(with_velocity(
                    &mut run.rec,
                    model,
                    state,
                    &self.velocities,
                    underflow,
                ));
            }
            let Some(steps) = interval.steps(max_steps) else {
                let state = (t, q, p);
                let velocities = &self.velocities;
                return Err(out_of_budget(
                    &mut run.rec,
                    model,
                    state,
                    velocities,
                    max_steps,
                ));
            };
            let mut restarted = false;
            for k in 1..=steps {
                let (t, q, p) = (self.t, self.q, self.p);
                if run.steps_this_call().0 >= max_steps {
                    let velocities = &self.velocities;
                    return Err(out_of_budget(
                        &mut run.rec,
                        model,
                        (t, q, p),
                        velocities,
                        max_steps,
                    ));
                }
                let t_next = interval.time(k, steps);
                let dt = t_next - t;
                let del = DiscreteEulerLagrange {
                    model,
                    t_mid: t + dt / nalgebra::convert(2.0),
                    q,
                    p,
                    half_h: dt / nalgebra::convert(2.0),
                    augment: self.velocities.augment,
                };
                let guess = self.velocities.predict(del.t_mid);
                let solved = if self.constrained {
                    let near = self.velocities.latest();
                    method.rattle(&mut run.rec, &del, guess, self.force, (t, t_next), &near)
                } else {
                    let solved = method.solve(&mut run.rec.stats, &del, guess);
                    solved.map(|(v, rate)| (v, rate, self.force))
                };
                let (v, impulse_rate, step_force) = match solved {
                    Ok(solution) => solution,
                    Err(StepFailure::Error(error)) => return Err(error),
                    Err(StepFailure::Diverged { iterations }) => {
                        let diverged = |qdot| IntegrationError::NewtonDivergence {
                            t,
                            h: dt,
                            iterations,
                            q,
                            qdot,
                        };
                        let state = (t, q, p);
                        let velocities = &self.velocities;
                        return Err(with_velocity(
                            &mut run.rec,
                            model,
                            state,
                            velocities,
                            diverged,
                        ));
                    }
                };
                let before = (t, (q, self.qdot_now));
                self.q += v * dt;
                self.p += impulse_rate * dt;
                self.velocities.push(del.t_mid, v);
                self.t = t_next;
                run.rec.stats.steps_accepted += 1;
                if self.constrained {
                    self.force = step_force;
                    self.p -= self.force * dt;
                    let state = (self.t, &self.q, &self.p);
                    self.p =
                        Variational::rattle_momenta(&mut run.rec, model, state, &self.velocities)?;
                }
                if run.rec.watching() {
                    let (t, q, p) = (self.t, self.q, self.p);
                    self.qdot_now =
                        velocity(&mut run.rec.stats, model, t, &q, &p, &self.velocities)?;
                    let (t_before, start) = before;
                    let end = (q, self.qdot_now);
                    let crossed = run
                        .rec
                        .watch_hermite(model, (t_before, &start), (t, &end))?;
                    match run.take((t, end.0, end.1), crossed, target) {
                        Flow::Go => {}
                        Flow::Stopped => return Ok(Advanced::Stopped),
                        Flow::Rebuild => return Ok(Advanced::Rebuild),
                        Flow::Restarted(at_target) => {
                            if at_target {
                                run.t = target;
                                return Ok(Advanced::Reached);
                            }
                            restarted = true;
                            break;
                        }
                    }
                }
            }
            if !restarted {
                let (t, q, p) = (self.t, self.q, self.p);
                let qdot = velocity(&mut run.rec.stats, model, t, &q, &p, &self.velocities)?;
                (run.t, run.q, run.qdot) = (t, q, qdot);
                run.record_landed();
            }
        }
    }
}
