//! Numerical stability at the extremes: Kepler orbits of eccentricity 0.6
//! and 0.9 over up to 10⁴ periods with a fixed step. Over runs this long the
//! methods part ways not by order but by kind: the energy error of the
//! symplectic and symmetric methods stays bounded, RK4's drifts linearly,
//! explicit Euler's runs away; and the angular momentum `x ẏ − y ẋ`, a
//! quadratic invariant in Cartesian coordinates, is kept to round-off by the
//! Gauss methods and lost at the truncation error by RK4.
//!
//! **How growth is measured.** The energy error of a symplectic method
//! oscillates along the orbit with a sharp peak at pericentre (at e = 0.9 a
//! pericentre passage takes about 1/300 of the period). Every step is
//! sampled and each orbit keeps its worst error; windows of doubling length
//! (orbit 1, 2, 3–4, 5–8, …, the last cut at the run's end) keep the worst of
//! their orbits, and the least-squares slope of log(worst) against log(end of
//! window) is the *growth exponent*: 0 for a bounded error, 1 for linear
//! drift, ½ for a random walk. Sampling once per orbit at a slowly sliding
//! phase would read the oscillation as growth.
//!
//! Each orbit is one `integrate` call sampling every step, started from the
//! previous orbit's last sample, so memory holds one orbit. Restarting is
//! exact for the one-step methods, whose state is `(q, q̇)`; `Variational`
//! converts `q̇ ↔ p` at each restart, exact for `M = I` and one rounding per
//! orbit in polar coordinates, far below its `O(h²)` energy error.
//!
//! The figures (for STABILITY.md):
//! `cargo test --release --test extremes -- kepler:: --nocapture` (a few
//! seconds). The full 10⁴-period runs are ignored in CI (about two minutes
//! on two cores):
//! `cargo test --release --test extremes -- kepler:: --ignored --nocapture`.

use std::f64::consts::PI;
use std::sync::OnceLock;
use std::time::Instant;

use crate::support::fit::log_slope;
use lagrange::models::{Kepler, Method, PolarKepler};
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;

/// The period of every orbit here: semi-major axis 1, μ = 1.
const PERIOD: f64 = 2.0 * PI;
const EPS: f64 = f64::EPSILON;

type V2 = Vector2<f64>;

/// Start at pericentre of the orbit of eccentricity `e`.
fn cartesian_start(e: f64) -> (V2, V2) {
    Kepler::new(1.0).pericentre(e)
}

fn polar_start(e: f64) -> (V2, V2) {
    PolarKepler::new(1.0).pericentre(e)
}

fn cartesian_angular_momentum(q: &V2, v: &V2) -> f64 {
    Kepler::angular_momentum(q, v)
}

fn polar_angular_momentum(q: &V2, v: &V2) -> f64 {
    PolarKepler::angular_momentum(q, v)
}

/// One long run: the worst relative errors of each completed orbit.
struct Flight {
    label: String,
    method: Method,
    /// Worst `|E − E₀| / |E₀|` over the steps of each orbit.
    energy: Vec<f64>,
    /// Worst `|L − L₀| / |L₀|` likewise.
    momentum: Vec<f64>,
    steps: usize,
    seconds: f64,
    failure: Option<String>,
}

