//! Numerical stability at the extremes: a pendulum a millionth of its
//! energy range from the separatrix, against the exact solution in Jacobi
//! elliptic functions (`tests/support/elliptic.rs`).
//!
//! `θ̈ = −ω₀² sin θ` (here `ω₀ = 1`) started at the bottom with
//! `θ̇ = 2 ω₀ κ`: the energy above the bottom is `2 κ²` (units `m g l`),
//! the separatrix at `κ = 1`. With `κ² = 1 ∓ δ`, `δ = 10⁻⁶`:
//!
//! - just below, a libration that creeps up to `π − 2√δ` and back: period
//!   `4 K(κ) ≈ 2 ln(16/δ) = 33.2` instead of 2π;
//! - just above, a rotation that crawls over the top once per revolution,
//!   `2 K(1/κ)/κ ≈ 16.6`.
//!
//! Near the top the pendulum sits by the unstable equilibrium, where
//! perturbations grow like `e^t`, and the period depends on the energy like
//! `ln(1/δ)`: an energy error `ΔE` shifts every later pass by `~ΔE/δ`. So
//! after the first pass the error is the tolerance amplified ~10⁶ times, by
//! the problem, not the method; the bounds below carry that growth,
//! computed from the exact solution's own derivatives. Step control must
//! not stall in the slow creep either.
//!
//! Every test prints the figures quoted in STABILITY.md; run with
//! `cargo test --release --test suite -- extremes::separatrix:: --nocapture`.

use crate::support::elliptic::{Swing, complete_k, jacobi};
use lagrange::IntegrationResult;
use lagrange::Method;
use lagrange::models::Pendulum;
use lagrange::nalgebra::Vector1;
use lagrange::prelude::*;

/// `g = l = 1`: `ω₀ = 1`, energies in units of `m g l`.
fn pendulum() -> Pendulum {
    Pendulum::new(1.0, 1.0, 1.0)
}

/// `κ² = 1 − δ` (libration) or `1 + δ` (rotation).
fn swing(delta: f64, above: bool) -> Swing {
    let kappa = if above { 1.0 + delta } else { 1.0 - delta }.sqrt();
    Swing { omega0: 1.0, kappa }
}

/// From the bottom: `θ = 0`, `θ̇ = 2 κ`.
fn integrate<I: Integrator<f64>>(
    method: &I,
    s: &Swing,
    times: &[f64],
) -> IntegrationResult<f64, 1> {
    let v0 = 2.0 * s.omega0 * s.kappa;
    method.integrate(&pendulum(), 0.0, Vector1::new(0.0), Vector1::new(v0), times)
}

/// `(u, am(u), sn(u), dn(u))`.
type Row = (f64, f64, f64, f64);

/// 30-digit values from mpmath 1.3 (`ellipfun`, `ellipk`; `am` from
/// `atan2(sn, cn)` unwrapped by `u/4K`): `(u, am, sn, dn)` for
/// `k'² = 1/2, 10⁻⁶, 10⁻¹²`, and `K`.
#[allow(clippy::excessive_precision)]
const MPMATH: [(f64, f64, [Row; 5]); 3] = [
    (
        0.5,
        1.8540746773013719184,
        [
            (
                0.3,
                0.29779474912983027416,
                0.29341273316845538786,
                0.97824050417436120377,
            ),
            (
                2.5,
                2.0428964885549356885,
                0.89061518822609435595,
                0.7767897355465629868,
            ),
            (
                7.0,
                5.8726722814362782863,
                -0.39907978209954034503,
                0.95935794350163781755,
            ),
            (
                20.0,
                16.9959951128080968,
                -0.96028778672190989093,
                0.73411421681940464303,
            ),
            (
                55.5,
                47.001801191236021291,
                0.12178553730800158273,
                0.99628517074746258481,
            ),
        ],
    ),
    (
        1e-6,
        8.2940514636154399853,
        [
            (
                0.3,
                0.29559868036758412527,
                0.29131261664447189645,
                0.95662795497873235194,
            ),
            (
                2.5,
                1.4069949795675834232,
                0.98661452818385370167,
                0.16307282478935284949,
            ),
            (
                7.0,
                1.5691096390455253151,
                0.99999857754255529137,
                0.0019608442113332726928,
            ),
            (
                20.0,
                4.6464594497191024047,
                -0.99782743562184826579,
                0.065889334341132436823,
            ),
            (
                55.5,
                10.989155716388289008,
                -0.99997940104274928744,
                0.0064959563566033229735,
            ),
        ],
    ),
    (
        1e-12,
        15.201804919087715174,
        [
            (
                0.3,
                0.29559867598460852066,
                0.2913126124515950987,
                0.95662791190029136809,
            ),
            (
                2.5,
                1.406993568937564385,
                0.98661429815166032231,
                0.16307123193157068586,
            ),
            (
                7.0,
                1.5689725635063672024,
                0.99999833694419466549,
                0.0018237625516802022828,
            ),
            (
                20.0,
                1.5708569683219967416,
                0.99999999816130259605,
                0.00006064977167742232569,
            ),
            (
                55.5,
                4.7223002712077832367,
                -0.99995088355918609182,
                0.0099111286038957194357,
            ),
        ],
    ),
];

