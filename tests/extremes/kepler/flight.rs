//! One long run and how its growth is measured (see the module above).

use std::time::Instant;

use super::{EPS, PERIOD, V2};
use crate::support::fit::log_slope;
use lagrange::Method;
use lagrange::prelude::*;

/// One long run: the worst relative errors of each completed orbit.
pub(super) struct Flight {
    pub(super) label: String,
    pub(super) method: Method,
    /// Worst `|E − E₀| / |E₀|` over the steps of each orbit.
    pub(super) energy: Vec<f64>,
    /// Worst `|L − L₀| / |L₀|` likewise.
    pub(super) momentum: Vec<f64>,
    pub(super) steps: usize,
    pub(super) seconds: f64,
    pub(super) failure: Option<String>,
}

/// Flies `orbits` periods of `steps_per_orbit` equal steps, one orbit per
/// call, sampling every step (see the module documentation).
pub(super) fn fly<L: Lagrangian<2, Scalar = f64>>(
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
pub(super) fn growth_exponent(windows: &[(f64, f64)]) -> f64 {
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

pub(super) fn sci(windows: &[(f64, f64)]) -> String {
    let parts: Vec<String> = windows.iter().map(|w| format!("{:.1e}", w.1)).collect();
    parts.join(" ")
}

impl Flight {
    pub(super) fn energy_windows(&self) -> Vec<(f64, f64)> {
        windows(&self.energy)
    }

    pub(super) fn energy_exponent(&self) -> f64 {
        growth_exponent(&self.energy_windows())
    }

    /// The worst energy error of the first orbit and of the last window.
    pub(super) fn energy_first_and_last(&self) -> (f64, f64) {
        let w = self.energy_windows();
        (w[0].1, w[w.len() - 1].1)
    }

    pub(super) fn momentum_worst(&self) -> f64 {
        self.momentum.iter().copied().fold(0.0, f64::max)
    }

    /// The run and its energy figures.
    pub(super) fn print(&self) {
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
    pub(super) fn print_momentum(&self) {
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
