//! Ensembles in parallel: generated models, their trajectories and a
//! `Stepper` are plain `Send + Sync` values, so a sweep is a rayon
//! `par_iter`, and each member's result is the same on any thread. And in
//! SIMD lanes (`lanes`): each lane of an `Ensemble` is its scalar
//! `Stepper`, bit for bit.

use lagrange::models::DoublePendulum;
use lagrange::nalgebra::Vector2;
use lagrange::prelude::*;
use rayon::prelude::*;

fn send_sync<T: Send + Sync>() {}

#[test]
fn a_sweep_in_parallel_equals_the_sweep_in_sequence() {
    send_sync::<DoublePendulum<f64>>();
    send_sync::<Trajectory<f64, 2>>();
    send_sync::<Stepper<'static, DoublePendulum<f64>, Dopri5<f64>, 2>>();
    let model = DoublePendulum::unit();
    let angles: Vec<(f64, f64)> = (0..64)
        .map(|k| {
            (
                -3.0 + 6.0 * (k % 8) as f64 / 7.0,
                -3.0 + 6.0 * (k / 8) as f64 / 7.0,
            )
        })
        .collect();
    let end = |&(a, b): &(f64, f64)| {
        let q0 = Vector2::new(a, b);
        let run = Dop853::new()
            .integrate(&model, 0.0, q0, Vector2::zeros(), &[2.0])
            .unwrap();
        run.last().unwrap().q
    };
    let parallel: Vec<Vector2<f64>> = angles.par_iter().map(end).collect();
    let serial: Vec<Vector2<f64>> = angles.iter().map(end).collect();
    assert_eq!(parallel, serial);
}

/// SIMD lanes (`lagrange::ensemble`): every lane of an `Ensemble` is the
/// `Stepper` of its own parameters and start, bit for bit, for each
/// fixed-step method, in `f64` and `f32` lanes; a lane's failure is its
/// scalar run's, with the lane named.
mod lanes {
    use lagrange::ensemble::{
        AdaptiveEnsemble, AutoF32x8, AutoF64x4, Ensemble, EnsembleError, LaneModel,
    };
    use lagrange::models::{Chain, DoublePendulum, Tree};
    use lagrange::nalgebra::{RealField, SVector, SimdRealField, SimdValue};
    use lagrange::prelude::*;
    use lagrange::{IntegrationError, InvalidInput, LaneStep, StepMethod, Trajectory};

    /// Frames that are not multiples of the step, so that every advance
    /// cuts its interval into equal steps shorter than `h`.
    const FRAMES: [f64; 4] = [0.0137, 0.2, 0.5003, 0.75];

    /// The ensemble of `lane_model` (lanes built by `lane`), stepped to
    /// every frame, against one scalar `Stepper` per lane of `scalar`:
    /// equal bits, or the same error for the lane that fails.
    fn lanes_match<S, V, L, Sc, M, const N: usize>(
        lane_model: L,
        scalar: impl Fn(usize) -> Sc,
        method: M,
        starts: impl Fn(usize) -> (SVector<S, N>, SVector<S, N>),
    ) where
        S: RealField + Copy,
        V: SimdRealField<Element = S> + Copy,
        L: LaneModel<N, Lanes = V>,
        Sc: Lagrangian<N, Scalar = S>,
        M: LaneStep<S> + StepMethod<S> + Copy,
    {
        let lanes = V::LANES;
        let (q0, qdot0): (Vec<_>, Vec<_>) = (0..lanes).map(&starts).unzip();
        let mut ensemble = Ensemble::new(lane_model, method, S::zero(), &q0, &qdot0).unwrap();
        let mut steppers: Vec<_> = (0..lanes)
            .map(|lane| {
                Stepper::new(scalar(lane), method, S::zero(), q0[lane], qdot0[lane]).unwrap()
            })
            .collect();
        let bits = |x: SVector<S, N>| x.map(|v| format!("{v:?}"));
        for frame in FRAMES {
            let frame: S = lagrange::nalgebra::convert(frame);
            ensemble.advance_to(frame).unwrap();
            for (lane, stepper) in steppers.iter_mut().enumerate() {
                stepper.advance_to(frame).unwrap();
                assert_eq!(
                    bits(ensemble.q(lane)),
                    bits(*stepper.q()),
                    "lane {lane}, q at {frame:?}"
                );
                assert_eq!(
                    bits(ensemble.qdot(lane)),
                    bits(*stepper.qdot()),
                    "lane {lane}, q̇"
                );
            }
            assert_eq!(ensemble.t(), steppers[0].t());
        }
        assert_eq!(
            ensemble.stats().steps_accepted,
            steppers[0].stats().steps_accepted
        );
        assert_eq!(ensemble.stats().rhs_evals, steppers[0].stats().rhs_evals);
    }

