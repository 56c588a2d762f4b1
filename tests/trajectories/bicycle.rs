//! The Whipple bicycle (`lagrange::models::WhippleBicycle`), written in the
//! language as the full nonlinear model with rolling wheels, against the
//! benchmark of Meijaard, Papadopoulos, Ruina and Schwab (2007): its
//! linearization about upright straight running against the benchmark's
//! closed-form `M`, `C1`, `K0`, `K2`, the weave and capsize speeds, and
//! nonlinear runs against the linear motion.

use lagrange::analysis::{Turns, linearize_steady_motion, stability_crossing};
use lagrange::models::{WhippleBicycle, WhippleBicycleParameters};
use lagrange::nalgebra::{DMatrix, Matrix2, Matrix4, Vector4};
use lagrange::prelude::*;

/// The closed form as transcribed (`WhippleBicycle::benchmark_matrices`)
/// gives the matrices the paper prints (section 5.3, to 14 or 15 digits):
/// 1e-13 of each matrix's largest entry is the last printed digit.
#[test]
fn the_closed_form_gives_the_published_matrices() {
    let published = [
        Matrix2::new(
            80.81722,
            2.31941332208709,
            2.31941332208709,
            0.29784188199686,
        ),
        Matrix2::new(0.0, 33.86641391492494, -0.85035641456978, 1.68540397397560),
        Matrix2::new(
            -80.95,
            -2.59951685249872,
            -2.59951685249872,
            -0.80329488458618,
        ),
        Matrix2::new(0.0, 76.59734589573222, 0.0, 2.65431523794604),
    ];
    let ours = WhippleBicycle::benchmark().benchmark_matrices();
    for (name, (a, b)) in ["M", "C1", "K0", "K2"]
        .iter()
        .zip(ours.iter().zip(&published))
    {
        assert!((a - b).amax() < 1e-13 * b.amax(), "{name}: {a} against {b}");
    }
}

/// The nonlinear model's linearization about upright straight running at
/// `v`, reduced to lean and steer.
fn linearized(bike: &WhippleBicycle<f64>, v: f64) -> Matrix4<f64> {
    let (q, qdot) = bike.upright(0.0, v);
    let lin = linearize_steady_motion(bike, 0.0, &q, &qdot, &["phi", "delta"], &["phi", "delta"])
        .unwrap_or_else(|e| panic!("upright running at {v} m/s is steady in lean and steer: {e}"));
    assert_eq!(lin.states, ["phi", "delta", "dot(phi)", "dot(delta)"]);
    Matrix4::from_iterator(lin.state_matrix.iter().copied())
}

/// The linearization equals the benchmark's, entry by entry, at speeds
/// from standing still to 10 m/s, to 1e-10 of the matrix's largest entry
/// (the bound; measured 5.4e-11). The linearization takes
/// extrapolated central differences (relative error about ε^(4/5) ≈ 3e-13
/// of each derivative) of the saddle-point solve and of the constraints
/// that span its basis, whose conditions (about 1e2 here) multiply it.
#[test]
fn the_linearized_bicycle_is_the_benchmark() {
    let bike = WhippleBicycle::benchmark();
    let mut worst = 0.0f64;
    for v in [0.0, 1.0, 2.0, 4.0, 4.6, 5.0, 6.0, 8.0, 10.0] {
        let (ours, theirs) = (linearized(&bike, v), bike.benchmark_state_matrix(v));
        let error = (ours - theirs).amax() / theirs.amax();
        worst = worst.max(error);
        assert!(
            error < 1e-10,
            "v = {v}: relative error {error:e}\nours {ours}\ntheirs {theirs}"
        );
    }
    println!("largest relative difference from the benchmark's state matrix: {worst:e}");
}

/// `M`, `C1`, `K0` and `K2` one by one against the benchmark's, each to
/// 1e-10 of its largest entry (the bound), from the general
/// `analysis::steady_motion_matrices` (through
/// `WhippleBicycle::lean_steer_matrices`, which only divides by `g`, `v`
/// and `v²`): `M` is the inverse of the lean and steer compliance through
/// the saddle-point system, exact up to rounding (a 13 × 13 LU); `C` and
/// `K` are `−M` times the linearization's lower blocks, `K0` at rest, `C1`
/// and `K2` at 5 m/s. The state matrix carries the linearization's error
/// (5.4e-11 of its largest entry), which `K2`, a difference over
/// 25 (m/s)², divides by 25. Measured: `M` 5.5e-18, `C1` 2.1e-16, `K0`
/// 2.6e-15, `K2` 2.0e-11.
#[test]
fn the_benchmarks_m_c1_k0_k2_one_by_one() {
    let bike = WhippleBicycle::benchmark();
    let ours = bike
        .lean_steer_matrices(5.0)
        .expect("upright running is steady in lean and steer");
    for ((name, ours), theirs) in ["M", "C1", "K0", "K2"]
        .into_iter()
        .zip(ours)
        .zip(bike.benchmark_matrices())
    {
        let error = (ours - theirs).amax() / theirs.amax();
        println!("{name}: relative difference {error:.1e}");
        assert!(error < 1e-10, "{name}: {ours} against {theirs}");
    }
}

