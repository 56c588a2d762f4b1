//! Reversibility: run forward, flip the velocities, run the same time again,
//! and see whether the method comes back to where it started.
//!
//! The double pendulum is reversible (`T` quadratic in `q̇`, nothing depends
//! on `t`, no friction): `(q, q̇) ↦ (q, −q̇)` reverses its flow, so the exact
//! round trip is the identity. A Runge–Kutta method applied to a reversible
//! system is conjugate under the flip to itself with `−h`, so its round trip
//! is `Φ₋ₕᴺ ∘ Φₕᴺ`: the identity exactly when the method is symmetric
//! (`Φ₋ₕ = Φₕ⁻¹`: implicit midpoint, Gauss–Legendre, and the variational
//! midpoint rule in `(q, p)`), and off by its truncation error otherwise.
//! Figures: `cargo test --release --test suite -- extremes::reversibility:: --nocapture`.

use crate::support::fit::{log_slope, sci};
use lagrange::models::DoublePendulum;
use lagrange::nalgebra::{Matrix4, Vector2};
use lagrange::prelude::*;

type State = (Vector2<f64>, Vector2<f64>);

/// The double pendulum at moderate energy (about a tenth of what it takes
/// to swing the upper rod over the top): regular, not chaotic, so that
/// errors grow slowly and the round-off bound below stays meaningful.
fn problem() -> (DoublePendulum, State) {
    let (model, q0, v0) = DoublePendulum::regular();
    (model, (q0, v0))
}

/// Length of each leg of the round trip: about four periods of the slow
/// mode (2.6 rad/s; the fast one is 5.6 rad/s).
const T: f64 = 10.0;

fn distance(a: &State, b: &State) -> f64 {
    (a.0 - b.0).amax().max((a.1 - b.1).amax())
}

fn run<I: Integrator<f64>>(method: &I, start: State, times: &[f64]) -> Trajectory<f64, 2> {
    let (model, _) = problem();
    method
        .integrate(&model, 0.0, start.0, start.1, times)
        .unwrap()
}

fn end_of(traj: &Trajectory<f64, 2>) -> State {
    let s = traj.last().unwrap();
    (s.q, s.qdot)
}

/// Every 0.1 along the outward leg.
fn leg_times() -> Vec<f64> {
    (1..=100).map(|i| T * i as f64 / 100.0).collect()
}

/// The outward leg by Dop853 at 1e-13: a global error of order 1e-12 on
/// this regular problem, far below every truncation error it is compared
/// with here (≥ 1e-8).
fn reference_leg() -> Trajectory<f64, 2> {
    run(
        &Dop853::new().rtol(1e-13).atol(1e-13),
        problem().1,
        &leg_times(),
    )
}

/// How much the round trip can amplify an error made on the way.
///
/// An error made at time `t` on the way out is carried by the rest of the
/// trip, `T − t` forward then `T` back: together the flow back over `t`,
/// whose linearization is `J_t⁻¹` with `J_t = ∂y(t)/∂y(0)`. One made on the
/// way back, with `t` of the motion left to undo, is carried by the same
/// `J_t⁻¹`. So `G = max_t ‖J_t⁻¹‖_∞` (the norm induced by the max-norm
/// distance used here), over `t` every 0.1 up to `T`. `J_t` by forward
/// differences of Dop853 runs at 1e-12, each coordinate of the start moved
/// by `δ = 1e-6`: their error is `≈ 1e-12 / δ = 1e-6` relative, the
/// nonlinear term `≈ δ |J|`, both negligible.
fn perturbation_growth() -> f64 {
    let (_, (q0, v0)) = problem();
    let times = leg_times();
    let method = Dop853::new().rtol(1e-12).atol(1e-12);
    let base = run(&method, (q0, v0), &times);
    let delta = 1e-6;
    let moved: Vec<Trajectory<f64, 2>> = (0..4)
        .map(|i| {
            let (mut q, mut v) = (q0, v0);
            if i < 2 {
                q[i] += delta;
            } else {
                v[i - 2] += delta;
            }
            run(&method, (q, v), &times)
        })
        .collect();
    (0..times.len())
        .map(|k| {
            let b = base.get(k).unwrap();
            let jacobian = Matrix4::from_fn(|row, col| {
                let m = moved[col].get(k).unwrap();
                let d = if row < 2 {
                    m.q[row] - b.q[row]
                } else {
                    m.qdot[row - 2] - b.qdot[row - 2]
                };
                d / delta
            });
            let inverse = jacobian.try_inverse().expect("the flow is invertible");
            // ‖A‖_∞ is the largest absolute row sum.
            inverse
                .row_iter()
                .map(|r| r.iter().map(|x| x.abs()).sum::<f64>())
                .fold(0.0, f64::max)
        })
        .fold(1.0, f64::max)
}