/// Flies `orbits` periods of `steps_per_orbit` equal steps, one orbit per
/// call, sampling every step (see the module documentation).
fn fly<L: Lagrangian<2, Scalar = f64>>(
    label: &str,
    method: Method,
    model: &L,
    start: (V2, V2),
    angular_momentum: fn(&V2, &V2) -> f64,
    steps_per_orbit: usize,
    orbits: usize,
) -> Flight {
    let h = PERIOD / steps_per_orbit as f64;
    let (e0, l0) = (
        model.energy(0.0, &start.0, &start.1),
        angular_momentum(&start.0, &start.1),
    );
    let mut flight = Flight {
        label: format!("{label} {method:?}, h = T/{steps_per_orbit}"),
        method,
        energy: Vec::with_capacity(orbits),
        momentum: Vec::with_capacity(orbits),
        steps: 0,
        seconds: 0.0,
        failure: None,
    };
    let clock = Instant::now();
    let mut state = start;
    let mut times = vec![0.0; steps_per_orbit];
    for orbit in 0..orbits {
        let first = orbit * steps_per_orbit;
        // Times from the global step index, so they do not accumulate error.
        for (j, t) in times.iter_mut().enumerate() {
            *t = (first + j + 1) as f64 * h;
        }
        let trajectory =
            match method
                .with_step(h)
                .integrate(model, first as f64 * h, state.0, state.1, &times)
            {
                Ok(trajectory) => trajectory,
                Err(failure) => {
                    flight.failure = Some(format!("{} in orbit {}", failure.error, orbit + 1));
                    break;
                }
            };
        let (mut de, mut dl) = (0.0f64, 0.0f64);
        for s in &trajectory {
            de = de.max(((model.energy(s.t, &s.q, &s.qdot) - e0) / e0).abs());
            dl = dl.max(((angular_momentum(&s.q, &s.qdot) - l0) / l0).abs());
        }
        flight.energy.push(de);
        flight.momentum.push(dl);
        flight.steps += trajectory.stats().steps_accepted;
        let last = trajectory.last().unwrap();
        state = (last.q, last.qdot);
    }
    flight.seconds = clock.elapsed().as_secs_f64();
    flight
}

/// `(end of window in orbits, worst in window)` over windows of doubling
/// length: orbit 1, orbit 2, orbits 3–4, 5–8, …, the last cut at the end.
fn windows(per_orbit: &[f64]) -> Vec<(f64, f64)> {
    let worst = |xs: &[f64]| xs.iter().copied().fold(0.0, f64::max);
    let mut out = Vec::new();
    let (mut lo, mut hi) = (0, 1);
    while lo < per_orbit.len() {
        let end = hi.min(per_orbit.len());
        out.push((end as f64, worst(&per_orbit[lo..end])));
        (lo, hi) = (end, 2 * end);
    }
    out
}

/// Least-squares slope of log(worst) against log(end) over `windows`.
/// Errors below ε/2, the resolution of a relative difference of order-one
/// numbers, count as ε/2.
fn growth_exponent(windows: &[(f64, f64)]) -> f64 {
    let (ends, worst): (Vec<f64>, Vec<f64>) =
        windows.iter().map(|w| (w.0, w.1.max(EPS / 2.0))).unzip();
    log_slope(&ends, &worst)
}

/// The growth exponent, where there are enough windows to fit one.
fn exponent_text(windows: &[(f64, f64)]) -> String {
    if windows.len() < 3 {
        return "—".into();
    }
    format!("{:+.3}", growth_exponent(windows))
}

fn sci(windows: &[(f64, f64)]) -> String {
    let parts: Vec<String> = windows.iter().map(|w| format!("{:.1e}", w.1)).collect();
    parts.join(" ")
}

impl Flight {
    fn energy_windows(&self) -> Vec<(f64, f64)> {
        windows(&self.energy)
    }

    fn energy_exponent(&self) -> f64 {
        growth_exponent(&self.energy_windows())
    }

    /// The worst energy error of the first orbit and of the last window.
    fn energy_first_and_last(&self) -> (f64, f64) {
        let w = self.energy_windows();
        (w[0].1, w[w.len() - 1].1)
    }

    fn momentum_worst(&self) -> f64 {
        self.momentum.iter().copied().fold(0.0, f64::max)
    }

    /// The run and its energy figures.
    fn print(&self) {
        let (first, last) = self.energy_first_and_last();
        let energy = self.energy_windows();
        println!(
            "{}: {} orbits, {} steps, {:.2} s ({:.0} ns/step){}\n  \
             energy: first orbit {first:.2e}, last window {last:.2e}, exponent {}; windows {}",
            self.label,
            self.energy.len(),
            self.steps,
            self.seconds,
            self.seconds * 1e9 / self.steps as f64,
            self.failure
                .as_ref()
                .map(|f| format!(", stopped: {f}"))
                .unwrap_or_default(),
            exponent_text(&energy),
            sci(&energy),
        );
    }

    /// The angular momentum figures: the worst relative change against the
    /// linear (`K ε`) and random-walk (`√K ε`) scales.
    fn print_momentum(&self) {
        let momentum = windows(&self.momentum);
        let (worst, k) = (self.momentum_worst(), self.steps as f64);
        println!(
            "{}: |ΔL|/L worst {worst:.2e} after {k:.0e} steps = {:.3} K ε = {:.2} √K ε, \
             exponent {}; windows {}",
            self.label,
            worst / (k * EPS),
            worst / (k.sqrt() * EPS),
            exponent_text(&momentum),
            sci(&momentum),
        );
    }
}

