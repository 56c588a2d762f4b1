//! The bits of every method's results on the shared problems, against the
//! fingerprints recorded in `tests/data/fingerprints.txt`.
//!
//! A restructuring must keep every method's samples, events and statistics
//! (and a contact run's switches and forces) bit-identical; a fix that moves them re-blesses the file
//! (`LAGRANGE_BLESS=1 cargo test --test suite trajectories::fingerprints`) and says in its
//! commit which lines moved and by how much (`FINGERPRINT_DUMP=FILE` writes
//! every sample in full, to compare two builds).
//!
//! The fingerprints are of `f64` arithmetic on this project's CI machine
//! (x86-64, no fused multiply-add); another platform's libm may round a
//! `powf` differently, and then this test says so rather than anything
//! about the code.

use std::fmt::Write as _;

use lagrange::Method;
use lagrange::constraints::Drift;
use lagrange::models::{
    BlockOnBelt, BouncingBall, CartPole, CartesianPendulum, Chain, DoublePendulum, FourBar, Kepler,
    Oscillator, Pendulum, PendulumWall, SliderCrank, StiffChain, Tree, TumblingBox,
};
use lagrange::nalgebra::{SVector, Vector1, Vector2};
use lagrange::prelude::*;
use lagrange::{IntegrationResult, StepMethod};