/// The reference itself first: the AGM implementation against mpmath, from
/// an ordinary modulus to a millionth of a millionth from 1. `K` to 4 ε
/// relative (a handful of AGM steps, each a rounding or two). `am`, `sn`
/// and `dn` to `1e-14 (1 + |u|)`: the argument's own rounding `ε |u|` is
/// carried through `φ_N = 2^N a_N u` and halved back `N` times, and each
/// halving step adds a rounding of `φ`. Measured: 85 ε at worst (`am` at
/// `u = 7`, `k'² = 1e-12`).
#[test]
fn jacobi_functions_match_thirty_digit_references() {
    let mut worst: f64 = 0.0;
    for (kp2, big_k, rows) in MPMATH {
        let kp = f64::sqrt(kp2);
        let k = ((1.0 - kp) * (1.0 + kp)).sqrt();
        let ours = complete_k(k, kp);
        assert!(
            (ours - big_k).abs() <= 4.0 * f64::EPSILON * big_k,
            "K: {ours} vs {big_k}"
        );
        for (u, am, sn, dn) in rows {
            let j = jacobi(u, k, kp);
            let bound = 1e-14 * (1.0 + u);
            for (what, got, want) in [("am", j.am, am), ("sn", j.sn, sn), ("dn", j.dn, dn)] {
                let error = (got - want).abs();
                assert!(
                    error <= bound,
                    "{what}({u} | k'² = {kp2}) = {got}, want {want}"
                );
                worst = worst.max(error / f64::EPSILON);
            }
        }
    }
    println!("Jacobi functions: worst error {worst:.0} ε against mpmath");
}

/// How much the flow amplifies errors up to `t`: perturbing the start along
/// the flow (`θ0`, since `ẏ(0) = (θ̇0, 0)`) moves `y(t)` by `|ẏ(t)|/θ̇0` per
/// unit; perturbing `θ̇0` changes the energy, by `|∂y(t)/∂θ̇0|` (central
/// differences of the exact solution, step `10⁻⁴ δ` in `κ`). The larger.
fn growth(s: &Swing, delta: f64, t: f64) -> f64 {
    let v0 = 2.0 * s.kappa;
    let dk = 1e-4 * delta;
    let plus = Swing {
        kappa: s.kappa + dk,
        ..*s
    }
    .state(t);
    let minus = Swing {
        kappa: s.kappa - dk,
        ..*s
    }
    .state(t);
    let energy_direction = (plus.0 - minus.0).abs().max((plus.1 - minus.1).abs()) / (4.0 * dk);
    let (theta, rate) = s.state(t);
    let flow_direction = rate.abs().max(theta.sin().abs()) / v0;
    energy_direction.max(flow_direction)
}