/// A symplectic or symmetric method on a reversible orbit: by backward
/// error analysis it follows a modified Hamiltonian `H̃ = H + O(hᵖ)` exactly
/// (up to exponentially small terms), so `|H − H₀|` stays at its `O(hᵖ)`
/// oscillation amplitude: exponent 0. The bound 0.05 allows for the one
/// bias of the measurement: the step grid slides slowly against the
/// pericentre, so later windows see phases the first orbit did not, and the
/// envelope creeps up until it has seen them all (measured: under 1% at
/// e = 0.6, T/100; 5% for Gauss–Legendre 2 at e = 0.9, T/1000, exponent
/// 0.005; an exponent of 0.05 over 10⁴ orbits would be a factor 1.6).
/// Linear drift gives 1.
#[track_caller]
fn assert_bounded(flight: &Flight) {
    assert!(
        flight.failure.is_none(),
        "{}: {:?}",
        flight.label,
        flight.failure
    );
    let p = flight.energy_exponent();
    let (first, last) = flight.energy_first_and_last();
    assert!(p.abs() <= 0.05, "{}: energy exponent {p:.3}", flight.label);
    assert!(
        last <= 1.25 * first,
        "{}: energy error {first:.2e} in orbit 1, {last:.2e} at the end",
        flight.label
    );
}

/// RK4 is neither symplectic nor symmetric: each orbit adds an `O(h⁴)`
/// energy error of the same sign, so while the error is small (below 10%,
/// where the orbit is still close to the original one) it grows linearly:
/// exponent 1 ± 0.2.
#[track_caller]
fn assert_drifts_linearly(flight: &Flight) {
    let small: Vec<(f64, f64)> = flight
        .energy_windows()
        .into_iter()
        .take_while(|w| w.1 < 0.1)
        .collect();
    assert!(small.len() >= 5, "{}: too few windows", flight.label);
    let p = growth_exponent(&small);
    println!(
        "  {}: exponent {p:.3} over the {} windows with error below 10%",
        flight.label,
        small.len()
    );
    assert!((p - 1.0).abs() <= 0.2, "{}: exponent {p:.3}", flight.label);
}

/// The angular momentum `x ẏ − y ẋ` is quadratic in `(q, q̇)`, and Gauss
/// methods (midpoint included) conserve every quadratic invariant exactly
/// when their stage equations are solved exactly. They are solved until the
/// Newton correction is below 10 ε of the state (`implicit_rk.rs`; 10 ε of
/// the residual for `Variational`, whose discrete Noether theorem keeps the
/// rotation's momentum), so a step may move `L` by about 10 ε relative; the
/// leftover has the same sign step after step on a smooth orbit, so in the
/// worst case it adds up linearly: `|ΔL| / L ≤ 10 K ε` after `K` steps.
/// Symplectic Euler keeps `L` exactly in exact arithmetic (`q × a = 0` for a
/// central force, and `q_{n+1} × q̇_{n+1} = q_n × q̇_{n+1}`), so only the
/// rounding of each update remains, of either sign: a random walk, whose
/// excursions stay below 10 √K ε (a few standard deviations of ε √K).
#[track_caller]
fn assert_momentum_kept(flight: &Flight) {
    let (worst, k) = (flight.momentum_worst(), flight.steps as f64);
    let bound = if flight.method == Method::SymplecticEuler {
        10.0 * k.sqrt() * EPS
    } else {
        10.0 * k * EPS
    };
    assert!(
        worst <= bound,
        "{}: |ΔL|/L = {worst:.2e} after {k} steps, bound {bound:.2e}",
        flight.label
    );
}

/// The e = 0.6 orbit in Cartesian coordinates at h = T/100 (pericentre
/// passage ≈ 0.2 time units, three steps): coarse, but every method here is
/// stable at it and `Variational` still converges (it fails to at T/40).
fn cartesian_e06(method: Method, orbits: usize) -> Flight {
    let model = Kepler::new(1.0);
    let label = "cartesian e = 0.6";
    let start = cartesian_start(0.6);
    fly(
        label,
        method,
        &model,
        start,
        cartesian_angular_momentum,
        100,
        orbits,
    )
}