    /// Lane `i` of a double pendulum ensemble: masses, rods and start
    /// differ lane by lane (chaotic starts included: a chaotic run
    /// amplifies any difference in the last bit).
    fn pendulum_lane<S: RealField + Copy>(i: usize) -> DoublePendulum<S> {
        let c = lagrange::nalgebra::convert::<f64, S>;
        let i = i as f64;
        DoublePendulum::new(
            c(1.0 + 0.1 * i),
            c(0.7 + 0.05 * i),
            c(1.0),
            c(0.8 + 0.02 * i),
            c(9.81),
        )
    }

    fn pendulum_start<S: RealField + Copy>(i: usize) -> (SVector<S, 2>, SVector<S, 2>) {
        let c = lagrange::nalgebra::convert::<f64, S>;
        let i = i as f64;
        (
            SVector::from([c(0.3 + 0.35 * i), c(-0.4 + 0.5 * i)]),
            SVector::from([c(0.1 * i), c(0.5)]),
        )
    }

    fn chain_lane<S: RealField + Copy>(i: usize) -> Chain<S> {
        let c = lagrange::nalgebra::convert::<f64, S>;
        let i = i as f64;
        Chain::new(
            core::array::from_fn(|k| c(1.0 + 0.1 * (k as f64 + i))),
            core::array::from_fn(|k| c(1.0 - 0.05 * (k as f64) + 0.01 * i)),
        )
    }

    fn chain_start<S: RealField + Copy>(i: usize) -> (SVector<S, 5>, SVector<S, 5>) {
        let c = lagrange::nalgebra::convert::<f64, S>;
        let i = i as f64;
        (
            SVector::from_fn(|k, _| c(0.2 * (k as f64 + 1.0) + 0.3 * i)),
            SVector::from_fn(|k, _| c(0.1 * i - 0.05 * k as f64)),
        )
    }

    /// The double pendulums of `pendulum_lane`, one to a lane.
    fn pendulum<V: SimdRealField + Copy>() -> DoublePendulum<V>
    where
        V::Element: RealField + Copy,
    {
        let lanes = (0..V::LANES)
            .map(pendulum_lane::<V::Element>)
            .collect::<Vec<_>>();
        let field = |get: fn(&DoublePendulum<V::Element>) -> V::Element| {
            let mut v = V::splat(get(&lanes[0]));
            for (i, lane) in lanes.iter().enumerate() {
                v.replace(i, get(lane));
            }
            v
        };
        DoublePendulum::new(
            field(|p| p.m1),
            field(|p| p.m2),
            field(|p| p.l1),
            field(|p| p.l2),
            field(|p| p.g),
        )
    }

    /// The chains of `chain_lane`, one to a lane.
    fn chain<V: SimdRealField + Copy>() -> Chain<V>
    where
        V::Element: RealField + Copy,
    {
        let lanes = (0..V::LANES)
            .map(chain_lane::<V::Element>)
            .collect::<Vec<_>>();
        let field = |get: &dyn Fn(&Chain<V::Element>) -> V::Element| {
            let mut v = V::splat(get(&lanes[0]));
            for (i, lane) in lanes.iter().enumerate() {
                v.replace(i, get(lane));
            }
            v
        };
        Chain::new(
            core::array::from_fn(|k| field(&|c| c.m[k])),
            core::array::from_fn(|k| field(&|c| c.l[k])),
        )
    }

    fn tree_lane<S: RealField + Copy>(i: usize) -> Tree<S> {
        let c = lagrange::nalgebra::convert::<f64, S>;
        let i = i as f64;
        Tree::new(c(1.0 + 0.1 * i), c(1.0 - 0.05 * i), c(9.81))
    }

