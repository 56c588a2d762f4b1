//! The `Stepper`: frame by frame as `integrate` goes sample by sample
//! (bit for bit for the fixed-step methods), the adaptive step size kept
//! between frames, the model changed between frames, `f32`, typed refusals
//! and failures that keep the last good state, and no allocation once
//! built.

use crate::allocations::allocations;
use crate::models::{CartesianPendulum, CoupledOscillator, ForcingBreaksDown};
use lagrange::models::{BouncingBall, Oscillator};
use lagrange_runtime::nalgebra::{Vector1, Vector2};
use lagrange_runtime::prelude::*;
use lagrange_runtime::{InvalidInput, Stats, StepMethod};

const HZ: f64 = 60.0;

fn spring() -> (CoupledOscillator<f64>, Vector2<f64>, Vector2<f64>) {
    (
        CoupledOscillator { omega: 2.0 },
        Vector2::new(1.0, -0.5),
        Vector2::new(0.0, 0.3),
    )
}

/// Steps `frames` frames of `1/60` s and returns the state after each.
fn frames<M>(method: M, frames: usize) -> Vec<(f64, Vector2<f64>, Vector2<f64>)>
where
    M: StepMethod<f64>,
{
    let (model, q0, v0) = spring();
    let mut stepper = Stepper::new(model, method, 0.0, q0, v0).unwrap();
    (1..=frames)
        .map(|k| {
            stepper.advance_to(k as f64 / HZ).unwrap();
            (stepper.t(), *stepper.q(), *stepper.qdot())
        })
        .collect()
}

/// A fixed-step method cuts each frame as `integrate` cuts each interval
/// between samples, with the same step function: the states agree bit for
/// bit.
#[test]
fn fixed_steps_frame_by_frame_equal_integrate_bit_for_bit() {
    let (model, q0, v0) = spring();
    let times: Vec<f64> = (1..=120).map(|k| k as f64 / HZ).collect();
    let h = 1.0 / 250.0; // not a divisor of a frame: 5 steps of 1/300 each
    let check = |stepped: Vec<(f64, Vector2<f64>, Vector2<f64>)>, run: Trajectory<f64, 2>| {
        for ((t, q, v), s) in stepped.iter().zip(run.iter()) {
            assert_eq!((*t, *q, *v), (s.t, s.q, s.qdot));
        }
    };
    check(
        frames(Rk4::new(h), 120),
        Rk4::new(h).integrate(&model, 0.0, q0, v0, &times).unwrap(),
    );
    check(
        frames(ExplicitEuler::new(h), 120),
        ExplicitEuler::new(h)
            .integrate(&model, 0.0, q0, v0, &times)
            .unwrap(),
    );
    check(
        frames(SymplecticEuler::new(h), 120),
        SymplecticEuler::new(h)
            .integrate(&model, 0.0, q0, v0, &times)
            .unwrap(),
    );
    // The implicit ones carry their stages into the next step's starting
    // guess, across frames as across samples.
    check(
        frames(ImplicitMidpoint::new(h), 120),
        ImplicitMidpoint::new(h)
            .integrate(&model, 0.0, q0, v0, &times)
            .unwrap(),
    );
    check(
        frames(GaussLegendre::three_stage(h), 120),
        GaussLegendre::three_stage(h)
            .integrate(&model, 0.0, q0, v0, &times)
            .unwrap(),
    );
    // The variational step carries its momenta and velocity history from
    // frame to frame as from sample to sample (on a generated model: it
    // needs the momenta, which the hand-written spring does not give).
    let spring = Oscillator::new(1.0, 4.0, 0.0);
    let (x0, xd0) = (Vector1::new(1.0), Vector1::new(0.0));
    let mut stepper = Stepper::new(spring, Variational::new(h), 0.0, x0, xd0).unwrap();
    let run = Variational::new(h)
        .integrate(&spring, 0.0, x0, xd0, &times)
        .unwrap();
    for s in run.iter() {
        stepper.advance_to(s.t).unwrap();
        assert_eq!(
            (stepper.t(), *stepper.q(), *stepper.qdot()),
            (s.t, s.q, s.qdot)
        );
    }
}

