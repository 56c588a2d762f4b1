//! Numerical stability at the extremes: the same scenes in single
//! precision (`Model::<f32>`), measured against `f64` and exact references,
//! to document where `f32` stops being enough.
//!
//! `ε₃₂ = 1.19e-7`. Every step rounds the state to `ε₃₂/2` of its size, and
//! the flow carries those roundings on: a fixed-step run of `n` steps has a
//! round-off error of order `√n ε₃₂ |y|` (independent roundings, a random
//! walk; measured 0.06–0.3 of it) and at most `n ε₃₂ |y|` (a systematic
//! bias), times the flow's perturbation growth; `h⁴`-small truncation
//! cannot go below that. Adaptive methods
//! refuse `rtol < 10 ε₃₂` outright. The scenes: the double pendulum (smooth
//! and chaotic, the latter against the 25-digit reference in `tests/data/`),
//! a Kepler orbit's energy under a symplectic method, and the stiff chain
//! under Radau5.
//!
//! Every test prints the figures quoted in STABILITY.md; run with
//! `cargo test --release --test suite -- extremes::f32:: --nocapture`.

use crate::support::reference::Reference;
use lagrange::models::{DoublePendulum, Kepler, StiffChain};
use lagrange::nalgebra::{self, RealField, SVector, Vector2};
use lagrange::prelude::*;
use lagrange::{IntegrationResult, InvalidInput};

const EPS32: f64 = f32::EPSILON as f64;

fn c<S: RealField + Copy>(x: f64) -> S {
    nalgebra::convert(x)
}

fn widen<S: RealField + Copy, const N: usize>(v: &SVector<S, N>) -> SVector<f64, N> {
    v.map(|x| nalgebra::try_convert(x).unwrap())
}

/// Largest `|Δq|, |Δq̇|` between a run's sample (either precision) and an
/// `f64` state.
fn distance<S: RealField + Copy, const N: usize>(
    q: &SVector<S, N>,
    qdot: &SVector<S, N>,
    exact: &(SVector<f64, N>, SVector<f64, N>),
) -> f64 {
    (widen(q) - exact.0)
        .amax()
        .max((widen(qdot) - exact.1).amax())
}

// ---------------------------------------------------------------------------
// The smooth double pendulum of the integrator suite, to t = 1.
// ---------------------------------------------------------------------------

/// The regular double pendulum of the integrator suite.
fn smooth<S: RealField + Copy>() -> (DoublePendulum<S>, Vector2<S>, Vector2<S>) {
    DoublePendulum::regular()
}

/// Dop853 at 1e-13 in `f64`: ~1e-12 from the truth, far below any `f32`
/// error.
fn smooth_reference(end: f64) -> (Vector2<f64>, Vector2<f64>) {
    let (model, q0, v0) = smooth::<f64>();
    let run = Dop853::new()
        .rtol(1e-13)
        .atol(1e-13)
        .integrate(&model, 0.0, q0, v0, &[end])
        .unwrap();
    let end = run.last().unwrap();
    (end.q, end.qdot)
}

/// The error at `t = 1` and the steps taken, in either precision.
fn smooth_error<S: RealField + Copy, I: Integrator<S>>(
    method: &I,
    exact: &(Vector2<f64>, Vector2<f64>),
) -> (f64, usize) {
    let (model, q0, v0) = smooth::<S>();
    let run = method
        .integrate(&model, S::zero(), q0, v0, &[S::one()])
        .unwrap_or_else(|f| panic!("{f}"));
    let end = run.last().unwrap();
    (
        distance(&end.q, &end.qdot, exact),
        run.stats().steps_accepted,
    )
}