/// FNV-1a over 64-bit words: small, deterministic, no dependency.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
    fn word(&mut self, w: u64) {
        for b in w.to_le_bytes() {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn f(&mut self, x: f64) {
        self.word(x.to_bits());
    }
    fn state<const N: usize>(&mut self, q: &SVector<f64, N>, qdot: &SVector<f64, N>) {
        q.iter().chain(qdot.iter()).for_each(|&x| self.f(x));
    }
    fn text(&mut self, s: &str) {
        s.bytes().for_each(|b| self.word(u64::from(b)));
    }
}

/// What a run is fingerprinted by: every sample, event and count, and the
/// error of a failed run.
fn fingerprint<const N: usize>(result: &IntegrationResult<f64, N>, dump: &mut String) -> u64 {
    let mut h = Fnv::new();
    let (trajectory, error) = match result {
        Ok(t) => (t, None),
        Err(failure) => (&failure.trajectory, Some(failure.error.to_string())),
    };
    for s in trajectory.iter() {
        h.f(s.t);
        h.state(&s.q, &s.qdot);
        let _ = writeln!(
            dump,
            "  {:?} {:?} {:?}",
            s.t,
            s.q.as_slice(),
            s.qdot.as_slice()
        );
    }
    for e in trajectory.events() {
        h.text(e.name);
        h.f(e.t);
        h.state(&e.q, &e.qdot);
        if let Some((q, qdot)) = &e.after {
            h.state(q, qdot);
        }
        let _ = writeln!(dump, "  event {} {:?} {:?}", e.name, e.t, e.q.as_slice());
    }
    if let Some(stop) = trajectory.stopped() {
        h.text(stop.name);
        h.f(stop.t);
    }
    if let Some(t) = trajectory.interrupted() {
        h.f(t);
    }
    let s = trajectory.stats();
    for count in [
        s.steps_accepted,
        s.steps_rejected,
        s.rhs_evals,
        s.jacobian_evals,
        s.linear_solves,
        s.newton_iterations,
        s.projection_iterations,
        s.event_evals,
    ] {
        h.word(count as u64);
    }
    for x in [
        s.max_position_residual,
        s.max_velocity_residual,
        s.initial_position_correction,
        s.initial_velocity_correction,
    ] {
        h.f(x);
    }
    if let Some(error) = error {
        h.text(&error);
        let _ = writeln!(dump, "  error {error}");
    }
    let _ = writeln!(dump, "  stats {s:?}");
    h.0
}

/// A contact run fingerprinted as a run (its samples, events, work and
/// error), with its switches and the contact forces at every sample.
fn contact_fingerprint<const N: usize, const K: usize>(
    result: &lagrange::contact::ContactResult<f64, N, K>,
    dump: &mut String,
) -> u64 {
    let (run, error) = match result {
        Ok(run) => (run, None),
        Err(failure) => (&failure.trajectory, Some(failure.error.to_string())),
    };
    let mut h = Fnv(fingerprint(&Ok(run.trajectory().clone()), dump));
    for s in run.switches() {
        h.f(s.t);
        h.word(s.contact as u64);
        h.text(&format!("{:?} {:?} {:?}", s.cause, s.from, s.to));
        h.state(&s.q, &s.qdot);
        let _ = writeln!(dump, "  switch {:?} {} {:?}", s.t, s.contact, s.to);
    }
    for f in run.forces() {
        f.normal
            .iter()
            .chain(f.friction.iter())
            .for_each(|&x| h.f(x));
    }
    if let Some(error) = error {
        h.text(&error);
        let _ = writeln!(dump, "  contact error {error}");
    }
    h.0
}

/// A `Stepper` advanced frame by frame, fingerprinted as a trajectory of
/// its frames' ends (and its events, and its work).
fn stepped<L, M, const N: usize>(
    model: L,
    method: M,
    (q0, qdot0): (SVector<f64, N>, SVector<f64, N>),
    frames: usize,
    dt: f64,
    events: Option<&Events<'_, f64, N>>,
    dump: &mut String,
) -> u64
where
    L: Lagrangian<N, Scalar = f64>,
    M: StepMethod<f64>,
{
    let mut h = Fnv::new();
    let stepper = Stepper::new(model, method, 0.0, q0, qdot0);
    let mut stepper = match (stepper, events) {
        (Ok(s), Some(events)) => match s.with_events(events) {
            Ok(s) => s,
            Err(e) => {
                h.text(&e.to_string());
                return h.0;
            }
        },
        (Ok(s), None) => s,
        (Err(e), _) => {
            h.text(&e.to_string());
            return h.0;
        }
    };
    for _ in 0..frames {
        let result = stepper.advance(dt);
        h.f(stepper.t());
        h.state(stepper.q(), stepper.qdot());
        let _ = writeln!(
            dump,
            "  {:?} {:?} {:?}",
            stepper.t(),
            stepper.q().as_slice(),
            stepper.qdot().as_slice()
        );
        for e in stepper.events() {
            h.text(e.name);
            h.f(e.t);
            h.state(&e.q, &e.qdot);
        }
        if let Err(e) = result {
            h.text(&e.to_string());
            let _ = writeln!(dump, "  error {e}");
            break;
        }
    }
    let s = stepper.stats();
    for count in [
        s.steps_accepted,
        s.steps_rejected,
        s.rhs_evals,
        s.event_evals,
    ] {
        h.word(count as u64);
    }
    h.0
}

fn times(step: f64, count: usize) -> Vec<f64> {
    (1..=count).map(|i| step * i as f64).collect()
}

/// Every case: `(name, fingerprint)`, with every sample written to `dump`.
fn cases(dump: &mut String) -> Vec<(String, u64)> {
    let mut out = Vec::new();
    let mut case = |name: String, dump: &mut String, f: &mut dyn FnMut(&mut String) -> u64| {
        let _ = writeln!(dump, "{name}");
        let hash = f(dump);
        out.push((name, hash));
    };
    let every = |tight: bool| {
        Method::ALL.into_iter().flat_map(move |m| {
            let tols: &[f64] = if m.is_adaptive() && tight {
                &[1e-6, 1e-11]
            } else {
                &[1e-8]
            };
            tols.iter().map(move |&tol| (m, tol))
        })
    };

    let (dp, q, v) = DoublePendulum::<f64>::regular();
    let ts = times(0.1, 20);
    for (m, tol) in every(true) {
        let method = m.integrator(1e-2, tol);
        case(
            format!("double_pendulum {} {tol:e}", m.id()),
            dump,
            &mut |d| fingerprint(&method.integrate(&dp, 0.0, q, v, &ts), d),
        );
    }

    let chain = Chain::new([1.0, 0.8, 1.2, 0.9, 1.1], [1.0, 0.7, 0.9, 1.1, 0.6]);
    let q5 = SVector::<f64, 5>::from_fn(|i, _| 0.3 + 0.1 * i as f64);
    let ts = times(0.25, 8);
    for (m, tol) in every(false) {
        let method = m.integrator(5e-3, tol);
        case(format!("chain5 {} {tol:e}", m.id()), dump, &mut |d| {
            fingerprint(&method.integrate(&chain, 0.0, q5, SVector::zeros(), &ts), d)
        });
    }

    // Two branches of five links, solved by the recursion over the parts
    // of `T` the engine found (its `M` and `f` formed from them): what a
    // change to how the engine finds a tree must keep.
    let tree = Tree::unit();
    let q10 = SVector::<f64, 10>::from_fn(|i, _| 0.2 + 0.05 * i as f64);
    let ts = times(0.25, 4);
    for (m, tol) in every(false) {
        let method = m.integrator(5e-3, tol);
        case(format!("tree2x5 {} {tol:e}", m.id()), dump, &mut |d| {
            fingerprint(&method.integrate(&tree, 0.0, q10, SVector::zeros(), &ts), d)
        });
    }

    let kepler = Kepler::new(1.0);
    let (q, v) = kepler.pericentre(0.6);
    let ts = times(1.0, 10);
    for (m, tol) in every(true) {
        let method = m.integrator(1e-2, tol);
        case(format!("kepler {} {tol:e}", m.id()), dump, &mut |d| {
            fingerprint(&method.integrate(&kepler, 0.0, q, v, &ts), d)
        });
    }

    let stiff = StiffChain::ratio_1e6();
    let (q, v) = StiffChain::start();
    let ts = times(0.5, 4);
    for m in [
        Method::Radau5,
        Method::Dopri5,
        Method::ImplicitMidpoint,
        Method::Rk4,
    ] {
        let method = m.integrator(1e-3, 1e-6).max_steps(200_000);
        case(format!("stiff_chain {}", m.id()), dump, &mut |d| {
            fingerprint(&method.integrate(&stiff, 0.0, q, v, &ts), d)
        });
    }

    let damped = Oscillator::new(1.0, 4.0, 0.3);
    let ts = times(0.5, 10);
    for (m, tol) in every(false) {
        let method = m.integrator(1e-2, tol);
        case(
            format!("damped_oscillator {} {tol:e}", m.id()),
            dump,
            &mut |d| {
                fingerprint(
                    &method.integrate(&damped, 0.0, Vector1::new(1.0), Vector1::new(0.0), &ts),
                    d,
                )
            },
        );
    }

    // Constrained: every drift control.
    let pendulum = CartesianPendulum::new(1.0, 1.0, 9.81);
    let (q, v) = pendulum.state(1.0, 0.0);
    let ts = times(0.25, 8);
    let drifts = [
        ("projection", Drift::Projection),
        (
            "baumgarte",
            Drift::Baumgarte {
                alpha: 5.0,
                beta: 5.0,
            },
        ),
        ("none", Drift::None),
    ];
    for (m, tol) in every(false) {
        let method = m.integrator(1e-2, tol);
        for (drift_name, drift) in drifts {
            case(
                format!("cartesian_pendulum {drift_name} {} {tol:e}", m.id()),
                dump,
                &mut |d| {
                    fingerprint(
                        &method.integrate(&pendulum.with_drift(drift), 0.0, q, v, &ts),
                        d,
                    )
                },
            );
        }
    }
    let crank = SliderCrank::engine();
    let (q, v) = crank.state(0.3, 2.0);
    let four_bar = FourBar::crank_rocker();
    let (q4, v4) = four_bar.state(0.4, 1.5).expect("assembles");
    for (m, tol) in every(false) {
        let method = m.integrator(1e-3, tol);
        case(format!("slider_crank {} {tol:e}", m.id()), dump, &mut |d| {
            fingerprint(&method.integrate(&crank, 0.0, q, v, &ts), d)
        });
        case(format!("four_bar {} {tol:e}", m.id()), dump, &mut |d| {
            fingerprint(&method.integrate(&four_bar, 0.0, q4, v4, &ts), d)
        });
    }

    // Control inputs: constant, and a feedback controller.
    let cart = CartPole::new(1.0, 0.2, 0.5, 9.81);
    let (q, v) = (Vector2::new(0.0, 0.2), Vector2::zeros());
    let pushed = cart.with_inputs(&Vector1::new(1.5));
    let ts = times(0.2, 5);
    for (m, tol) in every(false) {
        let method = m.integrator(1e-2, tol);
        case(
            format!("cart_pole constant {} {tol:e}", m.id()),
            dump,
            &mut |d| fingerprint(&method.integrate(&pushed, 0.0, q, v, &ts), d),
        );
        let balanced = cart.with_controller(|_, q: &Vector2<f64>, v: &Vector2<f64>| {
            Vector1::new(40.0 * q[1] + 10.0 * v[1] + q[0] + 2.0 * v[0])
        });
        case(
            format!("cart_pole controlled {} {tol:e}", m.id()),
            dump,
            &mut |d| fingerprint(&method.integrate(&balanced, 0.0, q, v, &ts), d),
        );
    }

    // Events: resets (impacts), and a recording event.
    let ball = BouncingBall::new(1.0, 9.81);
    let floor = Events::new().with(BouncingBall::floor(0.8));
    let ts = times(0.25, 12);
    let swing = Pendulum::new(1.0, 1.0, 9.81);
    let wall = Events::new().with(
        PendulumWall {
            beta: 0.3,
            restitution: 0.8,
        }
        .event(),
    );
    let section = Events::new().with(Event::new(
        "upright",
        |_t, q: &SVector<f64, 2>, _v: &SVector<f64, 2>| q[0],
    ));
    let (dp, qd, vd) = DoublePendulum::<f64>::regular();
    for (m, tol) in every(false) {
        let method = m.integrator(1e-3, tol);
        case(
            format!("bouncing_ball {} {tol:e}", m.id()),
            dump,
            &mut |d| {
                let run = method.integrate_with_events(
                    &ball,
                    0.0,
                    Vector1::new(1.0),
                    Vector1::new(0.0),
                    &ts,
                    &floor,
                );
                fingerprint(&run, d)
            },
        );
        case(
            format!("pendulum_wall {} {tol:e}", m.id()),
            dump,
            &mut |d| {
                let run = method.integrate_with_events(
                    &swing,
                    0.0,
                    Vector1::new(1.0),
                    Vector1::new(0.0),
                    &ts,
                    &wall,
                );
                fingerprint(&run, d)
            },
        );
        case(
            format!("double_pendulum section {} {tol:e}", m.id()),
            dump,
            &mut |d| {
                let run = method.integrate_with_events(&dp, 0.0, qd, vd, &ts, &section);
                fingerprint(&run, d)
            },
        );
    }

    // Contact scenes: four corners of a tumbling box (impacts, sliding,
    // sticking) and a block on a belt (stick-slip), every method.
    let boxed = TumblingBox::new(2.0, 0.6, 0.3, 9.81, 0.4, 0.5);
    let belt = BlockOnBelt::new(1.0, 9.81, 40.0, 0.3, 0.6, 0.4);
    let ts = times(0.1, 15);
    for (m, tol) in every(false) {
        let method = m.integrator(1e-3, tol);
        let settings = lagrange::contact::ContactSettings::default();
        case(
            format!("contact tumbling_box {} {tol:e}", m.id()),
            dump,
            &mut |d| {
                let (q, v) = (
                    SVector::from([0.0, 0.5, 0.3]),
                    SVector::from([0.8, 0.0, 4.0]),
                );
                let run = lagrange::contact::integrate(&method, &boxed, 0.0, q, v, &ts, settings);
                contact_fingerprint(&run, d)
            },
        );
        case(format!("contact belt {} {tol:e}", m.id()), dump, &mut |d| {
            let (q, v) = (Vector2::zeros(), Vector2::new(0.3, 0.0));
            let run = lagrange::contact::integrate(&method, &belt, 0.0, q, v, &ts, settings);
            contact_fingerprint(&run, d)
        });
    }

    // Frame by frame, every method a stepper takes.
    macro_rules! steppers {
        ($($name:literal => $method:expr),* $(,)?) => {$(
            case(format!("stepper double_pendulum {}", $name), dump, &mut |d| {
                let (dp, q, v) = DoublePendulum::<f64>::regular();
                stepped(dp, $method, (q, v), 60, 1.0 / 60.0, None, d)
            });
            case(format!("stepper cartesian_pendulum {}", $name), dump, &mut |d| {
                let pendulum = CartesianPendulum::new(1.0, 1.0, 9.81);
                stepped(pendulum, $method, pendulum.state(1.0, 0.0), 60, 1.0 / 60.0, None, d)
            });
            case(format!("stepper bouncing_ball {}", $name), dump, &mut |d| {
                let start = (Vector1::new(1.0), Vector1::new(0.0));
                stepped(ball, $method, start, 180, 1.0 / 60.0, Some(&floor), d)
            });
        )*};
    }
    steppers! {
        "explicit_euler" => ExplicitEuler::new(1e-3),
        "symplectic_euler" => SymplecticEuler::new(1e-3),
        "rk4" => Rk4::new(4e-3),
        "implicit_midpoint" => ImplicitMidpoint::new(4e-3),
        "gauss_legendre_2" => GaussLegendre::two_stage(8e-3),
        "dopri5" => Dopri5::new().rtol(1e-8).atol(1e-8),
        "dop853" => Dop853::new().rtol(1e-11).atol(1e-11),
        "radau5" => Radau5::new().rtol(1e-8).atol(1e-8),
        "variational" => Variational::new(4e-3),
    }
    out
}

#[test]
fn every_methods_results_keep_their_bits() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/fingerprints.txt");
    let mut dump = String::new();
    let got = cases(&mut dump);
    let text: String = got
        .iter()
        .map(|(name, hash)| format!("{hash:016x} {name}\n"))
        .collect();
    if let Ok(file) = std::env::var("FINGERPRINT_DUMP") {
        std::fs::write(file, &dump).expect("writes the dump");
    }
    if std::env::var_os("LAGRANGE_BLESS").is_some() {
        std::fs::write(path, &text).expect("writes the fingerprints");
        return;
    }
    let recorded = std::fs::read_to_string(path).expect("tests/data/fingerprints.txt");
    let recorded: std::collections::BTreeMap<&str, &str> = recorded
        .lines()
        .filter_map(|line| line.split_once(' ').map(|(hash, name)| (name, hash)))
        .collect();
    let mut wrong = Vec::new();
    for (name, hash) in &got {
        match recorded.get(name.as_str()) {
            None => wrong.push(format!("new, not recorded: {name}")),
            Some(old) if *old != format!("{hash:016x}") => wrong.push(format!("moved: {name}")),
            Some(_) => {}
        }
    }
    for name in recorded.keys() {
        if !got.iter().any(|(n, _)| n == name) {
            wrong.push(format!("recorded, no longer run: {name}"));
        }
    }
    assert!(
        wrong.is_empty(),
        "{} of {} cases differ from tests/data/fingerprints.txt (re-bless with \
         LAGRANGE_BLESS=1 and say why):\n{}",
        wrong.len(),
        got.len(),
        wrong.join("\n")
    );
}