/// The weave speed (where the oscillating mode turns stable) and the
/// capsize speed (where the real mode turns unstable), from the nonlinear
/// model's linearization, against the same from the benchmark's closed
/// form, and the closed form's against the paper's (table 2). Both
/// crossings are simple roots of a growth rate whose slope is of order 1
/// per m/s: the speeds inherit the matrices' relative error, 1e-10 for the
/// linearization's (measured 3e-12) and rounding (1e-11 is a few hundred
/// ulps of the eigenvalues) for the closed form's. Each speed is one call
/// of `analysis::stability_crossing`, bisection to adjacent floats (64
/// state matrices, the 17 samples included), within 1e-10 of the
/// published figure (the bound; measured 3e-12 relative to the
/// closed form's).
#[test]
fn the_weave_and_capsize_speeds_are_the_benchmarks() {
    let bike = WhippleBicycle::benchmark();
    // The weave mode is the complex pair: the growth of the largest real
    // part between 3 and 5 m/s; capsize, the real mode, between 5.5 and 7.
    // One call each, on the nonlinear model's linearization and on the
    // closed form's state matrix.
    let ours = |lo, hi| {
        stability_crossing(lo, hi, |v| {
            let (q, qdot) = bike.upright(0.0, v);
            let states = ["phi", "delta"];
            linearize_steady_motion(&bike, 0.0, &q, &qdot, &states, &states)
                .map(|l| l.state_matrix)
                .map_err(Box::new)
        })
        .unwrap_or_else(|e| panic!("one crossing in {lo}..{hi}: {e}"))
    };
    let theirs = |lo, hi| {
        stability_crossing(lo, hi, |v| {
            let a = bike.benchmark_state_matrix(v);
            Ok::<_, std::convert::Infallible>(DMatrix::from_iterator(4, 4, a.iter().copied()))
        })
        .unwrap_or_else(|e| panic!("one crossing in {lo}..{hi}: {e}"))
    };
    let (weave, capsize) = (ours(3.0, 5.0), ours(5.5, 7.0));
    assert_eq!(weave.turns, Turns::Stable);
    assert!(
        weave.eigenvalue.im.abs() > 1.0,
        "the weave is an oscillation"
    );
    assert_eq!(capsize.turns, Turns::Unstable);
    assert_eq!(capsize.eigenvalue.im, 0.0, "capsize is a real mode");
    println!(
        "evaluations: weave {}, capsize {}",
        weave.evaluations, capsize.evaluations
    );
    let (ours_weave, ours_capsize) = (weave.parameter, capsize.parameter);
    let (theirs_weave, theirs_capsize) = (theirs(3.0, 5.0).parameter, theirs(5.5, 7.0).parameter);
    for (what, ours, theirs, published) in [
        ("weave", ours_weave, theirs_weave, 4.29238253634111),
        ("capsize", ours_capsize, theirs_capsize, 6.02426201538837),
    ] {
        let error = (ours - theirs).abs() / theirs;
        assert!(
            error < 1e-10,
            "{what}: {ours} against the closed form's {theirs}"
        );
        assert!(
            (theirs - published).abs() < 1e-11 * published,
            "{what}: the closed form gives {theirs}"
        );
        assert!(
            (ours - published).abs() < 1e-10,
            "{what}: {ours} against the published {published}"
        );
        println!(
            "{what} speed {ours:.12} m/s (closed form {theirs:.12}, relative difference {error:.1e}; \
             published {published}, off by {:.1e})",
            (ours - published).abs()
        );
    }
}