    fn tree_start<S: RealField + Copy>(i: usize) -> (SVector<S, 10>, SVector<S, 10>) {
        let c = lagrange::nalgebra::convert::<f64, S>;
        let i = i as f64;
        (
            SVector::from_fn(|k, _| c(0.3 * ((k as f64 + 1.0) * (i + 1.0)).sin())),
            SVector::from_fn(|k, _| c(0.2 * i - 0.1 * k as f64)),
        )
    }

    /// The trees of `tree_lane`, one to a lane.
    fn tree<V: SimdRealField + Copy>() -> Tree<V>
    where
        V::Element: RealField + Copy,
    {
        let lanes = (0..V::LANES)
            .map(tree_lane::<V::Element>)
            .collect::<Vec<_>>();
        let field = |get: fn(&Tree<V::Element>) -> V::Element| {
            let mut v = V::splat(get(&lanes[0]));
            for (i, lane) in lanes.iter().enumerate() {
                v.replace(i, get(lane));
            }
            v
        };
        Tree::new(field(|t| t.m), field(|t| t.l), field(|t| t.g))
    }

    /// The tree solves for `q̈` by the recursion over its links, on the
    /// lanes as on a scalar: the same bits. A lane whose links are massless
    /// is declined by the recursion and fails in the dense solve, with its
    /// scalar run's error.
    #[test]
    fn the_recursion_on_lanes_is_the_scalar_recursion() {
        lanes_match(tree::<AutoF64x4>(), tree_lane, Rk4::new(1e-3), tree_start);
        let mut model = tree::<AutoF64x4>();
        model.m.replace(2, 0.0);
        let (q0, qdot0): (Vec<_>, Vec<_>) = (0..4).map(tree_start::<f64>).unzip();
        let mut ensemble = Ensemble::new(model, Rk4::new(1e-3), 0.0, &q0, &qdot0).unwrap();
        let mut massless = tree_lane::<f64>(2);
        massless.m = 0.0;
        let mut scalar = Stepper::new(massless, Rk4::new(1e-3), 0.0, q0[2], qdot0[2]).unwrap();
        let expected = scalar.advance_to(0.1).unwrap_err();
        match ensemble.advance_to(0.1) {
            Err(EnsembleError::Lane { lane: 2, error }) => {
                assert!(matches!(error, IntegrationError::SingularMassMatrix { .. }));
                assert_eq!(error.to_string(), expected.to_string());
            }
            other => panic!("expected lane 2's singular M, got {other:?}"),
        }
    }