/// Radau5 steps frame by frame too: its step size, Jacobian and LU factors
/// are kept between frames, a step shortened to land on a frame. Over 10 s
/// at 60 Hz it stays within its tolerance's reach of the exact motion
/// (its global error grows like `rtol^(5/6)` per unit of time scale, see
/// its docs: 1e-8 at `rtol = 1e-10` over these three periods, so 1e-7),
/// and costs fewer right-hand sides than one `integrate` per frame, which
/// guesses a first step and factors anew every frame.
#[test]
fn radau5_steps_frame_by_frame() {
    let (model, q0, v0) = spring();
    let n = 600;
    let radau = Radau5::new().rtol(1e-10).atol(1e-10);
    let (stats, (t, q, v)) = stepped(radau, n);
    let (q_exact, v_exact) = model.exact(t, q0, v0);
    let err = (q - q_exact).amax().max((v - v_exact).amax());
    let per_frame_integrate = per_frame(&model, radau, n);
    println!(
        "Radau5 at 1e-10: stepper {} right-hand sides in {} steps, one integrate per frame {}; error {err:.1e}",
        stats.rhs_evals, stats.steps_accepted, per_frame_integrate
    );
    assert!(err < 1e-7, "{err}");
    assert!(stats.rhs_evals < per_frame_integrate);
    assert_eq!(t, n as f64 / HZ);
}

/// The adaptive methods keep their step size between frames: at these
/// tolerances the step the control wants is longer than a frame, so after
/// the first each frame is one step (shortened to land on the frame), with
/// no rejection and no new initial guess, where one `integrate` per frame
/// starts each frame with a fresh first slope and initial-step guess (2
/// evaluations more per frame). The result stays within the tolerance's reach of the
/// exact solution.
#[test]
fn adaptive_steps_keep_their_size_between_frames() {
    let (model, q0, v0) = spring();
    let n = 600;
    let dopri5 = Dopri5::new().rtol(1e-8).atol(1e-8);
    let dop853 = Dop853::new().rtol(1e-11).atol(1e-11);
    for (name, tol, (stats, (t, q, v)), per_frame_integrate) in [
        (
            "Dopri5",
            1e-8,
            stepped(dopri5, n),
            per_frame(&model, dopri5, n),
        ),
        (
            "Dop853",
            1e-11,
            stepped(dop853, n),
            per_frame(&model, dop853, n),
        ),
    ] {
        let evals = stats.rhs_evals;
        let (q_exact, v_exact) = model.exact(t, q0, v0);
        let err = (q - q_exact).amax().max((v - v_exact).amax());
        println!(
            "{name} at {tol:e}: stepper {evals} right-hand sides in {} steps, \
             one integrate per frame {per_frame_integrate}; error {err:.1e}",
            stats.steps_accepted
        );
        // The first frame may take a few steps from the initial guess.
        assert!(
            stats.steps_accepted <= n + 3 && stats.steps_rejected == 0,
            "{stats:?}"
        );
        assert!(
            evals + 2 * (n - 1) <= per_frame_integrate,
            "{evals} vs {per_frame_integrate}"
        );
        // Global error of a local-error-per-step control over 10 s (~3
        // periods): within 1000× the tolerance.
        assert!(err < 1e3 * tol, "{name}: {err}");
        assert_eq!(t, n as f64 / HZ);
    }
}

fn stepped<M: StepMethod<f64>>(method: M, n: usize) -> (Stats, (f64, Vector2<f64>, Vector2<f64>)) {
    let (model, q0, v0) = spring();
    let mut stepper = Stepper::new(model, method, 0.0, q0, v0).unwrap();
    for k in 1..=n {
        stepper.advance_to(k as f64 / HZ).unwrap();
    }
    let state = (stepper.t(), *stepper.q(), *stepper.qdot());
    (stepper.stats(), state)
}

fn per_frame<I: Integrator<f64>>(model: &CoupledOscillator<f64>, method: I, n: usize) -> usize {
    let (_, mut q, mut v) = spring();
    let mut evals = 0;
    for k in 1..=n {
        let (t0, t1) = ((k - 1) as f64 / HZ, k as f64 / HZ);
        let run = method.integrate(model, t0, q, v, &[t1]).unwrap();
        let last = run.last().unwrap();
        (q, v) = (last.q, last.qdot);
        evals += run.stats().rhs_evals;
    }
    evals
}