/// The adaptive methods refuse what `f32` cannot honour: `rtol < 10 ε₃₂ =
/// 1.19e-6` is `InvalidRelativeTolerance` with that minimum, before any
/// work; `10 ε₃₂` itself is accepted. Their defaults in `f32` are `100 ε₃₂
/// = 1.19e-5` (`1e-8` would be refused).
#[test]
fn adaptive_methods_refuse_f32_tolerances_below_ten_epsilon() {
    let (model, q0, v0) = smooth::<f32>();
    let min = 10.0 * f32::EPSILON;
    let refused = |result: IntegrationResult<f32, 2>, name: &str| match result {
        Err(failure) => match failure.error {
            IntegrationError::InvalidInput(InvalidInput::InvalidRelativeTolerance {
                rtol,
                min: floor,
            }) => {
                assert_eq!((rtol, floor), (1e-7, min), "{name}");
                assert!(failure.trajectory.is_empty());
                println!("f32 {name} rtol = 1e-7: {}", failure.error);
            }
            other => panic!("{name}: {other}"),
        },
        Ok(_) => panic!("{name} accepted rtol = 1e-7 in f32"),
    };
    let times = [1.0f32];
    refused(
        Dopri5::new()
            .rtol(1e-7)
            .integrate(&model, 0.0, q0, v0, &times),
        "Dopri5",
    );
    refused(
        Dop853::new()
            .rtol(1e-7)
            .integrate(&model, 0.0, q0, v0, &times),
        "Dop853",
    );
    refused(
        Radau5::new()
            .rtol(1e-7)
            .integrate(&model, 0.0, q0, v0, &times),
        "Radau5",
    );
    assert!(
        Dopri5::new()
            .rtol(min)
            .atol(min)
            .integrate(&model, 0.0, q0, v0, &times)
            .is_ok()
    );
    assert_eq!(
        Dopri5::<f32>::new(),
        Dopri5::new().rtol(1.1920929e-5).atol(1.1920929e-5)
    );
}

/// Fixed steps in `f32`: RK4 on the smooth double pendulum to `t = 1`,
/// halving `h` from 0.08 to 1e-5. While the `h⁴` truncation dominates,
/// `f32` and `f64` agree to the round-off of their `n` steps
/// (`n ε₃₂ |y|`). Below it the `f32` error stops falling: its smallest
/// value, at `h ≈ 5e-3`, is still above `ε₃₂`, and further halvings only add
/// roundings, ending more than 10× above that floor at `n = 10⁵` (the linear
/// bound `n ε₃₂ |y|` always holds; the measured growth is closer to the
/// random walk's `√n`).
#[test]
fn rk4_in_f32_has_an_error_floor_that_rises_with_the_step_count() {
    let exact = smooth_reference(1.0);
    let size = exact.0.amax().max(exact.1.amax()); // |y| ≈ 4.7
    let mut best: (f64, f64) = (f64::INFINITY, 0.0);
    let mut last = 0.0;
    let mut h = 0.08;
    while h > 5e-6 {
        let (e64, n) = smooth_error::<f64, _>(&Rk4::new(h), &exact);
        let (e32, _) = smooth_error::<f32, _>(&Rk4::new(h as f32), &exact);
        let roundoff = n as f64 * EPS32 * size;
        println!(
            "f32 Rk4 h = {h:.2e} ({n} steps): error f64 {e64:.2e}, f32 {e32:.2e} = {:.2} √n ε₃₂ |y|",
            e32 / ((n as f64).sqrt() * EPS32 * size)
        );
        assert!(e32 <= e64 + roundoff, "h = {h}: {e32:e}");
        if e64 > 100.0 * roundoff {
            assert!((e32 - e64).abs() <= roundoff, "h = {h}: {e32:e} vs {e64:e}");
        }
        if e32 < best.0 {
            best = (e32, h);
        }
        last = e32;
        h /= 2.0;
    }
    println!(
        "f32 Rk4: smallest error {:.2e} at h = {:.1e}; {:.0}× that at h = 1e-5",
        best.0,
        best.1,
        last / best.0
    );
    assert!(best.0 > EPS32, "f32 below its own epsilon: {:e}", best.0);
    assert!(last > 10.0 * best.0, "no rise past the floor: {last:e}");
}

// ---------------------------------------------------------------------------
// The chaotic double pendulum against tests/data/double_pendulum.json.
// ---------------------------------------------------------------------------