    /// The adaptive ensemble (one Dormand–Prince step shared by every
    /// lane): every lane reaches each frame exactly and meets its
    /// tolerance as its own scalar `Dopri5` run does; a lane that fails is
    /// named with its scalar error.
    #[test]
    fn the_adaptive_ensemble_meets_every_lanes_tolerance() {
        let tol = 1e-8;
        let (q0, qdot0): (Vec<_>, Vec<_>) = (0..4).map(pendulum_start::<f64>).unzip();
        let mut ensemble = AdaptiveEnsemble::new(
            pendulum::<AutoF64x4>(),
            Dopri5::new().rtol(tol).atol(tol),
            0.0,
            &q0,
            &qdot0,
        )
        .unwrap();
        for frame in FRAMES {
            ensemble.advance_to(frame).unwrap();
            assert_eq!(ensemble.t(), frame);
        }
        let end = FRAMES[FRAMES.len() - 1];
        for lane in 0..4 {
            let model = pendulum_lane::<f64>(lane);
            let run = |method: &dyn Fn() -> Trajectory<f64, 2>| {
                let last = method().last().expect("one sample");
                (last.q, last.qdot)
            };
            let (rq, rv) = run(&|| {
                Dop853::new()
                    .rtol(1e-13)
                    .atol(1e-13)
                    .integrate(&model, 0.0, q0[lane], qdot0[lane], &[end])
                    .unwrap()
            });
            let (sq, sv) = run(&|| {
                Dopri5::new()
                    .rtol(tol)
                    .atol(tol)
                    .integrate(&model, 0.0, q0[lane], qdot0[lane], &[end])
                    .unwrap()
            });
            let ours = (ensemble.q(lane) - rq)
                .amax()
                .max((ensemble.qdot(lane) - rv).amax());
            let scalar = (sq - rq).amax().max((sv - rv).amax());
            // The shared step is never longer than the step this lane's
            // error allows, so its global error is of the scalar run's
            // order (both a few times `tol` grown by the motion over
            // 0.75 s; measured 0.7e-8 to 5.4e-8 for the lanes and 1.2e-8
            // to 7.7e-8 for the scalar runs). Ten times the scalar's, or
            // `tol`, leaves room for the steps' different placement.
            assert!(
                ours <= 10.0 * scalar.max(tol),
                "lane {lane}: {ours:e} from the reference, the scalar run {scalar:e}"
            );
        }
        let stats = ensemble.stats();
        assert!(stats.steps_accepted > 0 && stats.rhs_evals >= 6 * stats.steps_accepted);

        // Lane 1 replaced by its start, at 0.75 s: it goes on from there as
        // its scalar run from that state does (1e-6: a hundred tolerances,
        // a quarter second of this motion grows the error far less).
        ensemble.set_lane(1, q0[1], qdot0[1]).unwrap();
        assert_eq!((ensemble.q(1), ensemble.qdot(1)), (q0[1], qdot0[1]));
        ensemble.advance_to(1.0).unwrap();
        let alone = Dopri5::new()
            .rtol(tol)
            .atol(tol)
            .integrate(&pendulum_lane::<f64>(1), 0.75, q0[1], qdot0[1], &[1.0])
            .unwrap();
        let last = alone.last().expect("one sample");
        assert!((ensemble.q(1) - last.q).amax() < 1e-6);
        let nan = SVector::from([f64::NAN, 0.0]);
        assert!(matches!(
            ensemble.set_lane(1, nan, qdot0[1]),
            Err(EnsembleError::InvalidInput(_))
        ));

        // Lane 2's tip massless: `M` singular there, at the start.
        let mut model = pendulum::<AutoF64x4>();
        model.m2.replace(2, 0.0);
        let error = AdaptiveEnsemble::new(model, Dopri5::new(), 0.0, &q0, &qdot0)
            .err()
            .expect("lane 2 fails");
        match error {
            EnsembleError::Lane { lane: 2, error } => {
                assert!(
                    matches!(error, IntegrationError::SingularMassMatrix { .. }),
                    "{error}"
                );
            }
            other => panic!("expected lane 2's singular M, got {other:?}"),
        }
    }

    /// The clock and the lanes' state move by the same step: far from
    /// `t = 0`, where an ulp of `t` is large (`2⁻²³ s` at `t = 2³⁰ s`), the
    /// harmonic oscillator's phase over 20 s, one frame a second, against
    /// `x0 cos ωt + v0/ω sin ωt` (released at `x0 = 1` with `v0 = 0.3`, no
    /// damping). The scalar driver's bound (`lagrange-runtime/tests/
    /// integrators/clock.rs`): at `rtol = atol = 1e-12` a fifth-order pair's
    /// global error over these 20 s stays within 10 tol per second, 1e-10;
    /// the shared step is no longer than any lane's own, so each lane's
    /// error is of its scalar run's order (measured 9.2e-12). A clock that
    /// moved to `fl(t + h)` while the state moved by `h` (before issue 45)
    /// put 4.7e-6 here: the rounding of each of a few hundred steps, up to
    /// 6e-8 s, as a phase.
    #[test]
    fn the_adaptive_ensembles_clock_far_from_zero_keeps_the_phase() {
        use lagrange::models::Oscillator;
        let t0 = 1_073_741_824.0; // 2³⁰
        let stiffness = [1.0, 2.0, 3.0, 4.0];
        let lanes = Oscillator::new(
            AutoF64x4::splat(1.0),
            AutoF64x4::new(1.0, 2.0, 3.0, 4.0),
            AutoF64x4::splat(0.0),
        );
        let (x0, v0) = (1.0, 0.3);
        let q0 = [SVector::from([x0]); 4];
        let qdot0 = [SVector::from([v0]); 4];
        let tol = 1e-12;
        let method = Dopri5::new().rtol(tol).atol(tol);
        let mut ensemble = AdaptiveEnsemble::new(lanes, method, t0, &q0, &qdot0).unwrap();
        let mut worst: f64 = 0.0;
        for k in 1..=20 {
            // t0 + k is exact, and so is its difference with t0.
            let t = t0 + k as f64;
            ensemble.advance_to(t).unwrap();
            assert_eq!(ensemble.t(), t);
            for (lane, k) in stiffness.iter().enumerate() {
                let omega = f64::sqrt(*k);
                let tau = t - t0;
                let exact = x0 * (omega * tau).cos() + v0 / omega * (omega * tau).sin();
                worst = worst.max((ensemble.q(lane)[0] - exact).abs());
            }
        }
        println!("worst phase error of the lanes from t0 = 2^30: {worst:.1e}");
        assert!(worst < 1e-10, "worst phase error {worst:e}");
    }

