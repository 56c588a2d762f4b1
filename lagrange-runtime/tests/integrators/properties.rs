//! Properties of every method on any input: random parameters, initial
//! states, times, step sizes and tolerances, finite or not, end in a typed
//! error or a finite trajectory at exactly the requested times; never a
//! panic, never a NaN or an infinity in a returned sample, never a hang
//! (each run's work is bounded by its step budget). Beside them, the
//! reproducers of what such inputs once did instead.
//!
//! The runs are deterministic: a fixed seed, a fixed number of cases, no
//! regression files. `cargo test -p lagrange-runtime --test integrators --
//! properties:: --nocapture` prints how the outcomes were spread.

use std::collections::BTreeMap;

use lagrange::models::Method;
use lagrange_runtime::nalgebra::{Matrix1, Matrix2, Vector1, Vector2};
use lagrange_runtime::prelude::*;
use lagrange_runtime::{IntegrationResult, InvalidInput};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};

// ---------------------------------------------------------------------------
// Models, written out by hand with the optional methods `Variational` needs.

/// A bob of mass `m` on a rod of length `l` in gravity `g`:
/// `L = ½ m l² θ̇² + m g l cos θ`.
#[derive(Debug, Clone, Copy)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
}

impl Lagrangian<1> for Pendulum {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["theta"];
    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> Matrix1<f64> {
        Matrix1::new(self.m * self.l * self.l)
    }
    fn forcing(&self, _t: f64, q: &Vector1<f64>, _qd: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(-self.m * self.g * self.l * q[0].sin())
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qd: &Vector1<f64>) -> f64 {
        0.5 * self.m * self.l * self.l * qd[0] * qd[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        -self.m * self.g * self.l * q[0].cos()
    }
    fn momentum(&self, _t: f64, _q: &Vector1<f64>, qd: &Vector1<f64>) -> Option<Vector1<f64>> {
        Some(Vector1::new(self.m * self.l * self.l * qd[0]))
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector1<f64>,
        _qd: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(-self.m * self.g * self.l * q[0].sin()))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector1<f64>,
        _qd: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::zeros())
    }
    fn parameters_are_finite(&self) -> bool {
        [self.m, self.l, self.g].iter().all(|p| p.is_finite())
    }
}

/// A pendulum (bob `m`, rod `l`) hanging from a cart of mass `mc` on a
/// rail: `M(θ) = [[mc + m, m l cos θ], [m l cos θ, m l²]]` depends on the
/// configuration, and `f = (m l θ̇² sin θ, −m g l sin θ)`.
#[derive(Debug, Clone, Copy)]
struct CartPendulum {
    mc: f64,
    m: f64,
    l: f64,
    g: f64,
}

impl CartPendulum {
    fn mass(&self, theta: f64) -> Matrix2<f64> {
        let coupling = self.m * self.l * theta.cos();
        Matrix2::new(
            self.mc + self.m,
            coupling,
            coupling,
            self.m * self.l * self.l,
        )
    }
}