/// Parameters changed between frames take effect at once: the stepper's
/// run equals two `integrate` runs, one per parameter value, the second
/// from the first one's end.
#[test]
fn a_parameter_changed_between_frames_is_used_from_the_next_frame() {
    let (model, q0, v0) = spring();
    let h = 1e-3;
    let mut stepper = Stepper::new(model, Rk4::new(h), 0.0, q0, v0).unwrap();
    stepper.advance_to(0.5).unwrap();
    stepper.model_mut().omega = 5.0;
    stepper.advance_to(1.0).unwrap();
    let first = Rk4::new(h)
        .integrate(&spring().0, 0.0, q0, v0, &[0.5])
        .unwrap();
    let mid = first.last().unwrap();
    let stiff = CoupledOscillator { omega: 5.0 };
    let second = Rk4::new(h)
        .integrate(&stiff, 0.5, mid.q, mid.qdot, &[1.0])
        .unwrap();
    assert_eq!(*stepper.q(), second.last().unwrap().q);

    // The same with an adaptive method, whose carried slope (first same as
    // last) must be recomputed: against the exact solution of the stiffer
    // spring from the state at 0.5.
    let tight = Dop853::new().rtol(1e-12).atol(1e-12);
    let mut stepper = Stepper::new(spring().0, tight, 0.0, q0, v0).unwrap();
    stepper.advance_to(0.5).unwrap();
    let (qm, vm) = (*stepper.q(), *stepper.qdot());
    stepper.model_mut().omega = 5.0;
    stepper.advance_to(1.0).unwrap();
    let (q_exact, _) = stiff.exact(0.5, qm, vm);
    let err = (stepper.q() - q_exact).amax();
    // A stale slope from ω = 2 would be off by O(h · Δω² |q|) ≈ 1e-2.
    assert!(err < 1e-9, "{err}");
}

/// In `f32` the stepper runs with the method's `f32` defaults and tracks
/// the exact solution to what `f32` holds.
#[test]
fn f32_steppers_track_the_exact_solution() {
    let model = CoupledOscillator { omega: 2.0f32 };
    let (q0, v0) = (Vector2::new(1.0f32, -0.5), Vector2::new(0.0f32, 0.3));
    let mut rk4 = Stepper::new(model, Rk4::new(1.0f32 / 240.0), 0.0, q0, v0).unwrap();
    let model = CoupledOscillator { omega: 2.0f32 };
    let mut dopri = Stepper::new(model, Dopri5::<f32>::new(), 0.0, q0, v0).unwrap();
    for k in 1..=600 {
        let t = k as f32 / 60.0;
        rk4.advance_to(t).unwrap();
        dopri.advance_to(t).unwrap();
    }
    let exact = CoupledOscillator { omega: 2.0f64 }.exact(
        10.0,
        Vector2::new(1.0, -0.5),
        Vector2::new(0.0, 0.3),
    );
    // An f32 clock at 10⁶ s moves in steps of 0.0625 s: a frame of 1/60 s
    // does not move it, and says so; moved back to 0 (the oscillator does
    // not depend on t) the stepper goes on from the same state.
    let mut late = Stepper::new(
        CoupledOscillator { omega: 2.0f32 },
        Rk4::new(1e-3f32),
        0.0,
        q0,
        v0,
    )
    .unwrap();
    late.set_time(1e6).unwrap();
    assert!(matches!(
        late.advance(1.0 / 60.0),
        Err(IntegrationError::InvalidInput(
            InvalidInput::TargetNotAhead { .. }
        ))
    ));
    late.set_time(0.0).unwrap();
    late.advance(1.0 / 60.0).unwrap();
    assert!(late.q() != &q0);

    // RK4: f32 rounding (ε = 6e-8) over 2400 steps grows like
    // √steps · ε · |q| ≈ 3e-6, and its truncation (h⁴ ω⁴ t ≈ 5e-9) is
    // below that: 1e-5. Dopri5: its default f32 tolerance, 1.2e-5, bounds
    // each step's error; over these three periods the global error stays
    // within ten times it: 1.2e-4. (Measured: 5.8e-7 and 4.8e-7.)
    for (name, q, bound) in [("Rk4", rk4.q(), 1e-5), ("Dopri5", dopri.q(), 1.2e-4)] {
        let err = (q.cast::<f64>() - exact.0).amax();
        println!("{name} f32 after 600 frames: error {err:.1e}");
        assert!(err < bound, "{name}: {err}");
    }
}

