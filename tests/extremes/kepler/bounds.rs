//! What each kind of method must show over a long run.

use super::EPS;
use super::flight::{Flight, growth_exponent};
use lagrange::Method;

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
pub(super) fn assert_bounded(flight: &Flight) {
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
pub(super) fn assert_drifts_linearly(flight: &Flight) {
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
pub(super) fn assert_momentum_kept(flight: &Flight) {
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