    /// Tolerances that leave Hairer's first-step estimate no number (an
    /// `atol` so small that the sums of squares overflow): the ensemble
    /// starts with RADAU5's default step, as a scalar run does, instead of a
    /// step of zero that never moves `t` (before issue 45 it spent its whole
    /// step budget at `t0` and stopped with `TooManySteps`). Each lane then
    /// meets the relative tolerance as its scalar run does: within 100 rtol
    /// of it after 1 s of the oscillator, each run's global error being a
    /// few rtol grown over one period at most (measured 2.5e-12 to 4.8e-10
    /// apart).
    #[test]
    fn a_first_step_without_an_estimate_is_the_default_step() {
        use lagrange::models::Oscillator;
        let lanes = Oscillator::new(
            AutoF64x4::splat(1.0),
            AutoF64x4::new(1.0, 2.0, 3.0, 4.0),
            AutoF64x4::splat(0.0),
        );
        let (rtol, atol) = (1e-8, 1e-300);
        let q0 = [SVector::from([1.0]); 4];
        let qdot0 = [SVector::from([0.0]); 4];
        let method = Dopri5::new().rtol(rtol).atol(atol);
        let mut ensemble = AdaptiveEnsemble::new(lanes, method, 0.0, &q0, &qdot0).unwrap();
        ensemble.advance_to(1.0).unwrap();
        for (lane, k) in [1.0, 2.0, 3.0, 4.0].into_iter().enumerate() {
            let scalar = Dopri5::new()
                .rtol(rtol)
                .atol(atol)
                .integrate(&Oscillator::new(1.0, k, 0.0), 0.0, q0[0], qdot0[0], &[1.0])
                .unwrap();
            let last = scalar.last().expect("one sample");
            let apart = (ensemble.q(lane) - last.q).amax();
            println!("lane {lane}: {apart:.1e} from its scalar run");
            assert!(
                apart < 100.0 * rtol,
                "lane {lane}: {apart:e} from its scalar run"
            );
        }
    }

    /// Every method in `f64` lanes, and each model in `f32` and `f64`
    /// lanes (fewer pairs than all: each costs the build a model's run
    /// loops; the lanes' code is one for every method and model).
    #[test]
    fn every_lane_is_its_scalar_stepper_bit_for_bit() {
        let h = 1e-3;
        lanes_match(
            pendulum::<AutoF64x4>(),
            pendulum_lane,
            Rk4::new(h),
            pendulum_start,
        );
        lanes_match(
            pendulum::<AutoF64x4>(),
            pendulum_lane,
            ExplicitEuler::new(h),
            pendulum_start,
        );
        lanes_match(
            pendulum::<AutoF64x4>(),
            pendulum_lane,
            SymplecticEuler::new(h),
            pendulum_start,
        );
        lanes_match(
            pendulum::<AutoF32x8>(),
            pendulum_lane,
            Rk4::new(1e-3_f32),
            pendulum_start,
        );
        lanes_match(chain::<AutoF64x4>(), chain_lane, Rk4::new(h), chain_start);
        lanes_match(
            chain::<AutoF32x8>(),
            chain_lane,
            SymplecticEuler::new(1e-3_f32),
            chain_start,
        );
    }