/// Bad targets and settings are typed refusals; a model that breaks down
/// stops the stepper with the error at its time, the last good state kept.
#[test]
fn refusals_and_failures_are_typed_and_keep_the_last_good_state() {
    let (model, q0, v0) = spring();
    let mut stepper = Stepper::new(model, Dopri5::new(), 0.0, q0, v0).unwrap();
    stepper.advance_to(1.0).unwrap();
    // 1e-300 is a positive `dt` that does not move t = 1.
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-300] {
        match stepper.advance(dt) {
            Err(IntegrationError::InvalidInput(InvalidInput::TargetNotAhead { t, .. })) => {
                assert_eq!(t, 1.0)
            }
            other => panic!("dt = {dt}: {other:?}"),
        }
    }
    assert!(matches!(
        Stepper::new(spring().0, Rk4::new(-1.0), 0.0, q0, v0),
        Err(IntegrationError::InvalidInput(
            InvalidInput::InvalidStepSize { .. }
        ))
    ));
    assert!(matches!(
        Stepper::new(spring().0, Dopri5::new().atol(0.0), 0.0, q0, v0),
        Err(IntegrationError::InvalidInput(
            InvalidInput::InvalidAbsoluteTolerance { .. }
        ))
    ));
    assert!(matches!(
        Stepper::new(
            spring().0,
            Rk4::new(0.1),
            0.0,
            Vector2::new(f64::NAN, 0.0),
            v0
        ),
        Err(IntegrationError::InvalidInput(
            InvalidInput::NonFiniteInitialPosition { .. }
        ))
    ));

    // The forcing is NaN after t* = 0.5.
    let (x0, xd0) = (Vector1::new(1.0), Vector1::new(0.0));
    let broken = || ForcingBreaksDown { t_star: 0.5 };
    let fixed = Stepper::new(broken(), Rk4::new(1e-3), 0.0, x0, xd0).unwrap();
    let adaptive = Stepper::new(broken(), Dopri5::new(), 0.0, x0, xd0).unwrap();
    check_breakdown("Rk4", fixed);
    check_breakdown("Dopri5", adaptive);
}

fn check_breakdown<M: StepMethod<f64>>(name: &str, mut stepper: Stepper<ForcingBreaksDown, M, 1>) {
    let error = (1..=60)
        .find_map(|k| stepper.advance_to(k as f64 / HZ).err())
        .expect("the model breaks down at 0.5");
    let t_error = error.time().expect("a failure at a time");
    let t_kept = stepper.t();
    println!("{name}: {error} (stepper kept t = {t_kept})");
    // The state kept is the last good one: before the breakdown, and at or
    // before the time reported, which is within one step (1e-3 for Rk4;
    // for Dopri5 its step, shrunk until it underflows at the breakdown)
    // of t*.
    assert!(t_kept <= 0.5 && t_kept <= t_error, "{t_kept} {t_error}");
    assert!((t_error - 0.5).abs() < 1e-3, "{t_error}");
    // The state is still there, finite, for the caller to use.
    assert!(stepper.q()[0].is_finite() && stepper.qdot()[0].is_finite());
}