/// The CI runs, shared by the tests that read them: the cheap methods fly
/// 10⁴ orbits (10⁶ steps), Gauss–Legendre 2000 (2·10⁵ steps, under a second
/// for both; the ignored test flies them 10⁴).
fn cartesian_e06_flights() -> &'static [Flight] {
    static FLIGHTS: OnceLock<Vec<Flight>> = OnceLock::new();
    FLIGHTS.get_or_init(|| {
        vec![
            cartesian_e06(Method::SymplecticEuler, 10_000),
            cartesian_e06(Method::Rk4, 10_000),
            cartesian_e06(Method::ImplicitMidpoint, 10_000),
            cartesian_e06(Method::Variational, 10_000),
            cartesian_e06(Method::GaussLegendre2, 2000),
            cartesian_e06(Method::GaussLegendre3, 2000),
        ]
    })
}

fn find(flights: &[Flight], method: Method) -> &Flight {
    flights.iter().find(|f| f.method == method).unwrap()
}

/// Symplectic Euler, the midpoint rule, Gauss–Legendre 2 and 3 (symplectic
/// for constant M) and the variational integrator keep the energy error of
/// the e = 0.6 orbit at its first-orbit level with no trend, over 10⁴ orbits
/// (2000 for Gauss–Legendre in CI; 10⁴ in the ignored test).
#[test]
fn symplectic_methods_keep_the_e06_kepler_energy_error_bounded_without_trend() {
    let flights = cartesian_e06_flights();
    for flight in flights.iter().filter(|f| f.method != Method::Rk4) {
        flight.print();
        assert_bounded(flight);
    }
}

/// RK4 at the same step drifts: linearly while the error is small; then
/// the orbit decays ever faster until a close pericentre passage flings it
/// out (measured: E = −0.61 at orbit 1000, −1.32 at 3900, +131 at 4000,
/// from E₀ = −0.5).
#[test]
fn rk4_energy_error_drifts_linearly_on_the_e06_kepler_orbit() {
    let rk4 = find(cartesian_e06_flights(), Method::Rk4);
    rk4.print();
    assert_drifts_linearly(rk4);
}

/// Angular momentum in Cartesian coordinates, a quadratic invariant, is kept
/// to round-off by the Gauss methods, the variational integrator and
/// symplectic Euler over 10⁶ steps (bounds in [`assert_momentum_kept`]);
/// RK4 loses it at its truncation error, many orders above the same bound.
#[test]
fn cartesian_angular_momentum_is_kept_to_round_off_over_a_million_steps() {
    let flights = cartesian_e06_flights();
    for flight in flights.iter().filter(|f| f.method != Method::Rk4) {
        flight.print_momentum();
        assert_momentum_kept(flight);
    }
    let rk4 = find(flights, Method::Rk4);
    rk4.print_momentum();
    let (worst, bound) = (rk4.momentum_worst(), 10.0 * rk4.steps as f64 * EPS);
    println!("  rk4: {:.0e} × the Gauss bound", worst / bound);
    assert!(worst > 1e3 * bound, "rk4 kept L to {worst:.2e}");
}

/// With M(q) = diag(1, r²) the variational integrator is still symplectic
/// (it works in (q, p)) and its energy error stays bounded; the Gauss
/// methods applied in (q, q̇) are not symplectic there, but symmetric, and on
/// this reversible, integrable orbit they show no drift either (Hairer,
/// Lubich & Wanner, ch. XI). Variational 10⁴ orbits, Gauss–Legendre 1000
/// (10⁴ in the ignored test).
#[test]
fn polar_kepler_energy_stays_bounded_for_variational_and_gauss_legendre() {
    for flight in polar_e06_flights(1000) {
        flight.print();
        assert_bounded(&flight);
    }
}

fn polar_e06_flights(gauss_orbits: usize) -> Vec<Flight> {
    let model = PolarKepler::new(1.0);
    let start = polar_start(0.6);
    let run = |method, orbits| {
        let label = "polar e = 0.6";
        fly(
            label,
            method,
            &model,
            start,
            polar_angular_momentum,
            100,
            orbits,
        )
    };
    vec![
        run(Method::Variational, 10_000),
        run(Method::GaussLegendre2, gauss_orbits),
        run(Method::GaussLegendre3, gauss_orbits),
    ]
}

