//! A pendulum against a wall: impact times against the exact swing.
//!
//! Between impacts the motion is a pendulum released from rest at the
//! current amplitude (run backwards, then forwards), so each impact time
//! is a root of the exact `θ(t)` of `support::elliptic`, found here by
//! bisection in `f64`, and each new amplitude follows from energy
//! ([`PendulumWall::amplitude_after`]): no integrator is involved.

use lagrange::Method;
use lagrange::models::{Pendulum, PendulumWall};
use lagrange::nalgebra::Vector1;
use lagrange::prelude::*;

use crate::support::elliptic::released_from_rest;

const G: f64 = 9.81;
const RELEASE: f64 = 1.0;
const WALL: PendulumWall = PendulumWall {
    beta: 0.2,
    restitution: 0.8,
};
const IMPACTS: usize = 10;

/// The time a pendulum released from rest at `amplitude` takes to reach the
/// wall, through the bottom: the root of `θ(t) = −β` on the second quarter
/// period, where `θ` falls from 0 to `−amplitude`, bisected to adjacent
/// floating-point numbers.
fn time_to_wall(wall: &PendulumWall, amplitude: f64) -> f64 {
    let (theta, quarter) = released_from_rest(G.sqrt(), amplitude);
    let (mut before, mut after) = (quarter, 2.0 * quarter);
    loop {
        let mid = 0.5 * (before + after);
        if mid <= before || mid >= after {
            return after;
        }
        if theta(mid).0 > -wall.beta {
            before = mid;
        } else {
            after = mid;
        }
    }
}

/// The first `n` impact times: the first fall, then each arc after an
/// impact, out to the new amplitude and back, twice that amplitude's fall.
fn exact_impacts(wall: &PendulumWall, n: usize) -> Vec<f64> {
    let (mut t, mut amplitude) = (time_to_wall(wall, RELEASE), RELEASE);
    let mut impacts = vec![t];
    for _ in 1..n {
        amplitude = wall.amplitude_after(amplitude);
        t += 2.0 * time_to_wall(wall, amplitude);
        impacts.push(t);
    }
    impacts
}

#[test]
fn impact_times_match_the_exact_swing() {
    let exact = exact_impacts(&WALL, IMPACTS);
    let pendulum = Pendulum::new(1.0, 1.0, G);
    let (q0, v0) = (Vector1::new(RELEASE), Vector1::new(0.0));
    println!("impact  exact t              error by method and tolerance");
    let mut table = vec![String::new(); IMPACTS];
    for (method, tol) in [
        (Method::Dopri5, 1e-10),
        (Method::Dop853, 1e-12),
        (Method::Radau5, 1e-12),
    ] {
        let events = Events::new().with(WALL.event());
        let run = method
            .with_tolerance(tol)
            .integrate_with_events(&pendulum, 0.0, q0, v0, &[exact[IMPACTS - 1] + 0.5], &events)
            .unwrap();
        let impacts = run.events();
        assert!(
            impacts.len() >= IMPACTS,
            "{method:?}: {} impacts",
            impacts.len()
        );
        for (k, (impact, t)) in impacts.iter().zip(&exact).enumerate() {
            let error = impact.t - t;
            table[k] += &format!("  {}@{tol:.0e}: {error:+.1e}", method.id());
            assert!((impact.q[0] + WALL.beta).abs() < 1e-12);
            // An impact's time error is the angle error at the wall over
            // |θ̇| there, which falls with the amplitude to 0.3 rad/s by the
            // tenth impact; the angle error of these methods grows by about
            // tol to 10 tol per second here (Radau5, the least accurate
            // per tolerance, ~10 tol at 1e-10 over five periods: see its
            // docs). So 100 tol (1 + t); the time tolerance, ~4 ε t, is far
            // below.
            let bound = 100.0 * tol * (1.0 + t);
            assert!(error.abs() < bound, "{method:?}, impact {k}: {error:e}");
        }
    }
    for (k, row) in table.iter().enumerate() {
        println!("{:>6}  {:.15}{row}", k + 1, exact[k]);
    }
}

/// A wall at −0.3 rad: the amplitude falls towards 0.3, so after a few
/// dozen impacts the pendulum only grazes the wall, and the motion the
/// integrator follows without the impact (through the wall and back)
/// dips below `θ = −β` for less than a step. Every impact must still be
/// found, with no bound on the step: the dip is seen in the rate of `g`
/// along each step's interpolant.
#[test]
fn grazing_impacts_are_all_found_without_a_step_bound() {
    const GRAZING: PendulumWall = PendulumWall {
        beta: 0.3,
        restitution: 0.8,
    };
    const IMPACTS: usize = 40;
    let exact = exact_impacts(&GRAZING, IMPACTS);
    let pendulum = Pendulum::new(1.0, 1.0, G);
    let (q0, v0) = (Vector1::new(RELEASE), Vector1::new(0.0));
    let end = [exact[IMPACTS - 1] + 0.1];
    for (method, setting) in [
        (Method::Dop853, 1e-12),
        (Method::Dopri5, 1e-10),
        (Method::Radau5, 1e-10),
        (Method::Rk4, 1e-3),
    ] {
        let events = Events::new().with(GRAZING.event());
        let run = method
            .integrator(setting, setting)
            .integrate_with_events(&pendulum, 0.0, q0, v0, &end, &events)
            .unwrap();
        let impacts = run.events();
        let mut worst: f64 = 0.0;
        for (k, t) in exact.iter().enumerate() {
            let Some(impact) = impacts.get(k) else {
                panic!("{method:?}: impact {} of {IMPACTS} missed", k + 1);
            };
            let error = impact.t - t;
            worst = worst.max(error.abs());
            // An impact's time error is the angle error at the wall over
            // |θ̇| there, as above, and |θ̇| falls to 5e-4 rad/s by the
            // 40th impact: the angle error of 100 tol (1 + t) for the
            // adaptive methods (see above), over |θ̇| where that is below
            // 1. RK4 at h = 1e-3 errs by ~h⁴ per unit of time and its
            // Hermite interpolant by h⁴/384 |θ⁗|: 1e-9 (1 + t) bounds both.
            let angle = if method.is_adaptive() {
                100.0 * setting
            } else {
                1e-9
            };
            let bound = angle * (1.0 + t) / impact.qdot[0].abs().min(1.0);
            assert!(
                error.abs() < bound,
                "{method:?}, impact {}: {error:e} at t = {t}",
                k + 1
            );
        }
        assert_eq!(impacts.len(), IMPACTS, "{method:?}: an impact too many");
        println!(
            "{}: {IMPACTS} impacts, worst time error {worst:.1e} (last at t = {:.1})",
            method.id(),
            exact[IMPACTS - 1]
        );
    }
}