/// Once built, a stepper does not allocate: 10⁶ RK4 frames of the coupled
/// oscillator, 10⁵ Dopri5 and Dop853 frames with a parameter change and a
/// state reset in between, 10⁴ frames of a constrained model (the Cartesian
/// pendulum, projected after every step) and of Gauss–Legendre (Newton on
/// its heap workspace, allocated in `Stepper::new`).
#[test]
fn a_stepper_does_not_allocate_per_step() {
    let (model, q0, v0) = spring();
    let mut rk4 = Stepper::new(model, Rk4::new(1.0 / HZ), 0.0, q0, v0).unwrap();
    let mut dopri = Stepper::new(spring().0, Dopri5::new(), 0.0, q0, v0).unwrap();
    let mut dop853 = Stepper::new(spring().0, Dop853::new(), 0.0, q0, v0).unwrap();
    let mut gauss = Stepper::new(spring().0, GaussLegendre::two_stage(1e-2), 0.0, q0, v0).unwrap();
    let pendulum = CartesianPendulum::unit();
    let (pq, pv) = pendulum.state(1.0, 0.0);
    let mut constrained = Stepper::new(pendulum, Dopri5::new(), 0.0, pq, pv).unwrap();
    // Radau5's workspace and the variational step's history are allocated
    // in `Stepper::new`.
    let mut radau = Stepper::new(spring().0, Radau5::new(), 0.0, q0, v0).unwrap();
    let spring_with_momenta = Oscillator::new(1.0, 4.0, 0.0);
    let (x0, xd0) = (Vector1::new(1.0), Vector1::new(0.0));
    let mut variational =
        Stepper::new(spring_with_momenta, Variational::new(1e-2), 0.0, x0, xd0).unwrap();

    let before = allocations();
    for k in 1..=1_000_000 {
        rk4.advance_to(k as f64 / HZ).unwrap();
    }
    for k in 1..=100_000 {
        let t = k as f64 / HZ;
        dopri.advance_to(t).unwrap();
        dop853.advance_to(t).unwrap();
        if k == 50_000 {
            dopri.model_mut().omega = 3.0;
            dop853.set_state(q0, v0).unwrap();
        }
    }
    for k in 1..=10_000 {
        let t = k as f64 / HZ;
        constrained.advance_to(t).unwrap();
        gauss.advance_to(t).unwrap();
        radau.advance_to(t).unwrap();
        variational.advance_to(t).unwrap();
        if k == 5_000 {
            gauss.model_mut().omega = 3.0;
            radau.model_mut().omega = 3.0;
            variational.set_state(x0, xd0).unwrap();
        }
    }
    let allocated = allocations() - before;
    let steps = rk4.stats().steps_accepted
        + dopri.stats().steps_accepted
        + dop853.stats().steps_accepted
        + constrained.stats().steps_accepted
        + gauss.stats().steps_accepted
        + radau.stats().steps_accepted
        + variational.stats().steps_accepted;
    println!("{steps} steps, {allocated} allocations");
    assert!(steps >= 1_230_000);
    assert_eq!(allocated, 0);
}

/// A ball bouncing at 60 Hz in a stepper (restitution 0.9): each bounce is
/// reported by the call whose frame it falls in, at the closed-form time,
/// the state after it the reversed velocity; frames go on to their targets.
#[test]
fn a_stepper_reports_the_bounces_of_each_frame() {
    let ball = BouncingBall::new(1.0, 9.81);
    // The bounces within the 7 s the frames cover.
    let exact: Vec<f64> = ball
        .bounce_times(1.0, 0.9, 100)
        .into_iter()
        .filter(|&t| t <= 7.0)
        .collect();
    let events = Events::new().with(BouncingBall::floor(0.9));
    let start = (Vector1::new(1.0), Vector1::new(0.0));
    for adaptive in [true, false] {
        let mut seen = Vec::new();
        let mut frame =
            |k: usize, t: f64, bounces: &[lagrange_runtime::events::EventRecord<f64, 1>]| {
                for b in bounces {
                    // Reported by the frame that contains it.
                    assert!(b.t > (k - 1) as f64 / HZ && b.t <= t, "frame {k}: {}", b.t);
                    let (_, after) = b.after.expect("a reset");
                    assert!((after[0] + 0.9 * b.qdot[0]).abs() < 1e-14);
                    seen.push(b.t);
                }
            };
        if adaptive {
            let method = Dopri5::new().rtol(1e-10).atol(1e-10);
            let mut s = Stepper::new(ball, method, 0.0, start.0, start.1).unwrap();
            s = s.with_events(&events).unwrap();
            for k in 1..=420 {
                s.advance_to(k as f64 / HZ).unwrap();
                assert_eq!(s.t(), k as f64 / HZ);
                frame(k, s.t(), s.events());
            }
        } else {
            let mut s = Stepper::new(ball, Rk4::new(1.0 / 240.0), 0.0, start.0, start.1).unwrap();
            s = s.with_events(&events).unwrap();
            for k in 1..=420 {
                s.advance_to(k as f64 / HZ).unwrap();
                frame(k, s.t(), s.events());
            }
        }
        assert_eq!(seen.len(), exact.len(), "adaptive = {adaptive}: {seen:?}");
        let worst = seen
            .iter()
            .zip(&exact)
            .map(|(a, b)| ((a - b) / b).abs())
            .fold(0.0, f64::max);
        println!(
            "stepper, adaptive = {adaptive}: {} bounces in 7 s, worst relative error {worst:.1e}",
            seen.len()
        );
        // Free fall is a quadratic: Dopri5's dense output and RK4's cubic
        // Hermite interpolant are exact on it, so the times are the
        // Illinois search's (a few ulps) plus the rounding of the summed
        // flights, as for `integrate` (bound 1e-12 there too).
        assert!(worst < 1e-12, "adaptive = {adaptive}: {worst}");
    }
}