/// What one round trip measured: how far from the start it ended, the
/// largest error of the outward leg against the true motion (sampled every
/// 0.1: the error at one instant can be small by accident), and the steps
/// taken (both legs).
struct RoundTrip {
    returned: f64,
    global: f64,
    steps: usize,
    scale: f64,
}

/// Forward `T`, flip `q̇`, forward `T` again, flip back, compare with the
/// start. `scale` is the state's size, `max(1, |q|, |q̇|)` over the samples
/// of the outward leg.
fn round_trip<I: Integrator<f64>>(method: &I) -> RoundTrip {
    let (_, start) = problem();
    let out = run(method, start, &leg_times());
    let (q, v) = end_of(&out);
    let back = run(method, (q, -v), &[T]);
    let (q_back, v_back) = end_of(&back);
    let scale = out
        .iter()
        .fold(1f64, |m, s| m.max(s.q.amax()).max(s.qdot.amax()));
    RoundTrip {
        returned: distance(&(q_back, -v_back), &start),
        global: out
            .iter()
            .zip(reference_leg().iter())
            .map(|(a, b)| distance(&(a.q, a.qdot), &(b.q, b.qdot)))
            .fold(0.0, f64::max),
        steps: out.stats().steps_accepted + back.stats().steps_accepted,
        scale,
    }
}

/// The round-off bound of a symmetric method's round trip: each step is the
/// exact symmetric map up to `c ε` of the state's size, with `c = 10` (the
/// Newton iteration stops once its correction is below `10 ε` of the state,
/// and a contracting iteration's remaining error is below its last
/// correction; the step's own arithmetic adds a few ε; the fixed-step driver
/// rounds the step sizes to an ulp of `t`, which moves a step by
/// `ε |t| |ẏ|`, a few ε too). Each such error is carried to the end
/// amplified at most `G` times (see [`perturbation_growth`]) and they add at
/// worst linearly: `steps · c ε · scale · G`. Random signs make the typical
/// sum `√steps` times smaller.
fn round_off_bound(trip: &RoundTrip, growth: f64) -> f64 {
    trip.steps as f64 * 10.0 * f64::EPSILON * trip.scale * growth
}

fn print(name: &str, trip: &RoundTrip, growth: f64) {
    let bound = round_off_bound(trip, growth);
    println!(
        "reversibility | {name:<18} | return error {:.2e} | forward global error {:.2e} | \
         return/global {:.2e} | steps (both legs) {} | round-off bound {bound:.2e} | return/bound {:.2e} | \
         growth G {growth:.2} | scale {:.2}",
        trip.returned,
        trip.global,
        trip.returned / trip.global,
        trip.steps,
        trip.returned / bound,
        trip.scale
    );
}

/// The step of the fixed-step methods: hω ≈ 0.11 for the fast mode
/// (ω ≈ 5.6 rad/s), well inside every method's stability region.
const H: f64 = 0.02;

/// A symmetric method returns to its start to round-off: the return error
/// is within [`round_off_bound`], while its truncation error over the
/// outward leg (printed) is orders of magnitude larger.
fn assert_returns<I: Integrator<f64>>(name: &str, method: &I) {
    let growth = perturbation_growth();
    let trip = round_trip(method);
    print(name, &trip, growth);
    let bound = round_off_bound(&trip, growth);
    assert!(
        trip.returned <= bound,
        "{name}: returned to {:.2e} of the start, round-off bound {bound:.2e}",
        trip.returned
    );
}

#[test]
fn implicit_midpoint_retraces_its_steps_to_round_off() {
    assert_returns("implicit midpoint", &ImplicitMidpoint::new(H));
}

#[test]
fn gauss_legendre_two_stage_retraces_its_steps_to_round_off() {
    assert_returns("Gauss-Legendre 2", &GaussLegendre::two_stage(H));
}

#[test]
fn gauss_legendre_three_stage_retraces_its_steps_to_round_off() {
    assert_returns("Gauss-Legendre 3", &GaussLegendre::three_stage(H));
}

/// The variational integrator flips `p = M(q) q̇` with `q̇` and is the
/// midpoint rule on the discrete Lagrangian: symmetric in `(q, p)`.
#[test]
fn variational_retraces_its_steps_to_round_off() {
    assert_returns("variational", &Variational::new(H));
}