/// The largest real part among the eigenvalues of `a`.
fn growth(a: &Matrix4<f64>) -> f64 {
    a.complex_eigenvalues()
        .iter()
        .map(|e| e.re)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The largest difference over `end` seconds between the nonlinear run
/// released at a lean `phi0` at speed `v` and the linear motion
/// `exp(A t) x0` of the same start; the largest lean over the last quarter;
/// the energy drift.
fn released(bike: &WhippleBicycle<f64>, v: f64, phi0: f64, end: f64) -> (f64, f64, f64) {
    let (mut q, qdot) = bike.upright(0.0, v);
    q[3] = phi0;
    let times: Vec<f64> = (1..=40).map(|k| end * k as f64 / 40.0).collect();
    let run = Dop853::new()
        .rtol(1e-11)
        .atol(1e-13)
        .integrate(bike, 0.0, q, qdot, &times)
        .expect("the run completes");
    let a = bike.benchmark_state_matrix(v);
    let x0 = Vector4::new(phi0, 0.0, 0.0, 0.0);
    let (mut off, mut late) = (0.0f64, 0.0f64);
    for s in run.iter() {
        let linear = (a * s.t).exp() * x0;
        off = off.max((s.q[3] - linear[0]).abs());
        if s.t > 0.75 * end {
            late = late.max(s.q[3].abs());
        }
    }
    let end = run.last().unwrap();
    let e0 = bike.kinetic_energy(0.0, &q, &qdot) + bike.potential_energy(0.0, &q);
    let e1 = bike.kinetic_energy(end.t, &end.q, &end.qdot) + bike.potential_energy(end.t, &end.q);
    (off, late, (e1 - e0).abs() / e0.abs())
}

/// Nonlinear runs released at a lean of 0.01 rad against the linear motion
/// of the same start. The bicycle is symmetric left to right, so the
/// nonlinear terms in lean and steer are cubic: halving the lean divides
/// the difference by 8 (between 6 and 10 allowed), which a linear part off
/// the benchmark's would not (it would halve it). The integration error
/// (Dop853 at 1e-11) is some 1e-10, far below the differences (1e-5 to
/// 1e-7). At 5 m/s (between the weave and capsize speeds) the lean decays
/// over 4 s; at 3 m/s (below the weave speed) it grows, at 1.7 /s, so
/// that run is compared over its first second, before the lean is large
/// (it falls over within 4 s). The energy is kept (rolling does no work)
/// to 1e-9 relative.
#[test]
fn a_released_lean_follows_the_linear_motion_decaying_at_5_m_s_and_growing_at_3_m_s() {
    let bike = WhippleBicycle::benchmark();
    let phi0 = 0.01;
    for (v, end) in [(5.0, 4.0), (3.0, 1.0)] {
        let (off, late, energy) = released(&bike, v, phi0, end);
        let (off_half, _, _) = released(&bike, v, phi0 / 2.0, end);
        let ratio = off / off_half;
        let rate = growth(&bike.benchmark_state_matrix(v));
        println!(
            "v = {v} m/s: growth rate {rate:.4} /s, largest lean in the last quarter of {end} s {late:.3e} rad, \
             off the linear motion by {off:.2e} (by {off_half:.2e} from half the lean: ratio {ratio:.2}), energy drift {energy:.1e}"
        );
        assert!(
            (6.0..10.0).contains(&ratio),
            "v = {v}: differences {off:e} and {off_half:e}"
        );
        if v == 5.0 {
            assert!(
                rate < 0.0 && late < phi0,
                "v = {v}: growth {rate}, lean {late}"
            );
        } else {
            assert!(
                rate > 0.0 && late > phi0,
                "v = {v}: growth {rate}, lean {late}"
            );
        }
        assert!(energy < 1e-9, "v = {v}: energy drift {energy:e}");
    }
}

/// At the capsize speed itself (where the bisection once landed) the
/// reduction holds: an SVD of the wide selection matrix once returned a
/// wrong pseudo-inverse at exactly this speed (residual 0.13 against 1e-14
/// at speeds 1e-12 away), and `NotReducible`; now a QR. The bound of the
/// linearization test.
#[test]
fn the_reduction_holds_at_the_capsize_speed_itself() {
    let bike = WhippleBicycle::benchmark();
    let v = 6.02426201650087;
    let (ours, theirs) = (linearized(&bike, v), bike.benchmark_state_matrix(v));
    assert!((ours - theirs).amax() < 1e-10 * theirs.amax());
}

/// The bicycle's 26 parameters by name: one that differs from the
/// benchmark in the rear frame's mass alone is the benchmark's parameters
/// with that field changed (by position it would take all 26 in order, and
/// a swap would compile), and a value outside its domain is refused with
/// its name.
#[test]
fn a_bicycle_is_built_by_name_from_another_and_a_value_outside_its_domain_is_named() {
    let bike = WhippleBicycle::benchmark();
    let heavier = WhippleBicycle::from_parameters(WhippleBicycleParameters {
        mB: 100.0,
        ..bike.parameters()
    })
    .unwrap();
    assert_eq!(heavier.mB, 100.0);
    let mut rest = heavier.parameters();
    rest.mB = bike.mB;
    assert_eq!(rest, bike.parameters());
    let error = WhippleBicycle::from_parameters(WhippleBicycleParameters {
        rF: -0.35,
        ..bike.parameters()
    })
    .unwrap_err();
    assert_eq!(
        error.to_string(),
        "parameter `rF` is -0.35, outside its domain `rF > 0`"
    );
}