/// One adaptive method on one swing: the error at each sample against the
/// exact solution, within `C tol' · growth(t) · scale(t)` (`C tol'` as in
/// the other suites: `100 tol` for Dormand–Prince, `100 tol^(5/6)` for
/// Radau5; `scale = max(1, |y|)`); the energy, whose error is not
/// amplified, within `steps · tol' · 10` (per step at most `tol'` times
/// `Σ |∂E/∂y| (1 + |y|) ≤ (1 + π) + 2 · 3 < 10`), and below a tenth of the
/// gap to the separatrix (`2δ`): the run stays on its side.
fn check_adaptive<I: Integrator<f64>>(
    name: &str,
    method: &I,
    allowance: f64,
    delta: f64,
    above: bool,
) {
    let s = swing(delta, above);
    let quarter = s.quarter();
    let times: Vec<f64> = [1.0, 2.0, 3.0, 4.0, 8.0].map(|k| k * quarter).to_vec();
    let run = integrate(method, &s, &times).unwrap_or_else(|f| panic!("{name}: {f}"));
    let energy0 = 2.0 * s.kappa * s.kappa - 1.0;
    let stats = run.stats();
    let attempts = (stats.steps_accepted + stats.steps_rejected) as f64;
    let mut row = Vec::new();
    let mut worst_energy: f64 = 0.0;
    for sample in &run {
        let (theta, rate) = s.state(sample.t);
        let error = (sample.q[0] - theta)
            .abs()
            .max((sample.qdot[0] - rate).abs());
        let scale = 1f64.max(theta.abs()).max(rate.abs());
        let bound = allowance * growth(&s, delta, sample.t) * scale;
        assert!(
            error <= bound,
            "{name} at t = {:.2}: error {error:e} > {bound:e}",
            sample.t
        );
        let energy = pendulum().energy(sample.t, &sample.q, &sample.qdot);
        worst_energy = worst_energy.max((energy - energy0).abs());
        row.push(format!("{error:.1e} (≤ {bound:.0e})"));
    }
    let energy_bound = (attempts * allowance / 100.0 * 10.0).min(0.2 * delta);
    println!(
        "{} δ = {delta:.0e}, {name}: errors at T/4 (top), T/2, 3T/4, T, 2T: {}; energy error \
         {worst_energy:.1e} (gap {:.0e}); {} steps, {} rejected",
        if above { "rotation" } else { "libration" },
        row.join(", "),
        2.0 * delta,
        stats.steps_accepted,
        stats.steps_rejected
    );
    assert!(
        worst_energy <= energy_bound,
        "{name}: energy error {worst_energy:e}"
    );
    // On its side of the separatrix: a libration is back at the bottom,
    // moving backwards, after half a period; a rotation has gone round.
    let half = run.get(1).unwrap();
    if above {
        assert!((half.q[0] - 2.0 * std::f64::consts::PI).abs() < 1e-3);
    } else {
        assert!(half.q[0].abs() < 1e-3 && half.qdot[0] < 0.0);
    }
}

/// Just below the separatrix (`δ = 10⁻⁶`): every adaptive method follows
/// the exact libration at `tol = 1e-10` to the bound above: at the top
/// (`T/4`, `θ = π − 2√δ`) to ~`tol`, and after passing it, amplified by the
/// energy sensitivity `~1/δ`, to the growth the exact solution predicts.
#[test]
fn libration_a_millionth_below_the_separatrix_follows_the_elliptic_solution() {
    check_every_adaptive(1e-6, false);
}

/// Just above (`δ = 10⁻⁶`): the rotation crawls over the top once per
/// revolution; the same checks.
#[test]
fn rotation_a_millionth_above_the_separatrix_follows_the_elliptic_solution() {
    check_every_adaptive(1e-6, true);
}

/// [`check_adaptive`] for every adaptive method at `tol = 1e-10`.
fn check_every_adaptive(delta: f64, above: bool) {
    let tol = 1e-10;
    for method in Method::ADAPTIVE {
        check_adaptive(
            &format!("{method:?} 1e-10"),
            &method.with_tolerance(tol),
            allowance(method, tol),
            delta,
            above,
        );
    }
}

/// `C tol'` as in the other suites: `100 tol` for Dormand–Prince,
/// `100 tol^(5/6)` for Radau5.
fn allowance(method: Method, tol: f64) -> f64 {
    match method {
        Method::Radau5 => 100.0 * f64::powf(tol, 5.0 / 6.0),
        _ => 100.0 * tol,
    }
}

/// Steps (accepted and rejected) over two libration periods at `δ`, with
/// a step budget so that a stall ends as `TooManySteps` instead of hanging.
fn steps_over_two_periods<I: Integrator<f64>>(method: &I, delta: f64) -> (f64, usize) {
    let s = swing(delta, false);
    let end = 8.0 * s.quarter();
    let run = integrate(method, &s, &[end]).unwrap_or_else(|f| panic!("δ = {delta}: {f}"));
    let stats = run.stats();
    (end, stats.steps_accepted + stats.steps_rejected)
}