impl Lagrangian<2> for CartPendulum {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["x", "theta"];
    fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
        self.mass(q[1])
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Vector2<f64> {
        let s = q[1].sin();
        Vector2::new(
            self.m * self.l * s * qd[1] * qd[1],
            -self.m * self.g * self.l * s,
        )
    }
    fn kinetic_energy(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
        0.5 * qd.dot(&(self.mass(q[1]) * qd))
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        -self.m * self.g * self.l * q[1].cos()
    }
    fn momentum(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Option<Vector2<f64>> {
        Some(self.mass(q[1]) * qd)
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        let s = q[1].sin();
        let dtheta = -self.m * self.l * s * (qd[0] * qd[1] + self.g);
        Some(Vector2::new(0.0, dtheta))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector2<f64>,
        _qd: &Vector2<f64>,
    ) -> Option<Vector2<f64>> {
        Some(Vector2::zeros())
    }
    fn parameters_are_finite(&self) -> bool {
        [self.mc, self.m, self.l, self.g]
            .iter()
            .all(|p| p.is_finite())
    }
}

/// A mass `m` on a spring `k` with a dashpot `c`: `Q = −c ẋ`.
#[derive(Debug, Clone, Copy)]
struct DampedSpring {
    m: f64,
    k: f64,
    c: f64,
}

impl Lagrangian<1> for DampedSpring {
    type Scalar = f64;
    const COORDINATES: [&'static str; 1] = ["x"];
    fn mass_matrix(&self, _t: f64, _q: &Vector1<f64>) -> Matrix1<f64> {
        Matrix1::new(self.m)
    }
    fn forcing(&self, _t: f64, q: &Vector1<f64>, qd: &Vector1<f64>) -> Vector1<f64> {
        Vector1::new(-self.k * q[0] - self.c * qd[0])
    }
    fn kinetic_energy(&self, _t: f64, _q: &Vector1<f64>, qd: &Vector1<f64>) -> f64 {
        0.5 * self.m * qd[0] * qd[0]
    }
    fn potential_energy(&self, _t: f64, q: &Vector1<f64>) -> f64 {
        0.5 * self.k * q[0] * q[0]
    }
    fn momentum(&self, _t: f64, _q: &Vector1<f64>, qd: &Vector1<f64>) -> Option<Vector1<f64>> {
        Some(Vector1::new(self.m * qd[0]))
    }
    fn lagrangian_gradient(
        &self,
        _t: f64,
        q: &Vector1<f64>,
        _qd: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(-self.k * q[0]))
    }
    fn nonconservative_forces(
        &self,
        _t: f64,
        _q: &Vector1<f64>,
        qd: &Vector1<f64>,
    ) -> Option<Vector1<f64>> {
        Some(Vector1::new(-self.c * qd[0]))
    }
    fn parameters_are_finite(&self) -> bool {
        [self.m, self.k, self.c].iter().all(|p| p.is_finite())
    }
}

/// Two unit masses on unit rods in gravity `g` (the README's double
/// pendulum).
struct DoublePendulum {
    g: f64,
}

impl Lagrangian<2> for DoublePendulum {
    type Scalar = f64;
    const COORDINATES: [&'static str; 2] = ["theta1", "theta2"];
    fn mass_matrix(&self, _t: f64, q: &Vector2<f64>) -> Matrix2<f64> {
        let c = (q[0] - q[1]).cos();
        Matrix2::new(2.0, c, c, 1.0)
    }
    fn forcing(&self, _t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> Vector2<f64> {
        let s = (q[0] - q[1]).sin();
        Vector2::new(
            -s * qd[1] * qd[1] - 2.0 * self.g * q[0].sin(),
            s * qd[0] * qd[0] - self.g * q[1].sin(),
        )
    }
    fn kinetic_energy(&self, t: f64, q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
        0.5 * qd.dot(&(self.mass_matrix(t, q) * qd))
    }
    fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
        -2.0 * self.g * q[0].cos() - self.g * q[1].cos()
    }
}

// ---------------------------------------------------------------------------
// Every method, in one list: a new method is tested here by adding a line.

/// Each method's settings, from one random draw: the fixed-step ones read
/// `h`, the adaptive ones `rtol` and `atol`; all get `max_steps`.
#[derive(Debug, Clone, Copy)]
struct Settings {
    h: f64,
    rtol: f64,
    atol: f64,
    max_steps: usize,
}

/// One method of `Method::ALL` (the one list of every integrator), with the
/// settings applied.
fn run<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    method: Method,
    s: Settings,
    model: &L,
    (t0, q0, v0): (f64, [f64; N], [f64; N]),
    times: &[f64],
) -> IntegrationResult<f64, N> {
    method
        .with_step(s.h)
        .tolerances(s.rtol, s.atol)
        .max_steps(s.max_steps)
        .integrate(model, t0, q0.into(), v0.into(), times)
}

// ---------------------------------------------------------------------------
// Random inputs.

/// Values no finite range draws: NaN, the infinities, zeros, the extremes.
fn special() -> impl Strategy<Value = f64> {
    prop::sample::select(vec![
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -0.0,
        f64::MAX,
        -f64::MAX,
        f64::MIN_POSITIVE,
        1e300,
        -1e300,
        1e-300,
        f64::EPSILON,
    ])
}

/// `±10^e`, `e` uniform in `[lo, hi)`: every scale, not only near 1.
fn magnitude(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi, any::<bool>()).prop_map(|(e, negative)| {
        let x = 10f64.powf(e);
        if negative {
            -x
        } else {
            x
        }
    })
}