/// Explicit Euler gains energy at every pericentre passage. At T/100,
/// where symplectic Euler holds 26%, it escapes (E ≥ 0) within the first
/// orbit; at T/16 000 it still gains about 1.4% of |E| in the first orbit
/// and keeps gaining, every window worse than the one before (the orbit
/// spirals outwards), at least 10× its first-orbit error within 64 orbits.
#[test]
fn explicit_euler_spirals_out_of_the_e06_kepler_orbit() {
    let model = Kepler::new(1.0);
    let start = cartesian_start(0.6);
    let coarse = fly(
        "cartesian e = 0.6",
        Method::ExplicitEuler,
        &model,
        start,
        cartesian_angular_momentum,
        100,
        1,
    );
    coarse.print();
    assert!(
        coarse.energy[0] >= 1.0,
        "E − E₀ = {:.2} |E₀|",
        coarse.energy[0]
    );

    let fine = fly(
        "cartesian e = 0.6",
        Method::ExplicitEuler,
        &model,
        start,
        cartesian_angular_momentum,
        16_000,
        64,
    );
    fine.print();
    let w = fine.energy_windows();
    assert!(w.windows(2).all(|p| p[1].1 > p[0].1), "{}", sci(&w));
    let (first, last) = fine.energy_first_and_last();
    assert!(last >= 10.0 * first, "{first:.2e} → {last:.2e}");
}

/// The e = 0.9 orbit at h = T/1000 (pericentre passage ≈ 0.02 time units,
/// three steps). Every symplectic or symmetric method keeps a bounded energy
/// error (symplectic Euler 93%, midpoint and variational 10%, Gauss–Legendre
/// 2 6e-5, 3 3e-7), RK4 drifts linearly (and over 10⁴ orbits loses the
/// orbit: 4 |E₀| by orbit 4096), and the Gauss methods keep L to round-off.
fn e09_flights(orbits: usize) {
    let model = Kepler::new(1.0);
    let start = cartesian_start(0.9);
    let label = "cartesian e = 0.9";
    let run = |method| {
        fly(
            label,
            method,
            &model,
            start,
            cartesian_angular_momentum,
            1000,
            orbits,
        )
    };
    for method in [
        Method::SymplecticEuler,
        Method::ImplicitMidpoint,
        Method::GaussLegendre2,
        Method::GaussLegendre3,
        Method::Variational,
    ] {
        let flight = run(method);
        flight.print();
        flight.print_momentum();
        assert_bounded(&flight);
        assert_momentum_kept(&flight);
    }
    let rk4 = run(Method::Rk4);
    rk4.print();
    assert_drifts_linearly(&rk4);

    let polar = PolarKepler::new(1.0);
    let polar_start = polar_start(0.9);
    for method in [Method::Variational, Method::GaussLegendre2] {
        let flight = fly(
            "polar e = 0.9",
            method,
            &polar,
            polar_start,
            polar_angular_momentum,
            1000,
            orbits,
        );
        flight.print();
        assert_bounded(&flight);
    }
}

/// 100 orbits of e = 0.9 (10⁵ steps per method).
#[test]
fn e09_kepler_energy_is_bounded_for_symplectic_methods_and_drifts_for_rk4() {
    e09_flights(100);
}

/// The full 10⁴ orbits of e = 0.9: 10⁷ steps per method, about a minute and
/// a half on two cores.
#[test]
#[ignore = "10⁷ steps per method; run with --ignored"]
fn e09_kepler_over_ten_thousand_orbits() {
    e09_flights(10_000);
}

/// Gauss–Legendre 2 and 3 over the full 10⁴ orbits of e = 0.6, Cartesian and
/// polar (10⁶ steps each, about twenty seconds).
#[test]
#[ignore = "10⁶ implicit steps per method; run with --ignored"]
fn e06_gauss_legendre_over_ten_thousand_orbits() {
    for method in [Method::GaussLegendre2, Method::GaussLegendre3] {
        let flight = cartesian_e06(method, 10_000);
        flight.print();
        flight.print_momentum();
        assert_bounded(&flight);
        assert_momentum_kept(&flight);
    }
    for flight in polar_e06_flights(10_000) {
        flight.print();
        assert_bounded(&flight);
    }
}