    /// Lane 2 with a massless tip (`m2 = 0`): `M` is singular there. The
    /// ensemble names lane 2 with the error its scalar run reports, and
    /// every lane stays at the start. Lane 1 with a tip of `1e-30`: `M`
    /// positive definite but too ill-conditioned for Cholesky, solved
    /// again alone by the scalar solve, with its scalar's answer.
    #[test]
    fn a_failing_lane_is_named_with_its_scalar_error() {
        let mut model = pendulum::<AutoF64x4>();
        model.m2.replace(2, 0.0);
        let mut massless = pendulum_lane::<f64>(2);
        massless.m2 = 0.0;
        let (q0, qdot0): (Vec<_>, Vec<_>) = (0..4).map(pendulum_start::<f64>).unzip();
        let method = Rk4::new(1e-3);
        let mut ensemble = Ensemble::new(model, method, 0.0, &q0, &qdot0).unwrap();
        let scalar = Stepper::new(massless, method, 0.0, q0[2], qdot0[2])
            .unwrap()
            .advance_to(0.1);
        let lane = ensemble.advance_to(0.1);
        assert!(
            matches!(scalar, Err(IntegrationError::SingularMassMatrix { .. })),
            "{scalar:?}"
        );
        assert_eq!(
            lane,
            Err(EnsembleError::Lane {
                lane: 2,
                error: scalar.unwrap_err()
            })
        );
        assert_eq!(ensemble.t(), 0.0);
        assert_eq!((ensemble.q(3), ensemble.qdot(3)), (q0[3], qdot0[3]));

        // Its mass and state replaced, the lane goes on with the others.
        ensemble
            .model_mut()
            .m2
            .replace(2, pendulum_lane::<f64>(2).m2);
        ensemble.set_lane(2, q0[2], qdot0[2]).unwrap();
        ensemble.advance_to(0.1).unwrap();

        let mut tiny = pendulum::<AutoF64x4>();
        tiny.m2.replace(1, 1e-30);
        let mut ensemble = Ensemble::new(tiny, method, 0.0, &q0, &qdot0).unwrap();
        let mut light = pendulum_lane::<f64>(1);
        light.m2 = 1e-30;
        let mut scalar = Stepper::new(light, method, 0.0, q0[1], qdot0[1]).unwrap();
        let (alone, together) = (scalar.advance_to(0.1), ensemble.advance_to(0.1));
        match alone {
            Ok(()) => {
                together.unwrap();
                let bits = |x: SVector<f64, 2>| x.map(f64::to_bits);
                assert_eq!(bits(ensemble.q(1)), bits(*scalar.q()));
                assert_eq!(bits(ensemble.qdot(1)), bits(*scalar.qdot()));
            }
            Err(error) => assert_eq!(together, Err(EnsembleError::Lane { lane: 1, error })),
        }
    }

    /// Lane 3 with a stiff pendulum (`g = 10⁶`, `h ω ≈ 10`, past RK4's
    /// stability limit of 2.8): its growth guard stops the ensemble where
    /// it stops the lane's scalar run, with the same error.
    #[test]
    fn an_unstable_lane_stops_where_its_scalar_run_stops() {
        let mut model = pendulum::<AutoF64x4>();
        model.g.replace(3, 1e6);
        let mut stiff = pendulum_lane::<f64>(3);
        stiff.g = 1e6;
        let (q0, qdot0): (Vec<_>, Vec<_>) = (0..4).map(pendulum_start::<f64>).unzip();
        let method = Rk4::new(1e-2);
        let mut ensemble = Ensemble::new(model, method, 0.0, &q0, &qdot0).unwrap();
        let mut scalar = Stepper::new(stiff, method, 0.0, q0[3], qdot0[3]).unwrap();
        let error = scalar.advance_to(5.0).unwrap_err();
        assert!(
            matches!(error, IntegrationError::Unstable { .. }),
            "{error:?}"
        );
        assert_eq!(
            ensemble.advance_to(5.0),
            Err(EnsembleError::Lane { lane: 3, error })
        );
        assert_eq!(ensemble.t(), scalar.t());
    }