/// Mostly `typical`, sometimes any scale, sometimes special.
fn value(typical: impl Strategy<Value = f64>) -> impl Strategy<Value = f64> {
    prop_oneof![
        24 => typical,
        2 => magnitude(-300.0, 300.0),
        1 => special(),
    ]
}

/// A physical parameter: mostly positive and of order one.
fn parameter() -> impl Strategy<Value = f64> {
    value(magnitude(-1.0, 1.0).prop_map(f64::abs))
}

fn coordinate() -> impl Strategy<Value = f64> {
    value(-5.0..5.0)
}

/// Step sizes and tolerances: mostly positive, from tiny to large.
fn positive(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    value(magnitude(lo, hi).prop_map(f64::abs))
}

fn settings() -> impl Strategy<Value = Settings> {
    (
        positive(-4.0, 0.5),
        positive(-16.0, 3.0),
        positive(-16.0, 3.0),
        // Small budgets keep every run short whatever the span asked for.
        prop_oneof![1 => 0usize..4, 9 => 50usize..2000],
    )
        .prop_map(|(h, rtol, atol, max_steps)| Settings {
            h,
            rtol,
            atol,
            max_steps,
        })
}

/// `t0` and sample times: mostly sorted and after `t0`, sometimes not.
fn times() -> impl Strategy<Value = (f64, Vec<f64>)> {
    let t0 = value(-10.0..10.0);
    let offset = value(0.0..20.0);
    let shuffled = prop::bool::weighted(0.1);
    (t0, prop::collection::vec(offset, 0..5), shuffled).prop_map(|(t0, offsets, shuffled)| {
        let mut times: Vec<f64> = offsets.iter().map(|d| t0 + d.abs()).collect();
        if !shuffled {
            times.sort_by(f64::total_cmp);
        }
        (t0, times)
    })
}

// ---------------------------------------------------------------------------
// The property.

/// What a run may return: a trajectory at exactly `times`, all finite; or a
/// typed failure whose samples are a finite prefix of `times` (none for
/// invalid input), within the budget. Returns the outcome's name.
fn check<const N: usize>(
    method: Method,
    s: Settings,
    times: &[f64],
    result: IntegrationResult<f64, N>,
) -> Result<String, TestCaseError> {
    let (trajectory, outcome) = match &result {
        Ok(trajectory) => (trajectory, "Ok".to_string()),
        Err(failure) => {
            // The message is part of the error: it must format.
            let message = failure.to_string();
            prop_assert!(!message.is_empty());
            let name = format!("{:?}", failure.error);
            let name = name.split([' ', '(', '{']).next().unwrap_or("").to_string();
            let name = match &failure.error {
                IntegrationError::InvalidInput(invalid) => {
                    prop_assert!(failure.trajectory.is_empty(), "{method:?}: {message}");
                    let which = format!("{invalid:?}");
                    format!(
                        "InvalidInput::{}",
                        which.split([' ', '{']).next().unwrap_or("")
                    )
                }
                _ => name,
            };
            (&failure.trajectory, name)
        }
    };
    let kept = trajectory.times();
    prop_assert!(kept.len() <= times.len(), "{method:?}: {outcome}");
    prop_assert!(kept == &times[..kept.len()], "{method:?}: {outcome}");
    if result.is_ok() {
        prop_assert_eq!(kept.len(), times.len(), "{:?}", method);
    }
    for sample in trajectory {
        let finite = sample
            .q
            .iter()
            .chain(sample.qdot.iter())
            .all(|x| x.is_finite());
        prop_assert!(finite, "{method:?}, {outcome}: sample {sample:?}");
    }
    let stats = trajectory.stats();
    let attempts = stats.steps_accepted + stats.steps_rejected;
    prop_assert!(attempts <= s.max_steps, "{method:?}: {attempts} attempts");
    Ok(outcome)
}