/// A method that is not symmetric does not come back: its round trip is
/// off by its truncation error, at least a hundred times the round-off bound
/// that the symmetric methods stay within.
///
/// And it is off by about its global error. For a method of odd order `p`
/// the leading error of the way back is the mirror image of the way out's
/// and adds to it: the return error is about twice the outward error carried
/// back by the flow, `J_T⁻¹ e_T`, whose size differs from `e_T`'s by a factor
/// of the order of the growth `G` at most (`J` is symplectic in `(q, p)`, so
/// `J` and `J⁻¹` share their singular values); asserted loosely as at least
/// `global / G`, printed exactly. (For an even order the leading terms
/// cancel: see
/// [`round_trip_error_of_rk4_is_fifth_order_and_of_euler_first_order`].)
fn assert_does_not_return<I: Integrator<f64>>(name: &str, method: &I) {
    let growth = perturbation_growth();
    let trip = round_trip(method);
    print(name, &trip, growth);
    let bound = round_off_bound(&trip, growth);
    assert!(
        trip.returned >= 100.0 * bound,
        "{name}: returned to {:.2e} of the start, within 100× the round-off bound {bound:.2e}",
        trip.returned
    );
    assert!(
        trip.returned >= trip.global / growth,
        "{name}: return error {:.2e} far below the global error {:.2e}",
        trip.returned,
        trip.global
    );
}

/// Explicit Euler (order 1) at a step small enough that its error over the
/// leg stays well below O(1) (the steps are many but cheap).
#[test]
fn explicit_euler_does_not_return() {
    assert_does_not_return("explicit Euler", &ExplicitEuler::new(1e-4));
}

/// Symplectic Euler keeps energy bounded but is not symmetric (its adjoint
/// is the other symplectic Euler): order 1, and it does not return.
#[test]
fn symplectic_euler_does_not_return() {
    assert_does_not_return("symplectic Euler", &SymplecticEuler::new(1e-4));
}

#[test]
fn rk4_does_not_return() {
    assert_does_not_return("RK4", &Rk4::new(H));
}

/// Dormand–Prince (order 5): the step sizes on the way back are chosen
/// afresh, which does not make the pair of legs symmetric either.
#[test]
fn dopri5_does_not_return() {
    assert_does_not_return("Dopri5 1e-8", &Dopri5::new().rtol(1e-8).atol(1e-8));
}

#[test]
fn dop853_does_not_return() {
    assert_does_not_return("Dop853 1e-8", &Dop853::new().rtol(1e-8).atol(1e-8));
}

/// The round trip's error as `h` halves. With `Φₕ = φₕ + C hᵖ⁺¹ + O(hᵖ⁺²)`
/// per step, the round trip `Φ₋ₕᴺ ∘ Φₕᴺ` is off by `(1 + (−1)ᵖ⁺¹) C hᵖ⁺¹`
/// per step: twice the local error for odd `p` (Euler: return error
/// `O(h)`, like its global error), zero for even `p`, leaving `O(hᵖ⁺²)` per
/// step (RK4: return error `O(h⁵)`, one order above its global error's
/// asymptotic `O(h⁴)`; on `ẏ = λy`, `R(z) R(−z) = 1 + O(z⁶)`). Observed
/// orders within ±0.2, the ladder's bound; every return error at least 100×
/// [`round_off_bound`] (checked). The global error's slope is printed, not
/// asserted: over `T = 10` at these steps (`hω ≤ 0.11` for the fast mode)
/// RK4's is still pre-asymptotic, 5.6, settling to 4 only below
/// `h = 0.005`, where the return error would sink under the round-off
/// bound.
#[test]
fn round_trip_error_of_rk4_is_fifth_order_and_of_euler_first_order() {
    let growth = perturbation_growth();
    let check = |name: &str, order: f64, hs: &[f64], trips: Vec<RoundTrip>| {
        let returned: Vec<f64> = trips.iter().map(|t| t.returned).collect();
        let global: Vec<f64> = trips.iter().map(|t| t.global).collect();
        let (p_return, p_global) = (log_slope(hs, &returned), log_slope(hs, &global));
        println!(
            "round-trip order | {name:<14} | return error order theory {order} observed {p_return:.3} | \
             global error order observed {p_global:.3} | h {} | return error {} | global error {}",
            sci(hs),
            sci(&returned),
            sci(&global)
        );
        for t in &trips {
            assert!(t.returned >= 100.0 * round_off_bound(t, growth));
        }
        assert!(
            (p_return - order).abs() <= 0.2,
            "{name}: return error order {p_return:.3}, theory {order}"
        );
    };
    let hs = [0.02, 0.01, 0.005];
    check(
        "RK4",
        5.0,
        &hs,
        hs.iter().map(|&h| round_trip(&Rk4::new(h))).collect(),
    );
    let hs = [2e-4, 1e-4, 5e-5];
    check(
        "explicit Euler",
        1.0,
        &hs,
        hs.iter()
            .map(|&h| round_trip(&ExplicitEuler::new(h)))
            .collect(),
    );
}