    /// The same stiff lane (`g = 10⁶`) under the adaptive ensemble at
    /// tolerances too loose to hold Dopri5 within its stability region
    /// (0.1 and 1): the lane's scalar run stops `Unstable`, and so does the
    /// ensemble, naming the lane, with its state still of the size the
    /// guard allows (within a few doublings of 1000 times its start, far
    /// from overflow). Without the guard the lanes ran on to a step-size
    /// underflow at `|q̇| ≈ 10¹⁶`. (At `10³` the shared steps grow so fast
    /// that one step overflows a stage's forcing before any guard can see
    /// growth: a `NonFiniteState` at its state, a typed stop too.)
    #[test]
    fn an_unstable_lane_stops_the_adaptive_ensemble_as_its_scalar_run() {
        for tol in [1e-1, 1.0] {
            let mut model = pendulum::<AutoF64x4>();
            model.g.replace(3, 1e6);
            let mut stiff = pendulum_lane::<f64>(3);
            stiff.g = 1e6;
            let (q0, qdot0): (Vec<_>, Vec<_>) = (0..4).map(pendulum_start::<f64>).unzip();
            let method = Dopri5::new().rtol(tol).atol(tol);
            let mut scalar = Stepper::new(stiff, method, 0.0, q0[3], qdot0[3]).unwrap();
            let alone = scalar.advance_to(5.0).unwrap_err();
            assert!(
                matches!(alone, IntegrationError::Unstable { .. }),
                "{tol}: {alone:?}"
            );
            let mut ensemble = AdaptiveEnsemble::new(model, method, 0.0, &q0, &qdot0).unwrap();
            let together = ensemble.advance_to(5.0);
            let Err(EnsembleError::Lane {
                lane: 3,
                error: IntegrationError::Unstable { q, qdot, .. },
            }) = together
            else {
                panic!("{tol}: expected lane 3 Unstable, got {together:?}");
            };
            let size = q.amax().max(qdot.amax());
            assert!(size < 1e12, "{tol}: the lane grew to {size:e}");
        }
    }

    // `tests/extremes/nonfinite.rs`'s spring whose force `a √(t* − t)` is
    // zero up to `t*` (with `a = 0`) and NaN after.
    use crate::extremes::nonfinite::RunsOut;

    /// A lane whose force turns NaN at `t* = 2.3456` (the others' at 100)
    /// stops the adaptive ensemble where its scalar `Dopri5` run stops: a
    /// step with a stage past `t*` is retried shorter, as the scalar pairs
    /// retry it, until the step no longer moves `t`, so the failing
    /// evaluation is within `10 ε t*` of `t*` (1e-12 relative leaves a
    /// factor of 100), naming the lane and its forcing. Before, the
    /// ensemble stopped at the first stage past `t*`, up to a step later.
    #[test]
    fn a_lane_that_fails_inside_a_step_is_retried_shorter_as_its_scalar_run() {
        let t_star = 2.3456;
        let lane_t_star = [100.0, 100.0, t_star, 100.0];
        let model = RunsOut::<AutoF64x4>::new(
            AutoF64x4::splat(1.0),
            AutoF64x4::splat(0.0),
            AutoF64x4::from(lane_t_star),
        );
        let (q0, qdot0) = ([SVector::from([1.0]); 4], [SVector::from([0.0]); 4]);
        let method = Dopri5::new();
        let alone = Stepper::new(RunsOut::new(1.0, 0.0, t_star), method, 0.0, q0[2], qdot0[2])
            .unwrap()
            .advance_to(3.0)
            .unwrap_err();
        let mut ensemble = AdaptiveEnsemble::new(model, method, 0.0, &q0, &qdot0).unwrap();
        let together = ensemble.advance_to(3.0);
        let Err(EnsembleError::Lane {
            lane: 2,
            error: IntegrationError::NonFiniteState { t, value, .. },
        }) = together
        else {
            panic!("expected lane 2 NonFiniteState, got {together:?}");
        };
        let IntegrationError::NonFiniteState { t: t_alone, .. } = alone else {
            panic!("expected NonFiniteState alone, got {alone:?}");
        };
        assert_eq!(value, lagrange::NonFiniteValue::Forcing);
        for at in [t, t_alone] {
            assert!(at > t_star && at - t_star <= 1e-12 * t_star, "t = {at}");
        }
        assert!(
            ensemble.t() < t_star && ensemble.t() > 2.0,
            "{}",
            ensemble.t()
        );
    }