/// Runs every method on `cases` random inputs for the model that `model`
/// draws, and prints how the outcomes were spread.
fn every_method_on<L, const N: usize>(
    name: &str,
    seed: u8,
    cases: u32,
    model: impl Strategy<Value = L>,
) where
    L: Lagrangian<N, Scalar = f64> + std::fmt::Debug,
{
    let config = Config {
        cases,
        failure_persistence: None,
        max_shrink_iters: 256,
        ..Config::default()
    };
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]);
    let mut runner = TestRunner::new_with_rng(config, rng);
    let state = prop::array::uniform(coordinate());
    let inputs = (
        model,
        settings(),
        times(),
        state,
        prop::array::uniform(coordinate()),
    );
    let outcomes = std::cell::RefCell::new(BTreeMap::<String, usize>::new());
    let result = runner.run(&inputs, |(model, s, (t0, times), q0, v0)| {
        for method in Method::ALL {
            let result = run(method, s, &model, (t0, q0, v0), &times);
            let outcome = check(method, s, &times, result)?;
            *outcomes.borrow_mut().entry(outcome).or_default() += 1;
        }
        Ok(())
    });
    if let Err(failure) = result {
        panic!("{name}: {failure}");
    }
    println!(
        "{name}: {cases} cases × {} methods: {:?}",
        Method::ALL.len(),
        outcomes.borrow()
    );
}

// 1000 cases per model, 10 methods each: 30 000 runs.
const CASES: u32 = 1000;

#[test]
fn every_method_on_a_random_pendulum_gives_a_typed_error_or_finite_samples() {
    let model = (parameter(), parameter(), parameter()).prop_map(|(m, l, g)| Pendulum { m, l, g });
    every_method_on("pendulum", 1, CASES, model);
}

#[test]
fn every_method_on_a_random_cart_pendulum_gives_a_typed_error_or_finite_samples() {
    let model = (parameter(), parameter(), parameter(), parameter())
        .prop_map(|(mc, m, l, g)| CartPendulum { mc, m, l, g });
    every_method_on("cart pendulum", 2, CASES, model);
}

#[test]
fn every_method_on_a_random_damped_spring_gives_a_typed_error_or_finite_samples() {
    let model =
        (parameter(), parameter(), parameter()).prop_map(|(m, k, c)| DampedSpring { m, k, c });
    every_method_on("damped spring", 3, CASES, model);
}

// ---------------------------------------------------------------------------
// Reproducers: each failed before its fix.

fn pendulum() -> Pendulum {
    Pendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    }
}

/// `h = 0.01` up to `t = 1e300` needs 1e302 steps: more than any budget.
/// The step count used to saturate and the step was stretched to ~5e280,
/// running into a non-finite state; now the interval is refused before its
/// first step, with the samples before it, never covered by longer steps.
#[test]
fn a_fixed_step_too_small_for_the_span_is_too_many_steps_before_any_step() {
    let fixed = Settings {
        h: 0.01,
        rtol: 1e-8,
        atol: 1e-8,
        max_steps: 10_000_000,
    };
    for method in Method::FIXED_STEP {
        let start = (0.0, [0.5], [0.0]);
        let failure = run(method, fixed, &pendulum(), start, &[1e300]).unwrap_err();
        let IntegrationError::TooManySteps { t, max_steps, .. } = failure.error else {
            panic!("{method:?}: {}", failure.error);
        };
        assert_eq!((t, max_steps), (0.0, 10_000_000), "{method:?}");
        assert_eq!(failure.trajectory.stats().steps_accepted, 0, "{method:?}");
        assert!(failure.trajectory.is_empty(), "{method:?}");

        // With a reachable sample first: 100 steps of 0.01 to it, then the
        // same refusal there, the sample kept.
        let failure = run(method, fixed, &pendulum(), start, &[1.0, 1e300]).unwrap_err();
        let IntegrationError::TooManySteps { t, .. } = failure.error else {
            panic!("{method:?}: {}", failure.error);
        };
        assert_eq!(t, 1.0, "{method:?}");
        assert_eq!(failure.trajectory.times(), &[1.0], "{method:?}");
        assert_eq!(failure.trajectory.stats().steps_accepted, 100, "{method:?}");
    }
}