/// The chaotic double pendulum (unit masses and rods, `g = 9.81`; a
/// perturbation of the start grows 3, 15, 13, 1930 and 1.1e9 times by
/// `t = 0.5, 1, 2, 5, 10`), RK4 at `h = 1e-4` in both precisions against
/// the 25-digit reference. `f64` keeps its truncation (~1e-11) until chaos
/// takes over at `t = 10` (6.6e-6). `f32` starts from a state rounded to
/// `ε₃₂` and rounds every step: its error is that round-off times the
/// growth, within `√n ε₃₂ |y| · growth` (`n` the steps so far, the random
/// walk's size; measured 35–200× below), and at `t = 10` nothing is left (error
/// above 0.1 on a state of size ~10): for this motion `f32` is enough to
/// `t ≈ 2` (error 3e-5) and useless past `t ≈ 5`.
#[test]
fn chaotic_double_pendulum_in_f32_has_no_digit_left_by_t_10() {
    let reference = Reference::double_pendulum();
    let times = reference.times();
    let h = 1e-4;
    let model = DoublePendulum::new(1.0, 1.0, 1.0, 1.0, 9.81);
    let run64 = Rk4::new(h)
        .integrate(&model, 0.0, reference.q0, reference.qdot0, &times)
        .unwrap();
    let model32 = DoublePendulum::<f32>::new(1.0, 1.0, 1.0, 1.0, 9.81);
    let times32: Vec<f32> = times.iter().map(|&t| t as f32).collect();
    let run32 = Rk4::new(h as f32)
        .integrate(
            &model32,
            0.0,
            reference.q0.cast(),
            reference.qdot0.cast(),
            &times32,
        )
        .unwrap();
    let mut rows = Vec::new();
    for (k, s) in reference.samples.iter().enumerate() {
        let (t, q, qdot, growth) = (s.t, s.q, s.qdot, s.growth);
        let (a, b) = (run64.get(k).unwrap(), run32.get(k).unwrap());
        let e64 = distance(&a.q, &a.qdot, &(q, qdot));
        let e32 = distance(&b.q, &b.qdot, &(q, qdot));
        let size = q.amax().max(qdot.amax());
        let steps = (t / h).round();
        let bound = steps.sqrt() * EPS32 * size * growth;
        rows.push(format!("t = {t}: f64 {e64:.1e}, f32 {e32:.1e}"));
        if t < 10.0 {
            assert!(e32 <= bound, "t = {t}: f32 error {e32:e} > {bound:e}");
        } else {
            assert!(
                e32 > 0.1,
                "t = 10: f32 error {e32:e}, expected no digit left"
            );
            assert!(e64 < 1e-4, "t = 10: f64 error {e64:e}");
        }
    }
    println!("chaotic double pendulum, Rk4 h = 1e-4: {}", rows.join("; "));
}