    /// The start and the settings are refused as a `Stepper` refuses them,
    /// naming the lane; a wrong number of states is refused too.
    #[test]
    fn starts_and_settings_are_checked() {
        let model = pendulum::<AutoF64x4>();
        let (mut q0, qdot0): (Vec<_>, Vec<_>) = (0..4).map(pendulum_start::<f64>).unzip();
        let method = Rk4::new(1e-3);
        assert_eq!(
            Ensemble::new(model, method, 0.0, &q0[..3], &qdot0[..3]).err(),
            Some(EnsembleError::LaneCount { lanes: 4, given: 3 })
        );
        assert_eq!(
            Ensemble::new(model, Rk4::new(-1.0), 0.0, &q0, &qdot0).err(),
            Some(EnsembleError::InvalidInput(InvalidInput::InvalidStepSize {
                h: -1.0
            }))
        );
        q0[3][1] = f64::NAN;
        let Some(EnsembleError::Lane { lane: 3, error }) =
            Ensemble::new(model, method, 0.0, &q0, &qdot0).err()
        else {
            panic!("lane 3 refused");
        };
        assert!(matches!(
            error,
            IntegrationError::InvalidInput(InvalidInput::NonFiniteInitialPosition {
                coordinate: "theta2",
                ..
            })
        ));
    }

    /// `ẍ = −x` solved by hand on the lanes; its `M` and `f` say `ẍ = 0`.
    struct LaneSpring<const FLAGGED: bool>;

    impl<const FLAGGED: bool> LaneModel<1> for LaneSpring<FLAGGED> {
        type Lanes = AutoF64x4;
        const COORDINATES: [&'static str; 1] = ["x"];
        const SOLVES_ACCELERATIONS: bool = FLAGGED;
        fn mass_matrix_and_forcing(
            &self,
            _: AutoF64x4,
            _: &SVector<AutoF64x4, 1>,
            _: &SVector<AutoF64x4, 1>,
        ) -> (
            lagrange::nalgebra::SMatrix<AutoF64x4, 1, 1>,
            SVector<AutoF64x4, 1>,
        ) {
            let (one, zero) = (AutoF64x4::splat(1.0), AutoF64x4::splat(0.0));
            (
                lagrange::nalgebra::SMatrix::from_element(one),
                SVector::from_element(zero),
            )
        }
        fn accelerations(
            &self,
            _: AutoF64x4,
            q: &SVector<AutoF64x4, 1>,
            _: &SVector<AutoF64x4, 1>,
        ) -> Option<(SVector<AutoF64x4, 1>, <AutoF64x4 as SimdValue>::SimdBool)> {
            Some((-q, <AutoF64x4 as SimdValue>::SimdBool::splat(true)))
        }
    }

    /// A lane model whose `accelerations` answer without the flag is
    /// refused, as a scalar run refuses one, instead of stepped from `M` and
    /// `f` with the method ignored.
    #[test]
    fn accelerations_without_their_flag_are_refused() {
        let q0 = vec![SVector::<f64, 1>::from([1.0]); 4];
        let qdot0 = vec![SVector::<f64, 1>::zeros(); 4];
        assert_eq!(
            Ensemble::new(LaneSpring::<false>, Rk4::new(1e-3), 0.0, &q0, &qdot0).err(),
            Some(EnsembleError::InvalidInput(
                InvalidInput::AccelerationsNotFlagged
            ))
        );
        assert!(
            AdaptiveEnsemble::new(LaneSpring::<false>, Dopri5::new(), 0.0, &q0, &qdot0).is_err()
        );
        // Flagged, every lane is the cosine: RK4's error on the oscillator
        // is about t h⁴/120 ≈ 1e-14 at t = 1, h = 1e-3; 1e-12 leaves room
        // for the rounding of 1000 steps.
        let mut ensemble =
            Ensemble::new(LaneSpring::<true>, Rk4::new(1e-3), 0.0, &q0, &qdot0).expect("flagged");
        ensemble.advance_to(1.0).unwrap();
        for lane in 0..4 {
            assert!((ensemble.q(lane)[0] - 1f64.cos()).abs() < 1e-12);
        }
    }
}