/// Masses of opposite sign: `M = diag(1, −1)` is regular, and LU used to
/// solve it into a run-away motion. A kinetic energy negative for some
/// velocities is a modelling error, reported as such at the first state by
/// every method.
#[test]
fn opposite_masses_are_an_indefinite_mass_matrix_at_the_first_state() {
    /// `T = ½ (ẋ² − ẏ²)`, `V = ½ (x² + y²)`.
    #[derive(Debug)]
    struct OppositeMasses;
    impl Lagrangian<2> for OppositeMasses {
        type Scalar = f64;
        const COORDINATES: [&'static str; 2] = ["x", "y"];
        fn mass_matrix(&self, _t: f64, _q: &Vector2<f64>) -> Matrix2<f64> {
            Matrix2::new(1.0, 0.0, 0.0, -1.0)
        }
        fn forcing(&self, _t: f64, q: &Vector2<f64>, _qd: &Vector2<f64>) -> Vector2<f64> {
            -q
        }
        fn kinetic_energy(&self, _t: f64, _q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
            0.5 * (qd[0] * qd[0] - qd[1] * qd[1])
        }
        fn potential_energy(&self, _t: f64, q: &Vector2<f64>) -> f64 {
            0.5 * q.norm_squared()
        }
        fn momentum(&self, _t: f64, _q: &Vector2<f64>, qd: &Vector2<f64>) -> Option<Vector2<f64>> {
            Some(Vector2::new(qd[0], -qd[1]))
        }
        fn lagrangian_gradient(
            &self,
            _t: f64,
            q: &Vector2<f64>,
            _qd: &Vector2<f64>,
        ) -> Option<Vector2<f64>> {
            Some(-q)
        }
        fn nonconservative_forces(
            &self,
            _t: f64,
            _q: &Vector2<f64>,
            _qd: &Vector2<f64>,
        ) -> Option<Vector2<f64>> {
            Some(Vector2::zeros())
        }
    }
    let s = Settings {
        h: 0.01,
        rtol: 1e-8,
        atol: 1e-8,
        max_steps: 100_000,
    };
    let start = (0.5, [1.0, 1.0], [0.0, 0.3]);
    for method in Method::ALL {
        let failure = run(method, s, &OppositeMasses, start, &[1.0, 10.0]).unwrap_err();
        let IntegrationError::IndefiniteMassMatrix { t, q, qdot } = failure.error else {
            panic!("{method:?}: {}", failure.error);
        };
        assert_eq!(
            (t, q, qdot),
            (0.5, start.1.into(), start.2.into()),
            "{method:?}"
        );
        assert!(failure.trajectory.is_empty(), "{method:?}");
    }
}

/// `rtol = atol = 10` on the README's double pendulum: accepted as asked by
/// every adaptive method. It allows each step an error larger than the
/// state, so nothing holds the explicit methods within their stability
/// regions; Dopri5 used to end in a step-size underflow and Dop853 in an
/// infinite forcing, both far from the cause. Both now stop with
/// `Unstable`, as a fixed step beyond its limit does; Radau5, L-stable,
/// integrates to the end.
#[test]
fn loose_tolerances_are_honoured_and_an_unstable_explicit_run_is_unstable() {
    let model = DoublePendulum { g: 9.81 };
    let start = (0.0, [2.0, 2.5], [0.0, 0.0]);
    let times = [0.5, 1.0, 2.0];
    let loose = Settings {
        h: f64::NAN,
        rtol: 10.0,
        atol: 10.0,
        max_steps: 100_000,
    };
    for method in [Method::Dopri5, Method::Dop853] {
        let failure = run(method, loose, &model, start, &times).unwrap_err();
        assert!(
            matches!(failure.error, IntegrationError::Unstable { .. }),
            "{method:?}: {}",
            failure.error
        );
    }
    let radau = run(Method::Radau5, loose, &model, start, &times).unwrap();
    assert_eq!(radau.times(), &times);
}

/// `max_iterations = 0` allows no Newton iteration: refused before any
/// step by every implicit method, where Variational used to raise it to 1
/// silently and the Gauss methods failed each step as a divergence.
#[test]
fn zero_newton_iterations_are_invalid_input() {
    let (q0, v0) = (Vector1::new(0.5), Vector1::new(0.0));
    let runs = [
        ImplicitMidpoint::new(0.01)
            .max_iterations(0)
            .integrate(&pendulum(), 0.0, q0, v0, &[1.0]),
        GaussLegendre::three_stage(0.01)
            .max_iterations(0)
            .integrate(&pendulum(), 0.0, q0, v0, &[1.0]),
        Variational::new(0.01)
            .max_iterations(0)
            .integrate(&pendulum(), 0.0, q0, v0, &[1.0]),
    ];
    for (run, method) in runs
        .into_iter()
        .zip(["ImplicitMidpoint", "GaussLegendre", "Variational"])
    {
        let failure = run.unwrap_err();
        let expected = InvalidInput::NoNewtonIterations { method };
        assert_eq!(failure.error, IntegrationError::InvalidInput(expected));
        assert!(failure.trajectory.is_empty());
    }
}
