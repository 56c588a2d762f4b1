//! A pendulum against a wall: impact times against the exact swing.
//!
//! Between impacts the motion is a pendulum released from rest at the
//! current amplitude (run backwards, then forwards), so each impact time
//! is a root of the exact `θ(t)` of `support::elliptic`, found here by
//! bisection in `f64`, and each new amplitude follows from energy
//! ([`PendulumWall::amplitude_after`]): no integrator is involved.

use lagrange::models::{Method, Pendulum, PendulumWall};
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
fn time_to_wall(amplitude: f64) -> f64 {
    let (theta, quarter) = released_from_rest(G.sqrt(), amplitude);
    let (mut before, mut after) = (quarter, 2.0 * quarter);
    loop {
        let mid = 0.5 * (before + after);
        if mid <= before || mid >= after {
            return after;
        }
        if theta(mid).0 > -WALL.beta {
            before = mid;
        } else {
            after = mid;
        }
    }
}

/// The first `n` impact times: the first fall, then each arc after an
/// impact, out to the new amplitude and back, twice that amplitude's fall.
fn exact_impacts(n: usize) -> Vec<f64> {
    let (mut t, mut amplitude) = (time_to_wall(RELEASE), RELEASE);
    let mut impacts = vec![t];
    for _ in 1..n {
        amplitude = WALL.amplitude_after(amplitude);
        t += 2.0 * time_to_wall(amplitude);
        impacts.push(t);
    }
    impacts
}

#[test]
fn impact_times_match_the_exact_swing() {
    let exact = exact_impacts(IMPACTS);
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