/// The no-stall check for one method; `make(budget)` builds it.
fn assert_no_stall<I: Integrator<f64>>(name: &str, make: impl Fn(usize) -> I) {
    let (ordinary_time, ordinary) = steps_over_two_periods(&make(usize::MAX), 1e-2);
    let rate = ordinary as f64 / ordinary_time;
    let mut row = vec![format!("δ = 1e-2: {ordinary} steps in {ordinary_time:.1}")];
    for delta in [1e-6, 1e-12] {
        let (time, count) = steps_over_two_periods(&make(10 * ordinary), delta);
        row.push(format!("δ = {delta:.0e}: {count} in {time:.1}"));
        assert!(
            count as f64 / time <= rate,
            "{name} δ = {delta}: {count} steps in {time} vs {ordinary} in {ordinary_time}"
        );
    }
    println!("two libration periods, {name}: {}", row.join("; "));
}

/// Step control must not stall in the slow creep past the unstable
/// equilibrium: over two periods, the closer to the separatrix (`δ = 10⁻⁶`,
/// `10⁻¹²`), the longer the period (`≈ 2 ln(16/δ)`), but the steps per unit
/// time must not exceed those of an ordinary large swing (`δ = 10⁻²`,
/// 169°): near the top the motion is slow and smooth, `θ ≈ π − a e^{±t}`,
/// and the steps grow there. Every run has a budget of 10× the ordinary
/// swing's steps, so a stall would end as `TooManySteps`, not hang.
#[test]
fn step_control_does_not_stall_near_the_unstable_equilibrium() {
    let tol = 1e-10;
    for method in Method::ADAPTIVE {
        assert_no_stall(&format!("{method:?} 1e-10"), |b| {
            method.with_tolerance(tol).max_steps(b)
        });
    }
}

/// Fixed steps near the separatrix: the energy error, not the state error,
/// decides whether the motion stays qualitatively right, and it must stay
/// below the gap `2δ` or the libration turns into a rotation. RK4 at
/// `h = 0.01` drifts in energy by `O(h⁴)` per unit time (measured below the
/// gap over two periods); Gauss–Legendre (symplectic here: `M` is constant)
/// keeps a bounded energy error at a step five times longer. Both must
/// still be librating after two periods (back at the bottom, moving
/// forwards), and their state errors are printed.
#[test]
fn fixed_steps_keep_the_libration_on_its_side_of_the_separatrix() {
    let delta = 1e-6;
    let s = swing(delta, false);
    let quarter = s.quarter();
    let times: Vec<f64> = (1..=8).map(|k| k as f64 * quarter).collect();
    let energy0 = 2.0 * s.kappa * s.kappa - 1.0;
    let runs = [
        ("Rk4 h = 0.01", integrate(&Rk4::new(0.01), &s, &times)),
        (
            "GaussLegendre 3 h = 0.05",
            integrate(&GaussLegendre::three_stage(0.05), &s, &times),
        ),
    ];
    for (name, run) in runs {
        let run = run.unwrap_or_else(|f| panic!("{name}: {f}"));
        let energy_error = run
            .iter()
            .map(|p| (pendulum().energy(p.t, &p.q, &p.qdot) - energy0).abs())
            .fold(0.0, f64::max);
        let errors: Vec<String> = run
            .iter()
            .map(|p| {
                let (theta, rate) = s.state(p.t);
                format!(
                    "{:.1e}",
                    (p.q[0] - theta).abs().max((p.qdot[0] - rate).abs())
                )
            })
            .collect();
        let end = run.last().unwrap();
        println!(
            "libration δ = 1e-6, {name}: energy error {energy_error:.1e} (gap {:.0e}); state \
             errors at k T/4, k = 1..8: {}",
            2.0 * delta,
            errors.join(", ")
        );
        assert!(
            energy_error < 2.0 * delta,
            "{name}: energy error {energy_error:e}"
        );
        assert!(
            end.q[0].abs() < 1e-2 && end.qdot[0] > 0.0,
            "{name}: not librating"
        );
    }
}