/// A stopping event ends the call early at the event, and the next call
/// goes on from there; a stepper with events allocates nothing on steps
/// without a crossing.
#[test]
fn a_stop_ends_the_call_at_the_event_and_the_next_goes_on() {
    // The coupled oscillator's first coordinate, cos(2t) from 1, falls
    // through zero at t = π/4, 3π/4, …: a stopping event.
    let (model, q0, v0) = (
        CoupledOscillator { omega: 2.0 },
        Vector2::new(1.0, 0.0),
        Vector2::zeros(),
    );
    let zero = Event::new("x", |_t, q: &Vector2<f64>, _v: &Vector2<f64>| q[0])
        .falling()
        .stop();
    let events = Events::new().with(zero);
    let tight = Dop853::new().rtol(1e-12).atol(1e-12);
    let mut s = Stepper::new(model, tight, 0.0, q0, v0)
        .unwrap()
        .with_events(&events)
        .unwrap();
    let mut stops = Vec::new();
    let mut target = 0.0;
    while stops.len() < 3 {
        target += 1.0 / HZ;
        // Calls that stop early are repeated to their frame's end.
        while s.t() < target {
            s.advance_to(target).unwrap();
            if let Some(stop) = s.stopped() {
                assert_eq!(s.t(), stop.t);
                stops.push(stop.t);
            }
        }
    }
    for (k, t) in stops.iter().enumerate() {
        // Falling zeros of cos 2t: π/4 + kπ.
        let exact = std::f64::consts::FRAC_PI_4 + k as f64 * std::f64::consts::PI;
        // Dop853 at 1e-12 over a few periods, and the dense output's
        // error on top: within 1e-9.
        assert!((t - exact).abs() < 1e-9, "stop {k}: {t} vs {exact}");
    }

    // Record-only events on a steady run: no allocation per step.
    let record = Events::new().with(Event::new(
        "y",
        |_t, q: &Vector2<f64>, _v: &Vector2<f64>| q[1] - 5.0,
    ));
    let mut quiet = Stepper::new(
        CoupledOscillator { omega: 2.0 },
        Rk4::new(1.0 / HZ),
        0.0,
        q0,
        v0,
    )
    .unwrap()
    .with_events(&record)
    .unwrap();
    quiet.advance_to(1.0).unwrap();
    let before = allocations();
    for k in 1..=100_000 {
        quiet.advance_to(1.0 + k as f64 / HZ).unwrap();
    }
    assert!(quiet.stats().event_evals >= 100_000);
    assert_eq!(allocations() - before, 0, "watching events allocated");
}

/// The observer in a stepper: it ends the call at the end of the step it
/// stops on, and the next call goes on.
#[test]
fn an_observer_ends_a_stepper_call_at_its_step() {
    use std::ops::ControlFlow;
    let (model, q0, v0) = spring();
    let h = 1.0 / 240.0;
    let watchdog = Events::new().observe(|t, _q, _v| {
        if t > 0.5 && t < 0.6 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    });
    let mut s = Stepper::new(model, Rk4::new(h), 0.0, q0, v0)
        .unwrap()
        .with_events(&watchdog)
        .unwrap();
    s.advance_to(1.0).unwrap();
    assert!(s.interrupted());
    // The first step end past 0.5: 121 steps of 1/240.
    assert_eq!(s.t(), 121.0 * h);
    s.advance_to(1.0).unwrap();
    assert!(s.interrupted(), "still inside the watchdog's window");
    while s.t() < 1.0 {
        s.advance_to(1.0).unwrap();
    }
    assert!(!s.interrupted());
}