/// Adaptive methods in `f32` on the chaotic pendulum up to `t = 2` (growth
/// ≤ 15): at every accepted tolerance down to the smallest, `10 ε₃₂`, the
/// `f32` run is as accurate as the `f64` one at the same tolerance, because
/// the truncation allowed by `tol ≥ 10 ε₃₂` per step still dominates its
/// round-off; both are within `C tol' · growth · scale` (`C tol'` as in the
/// other suites: `100 tol`, or `100 tol^(5/6)` for Radau5) plus the
/// round-off `√n ε₃₂ |y| · growth`. Tighter is refused (test above): `f32`
/// ends at errors ~4e-5 here, where `f64` goes on to ~1e-13.
#[test]
fn adaptive_f32_matches_f64_down_to_its_smallest_tolerance() {
    let reference = Reference::double_pendulum();
    let samples: Vec<_> = reference.samples.iter().filter(|s| s.t <= 2.0).collect();
    let times: Vec<f64> = samples.iter().map(|s| s.t).collect();
    let times32: Vec<f32> = times.iter().map(|&t| t as f32).collect();
    let model = DoublePendulum::new(1.0, 1.0, 1.0, 1.0, 9.81);
    let model32 = DoublePendulum::<f32>::new(1.0, 1.0, 1.0, 1.0, 9.81);
    let (q0, v0) = (reference.q0, reference.qdot0);
    let worst = |errors: &dyn Fn(usize) -> f64| (0..samples.len()).map(errors).fold(0.0, f64::max);
    for tol in [1e-4, 1e-5, 10.0 * EPS32] {
        let tol32 = tol as f32;
        let runs = [
            (
                "Dopri5",
                100.0 * tol,
                Dopri5::new()
                    .rtol(tol)
                    .atol(tol)
                    .integrate(&model, 0.0, q0, v0, &times),
                Dopri5::new().rtol(tol32).atol(tol32).integrate(
                    &model32,
                    0.0,
                    q0.cast(),
                    v0.cast(),
                    &times32,
                ),
            ),
            (
                "Dop853",
                100.0 * tol,
                Dop853::new()
                    .rtol(tol)
                    .atol(tol)
                    .integrate(&model, 0.0, q0, v0, &times),
                Dop853::new().rtol(tol32).atol(tol32).integrate(
                    &model32,
                    0.0,
                    q0.cast(),
                    v0.cast(),
                    &times32,
                ),
            ),
            (
                "Radau5",
                100.0 * tol.powf(5.0 / 6.0),
                Radau5::new()
                    .rtol(tol)
                    .atol(tol)
                    .integrate(&model, 0.0, q0, v0, &times),
                Radau5::new().rtol(tol32).atol(tol32).integrate(
                    &model32,
                    0.0,
                    q0.cast(),
                    v0.cast(),
                    &times32,
                ),
            ),
        ];
        for (name, allowance, run64, run32) in runs {
            let (run64, run32) = (run64.unwrap(), run32.unwrap());
            let steps = run32.stats().steps_accepted as f64;
            let error = |k: usize, precision64: bool| {
                let (q, qdot) = (samples[k].q, samples[k].qdot);
                if precision64 {
                    let s = run64.get(k).unwrap();
                    distance(&s.q, &s.qdot, &(q, qdot))
                } else {
                    let s = run32.get(k).unwrap();
                    distance(&s.q, &s.qdot, &(q, qdot))
                }
            };
            let (e64, e32) = (worst(&|k| error(k, true)), worst(&|k| error(k, false)));
            println!(
                "chaotic pendulum to t = 2, {name} tol {tol:.1e}: error f64 {e64:.1e}, f32 {e32:.1e} \
                 ({steps} steps)"
            );
            for (k, s) in samples.iter().enumerate() {
                let (t, q, qdot, growth) = (s.t, s.q, s.qdot, s.growth);
                let size = q.amax().max(qdot.amax());
                let bound = (allowance + steps.sqrt() * EPS32) * growth * size;
                assert!(error(k, false) <= bound, "{name} {tol:e} f32 at t = {t}");
                assert!(error(k, true) <= bound, "{name} {tol:e} f64 at t = {t}");
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Energy under a symplectic method: Kepler, e = 0.6, Cartesian.
// ---------------------------------------------------------------------------

/// Worst energy error over the first and the last tenth of `orbits` orbits,
/// sampled 40 times per orbit, and the number of steps.
fn kepler_energy<S: RealField + Copy, I: Integrator<S>>(
    method: &I,
    orbits: usize,
) -> (f64, f64, usize) {
    let e = 0.6f64;
    let period = 2.0 * std::f64::consts::PI;
    // Without exact Jacobians: Gauss–Legendre differences the acceleration.
    let model = (Kepler::<S>::new(S::one())).without_jacobians();
    // The start in f64, rounded once to S.
    let (q0, v0) = Kepler::new(1.0).pericentre(e);
    let (q0, v0) = (q0.map(c), v0.map(c));
    let times: Vec<S> = (1..=orbits * 40)
        .map(|k| c(period * k as f64 / 40.0))
        .collect();
    let run = method.integrate(&model, S::zero(), q0, v0, &times).unwrap();
    // The energy evaluated in f64 from the widened state, so that only the
    // state carries f32 rounding, not the check.
    let errors: Vec<f64> = run
        .iter()
        .map(|s| {
            let (q, v) = (widen(&s.q), widen(&s.qdot));
            (v.norm_squared() / 2.0 - 1.0 / q.norm() + 0.5).abs()
        })
        .collect();
    let tenth = errors.len() / 10;
    let worst = |xs: &[f64]| xs.iter().copied().fold(0.0, f64::max);
    (
        worst(&errors[..tenth]),
        worst(&errors[errors.len() - tenth..]),
        run.stats().steps_accepted,
    )
}

/// Gauss–Legendre 2 on a Cartesian Kepler orbit (`e = 0.6`, `h = T/500`,
/// 100 orbits, 5·10⁴ steps) is symplectic: in `f64` its energy error is the
/// bounded `O(h⁴)` oscillation, the same over the last tenth of the run as
/// over the first (ratio < 1.5; drift would give ≈ 10). In `f32` the
/// roundings of each step are not symplectic: the error grows over the run
/// (last tenth > 1.5× the first; a random walk gives ≈ √10) and dwarfs the
/// truncation (> 10× the `f64` error), staying within the random walk's
/// size `√n ε₃₂ · E_scale` (`E_scale = |T| + |V| ≤ 4.5` at pericentre; a
/// systematic bias, growing like `n`, would break it). RK4 is printed
/// beside it: its truncation drift dominates in both precisions at this step.
#[test]
fn symplectic_energy_conservation_becomes_a_random_walk_in_f32() {
    let h = 2.0 * std::f64::consts::PI / 500.0;
    let orbits = 100;
    let (early64, late64, n) = kepler_energy::<f64, _>(&GaussLegendre::two_stage(h), orbits);
    let (early32, late32, _) = kepler_energy::<f32, _>(&GaussLegendre::two_stage(h as f32), orbits);
    let (rk_early64, rk_late64, _) = kepler_energy::<f64, _>(&Rk4::new(h), orbits);
    let (rk_early32, rk_late32, _) = kepler_energy::<f32, _>(&Rk4::new(h as f32), orbits);
    let walk = (n as f64).sqrt() * EPS32 * 4.5;
    println!(
        "Kepler e = 0.6, h = T/500, {orbits} orbits ({n} steps), energy error first/last tenth: \
         GaussLegendre 2 f64 {early64:.1e}/{late64:.1e}, f32 {early32:.1e}/{late32:.1e} \
         (random-walk bound {walk:.0e}); Rk4 f64 {rk_early64:.1e}/{rk_late64:.1e}, f32 \
         {rk_early32:.1e}/{rk_late32:.1e}"
    );
    assert!(
        late64 < 1.5 * early64,
        "f64 drifts: {early64:e} → {late64:e}"
    );
    assert!(
        late32 > 1.5 * early32,
        "f32 does not grow: {early32:e} → {late32:e}"
    );
    assert!(late32 > 10.0 * late64, "f32 {late32:e} vs f64 {late64:e}");
    assert!(late32 < walk, "f32 {late32:e} beyond a random walk");
}

// ---------------------------------------------------------------------------
// The stiff chain under Radau5.
// ---------------------------------------------------------------------------

/// Radau5 in `f32` on the stiff chain (stiffness ratio 10⁶, 10 s): the
/// Newton iterations converge in single precision too, and the error stays
/// within `100 tol^(5/6) · scale` at every tolerance down to `10 ε₃₂`, as in
/// `f64`, at the price of more Jacobians (Newton contracts less well when
/// each iterate carries `ε₃₂`; counts printed). Dopri5 in `f32`, held to its
/// stability limit, takes ~7000 steps regardless of the tolerance.
#[test]
fn stiff_chain_in_f32_is_solved_by_radau5_at_f32_tolerances() {
    let end = 10.0;
    let model = StiffChain::ratio_1e6();
    let (q0, v0) = StiffChain::start();
    let exact = model.exact(end, q0, v0);
    let model32 = StiffChain::<f32>::new(1.0, 1e6, 20.0);
    for tol in [1e-3, 1e-4, 1e-5, 10.0 * EPS32] {
        let tol32 = tol as f32;
        let run64 = Radau5::new()
            .rtol(tol)
            .atol(tol)
            .integrate(&model, 0.0, q0, v0, &[end])
            .unwrap();
        let run32 = Radau5::new()
            .rtol(tol32)
            .atol(tol32)
            .integrate(&model32, 0.0, q0.cast(), v0.cast(), &[end as f32])
            .unwrap_or_else(|f| panic!("f32 Radau5 at {tol:e}: {f}"));
        let (a, b) = (run64.last().unwrap(), run32.last().unwrap());
        let (e64, e32) = (
            distance(&a.q, &a.qdot, &exact),
            distance(&b.q, &b.qdot, &exact),
        );
        let bound = 100.0 * tol.powf(5.0 / 6.0) * 1.0;
        let explicit = Dopri5::new()
            .rtol(tol32)
            .atol(tol32)
            .integrate(&model32, 0.0, q0.cast(), v0.cast(), &[end as f32])
            .unwrap();
        let e_explicit = {
            let s = explicit.last().unwrap();
            distance(&s.q, &s.qdot, &exact)
        };
        println!(
            "stiff chain, tol {tol:.1e}: Radau5 f64 {e64:.1e} ({} steps, {} Jacobians), f32 \
             {e32:.1e} ({} steps, {} Jacobians); Dopri5 f32 {e_explicit:.1e} ({} steps)",
            run64.stats().steps_accepted,
            run64.stats().jacobian_evals,
            run32.stats().steps_accepted,
            run32.stats().jacobian_evals,
            explicit.stats().steps_accepted
        );
        assert!(e32 <= bound, "f32 Radau5 at {tol:e}: {e32:e} > {bound:e}");
        assert!(e64 <= bound, "f64 Radau5 at {tol:e}: {e64:e} > {bound:e}");
    }
}
