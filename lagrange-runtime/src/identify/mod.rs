//! Identification: a model's parameters (and, if asked, its initial state)
//! fitted to measured positions by nonlinear least squares, with their
//! standard errors, and a refusal where the data cannot tell them apart.
//!
//! [`fit`] minimizes `½ Σ (q_c(t_i) − y_ic)²` over the chosen
//! [`Direction`]s, summed over the measured samples `i` and the observed
//! coordinates `c` (and likewise over measured named `let`s, a bob's
//! Cartesian `x2` and `y2`: [`Measurements::lets`]), by
//! Levenberg–Marquardt. Each iteration is one run of
//! the model's [`Sensitivity`] by the method given: the residuals and
//! their exact Jacobian (the sensitivities at the sample times) at once.
//! The samples may be at any times at or after the start, irregular ones
//! included; recorded control inputs enter as a controller on the model
//! (`model.with_controller(..)` replaying `u(t)`), which the sensitivities
//! go through like any layer.
//!
//! At the solution, with `m` residuals and `D` directions:
//! - `σ̂² = |r|² / (m − D)`, the noise's variance as the residuals show it;
//! - the covariance `σ̂² (JᵀJ)⁻¹`, and each value's standard error its
//!   diagonal's root: the linearized, Gaussian-noise estimate, which holds
//!   where the noise is independent, of one size on every measured
//!   coordinate, and small enough that the model is linear across the
//!   confidence region;
//! - [`Fit::interval`]: `value ± 1.96 standard errors`, the 95 % interval
//!   of the normal approximation (for `m − D` in the hundreds and more, as
//!   a recorded motion gives, Student's t differs in the third digit).
//!
//! Before the first step the Jacobian at the starting values is checked:
//! scaled to relative changes of each direction, its smallest singular
//! value against its largest says whether some combination of the
//! directions leaves the measured motion unchanged. Without an input,
//! scaling every mass and every damping coefficient by one factor does;
//! [`FitError::NotIdentifiable`] names that combination instead of fitting
//! a value the data cannot fix.
//!
//! A parameter declared with a domain (`parameters: l > 0, e in [0, 1];`,
//! [`ParameterDerivatives::DOMAINS`]) stays inside it: a start outside any
//! parameter's domain is [`FitError::OutsideDomain`] before any run, and
//! every trial step is projected back inside (a closed end, `c >= 0`,
//! stops a value on it; an open one, `l > 0`, is approached by at most
//! 99 % of the distance left per step, never reached). Projection rather
//! than a reparametrization (`l = exp(u)`): a fit whose steps stay inside
//! takes them unchanged, bit for bit, and a value whose best fit is a
//! closed end reaches it. A value that ends on an end of its domain is a
//! constrained minimum: its standard error, the unconstrained
//! linearization's, does not describe it.
//!
//! The linear route, for a model with a regressor
//! (`#[lagrange(regressor(..))]`: `M q̈ − f = Y π + r₀`), is ordinary least
//! squares on `Y π = −r₀` stacked over the samples, with `q̇` and `q̈`
//! estimated from the positions ([`savitzky_golay`], whose docs say what
//! the noise does to them and to the estimate); the `identify` example
//! takes it beside the fit. Weights per output are not built: every
//! residual counts alike, so outputs measured with different noise (an
//! angle and a length) should be scaled to one noise level first.
//!
//! ```
//! use lagrange_runtime::identify::{Measurements, fit, FitSettings};
//! use lagrange_runtime::nalgebra::SVector;
//! use lagrange_runtime::{Dop853, Integrator, Lagrangian, ParameterDerivatives};
//! # use lagrange_runtime::nalgebra::SMatrix;
//! # /// `θ̈ = −(g/l) sin θ`, written by hand with its derivative by `l`.
//! # #[derive(Clone, Copy)]
//! # struct Pendulum { l: f64 }
//! # impl Lagrangian<1> for Pendulum {
//! #     type Scalar = f64;
//! #     const COORDINATES: [&'static str; 1] = ["theta"];
//! #     fn mass_matrix(&self, _: f64, _: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
//! #         SMatrix::<f64, 1, 1>::new(self.l * self.l)
//! #     }
//! #     fn forcing(&self, _: f64, q: &SVector<f64, 1>, _: &SVector<f64, 1>) -> SVector<f64, 1> {
//! #         SVector::<f64, 1>::new(-9.81 * self.l * q[0].sin())
//! #     }
//! #     fn kinetic_energy(&self, _: f64, _: &SVector<f64, 1>, v: &SVector<f64, 1>) -> f64 {
//! #         0.5 * (self.l * v[0]).powi(2)
//! #     }
//! #     fn potential_energy(&self, _: f64, q: &SVector<f64, 1>) -> f64 {
//! #         -9.81 * self.l * q[0].cos()
//! #     }
//! # }
//! # impl lagrange_runtime::sensitivity::Augmented<2, 3> for Pendulum {}
//! # impl ParameterDerivatives<1, 1> for Pendulum {
//! #     const PARAMETERS: [&'static str; 1] = ["l"];
//! #     fn parameter_values(&self) -> SVector<f64, 1> { SVector::<f64, 1>::new(self.l) }
//! #     fn set_parameter_values(&mut self, p: &SVector<f64, 1>) { self.l = p[0]; }
//! #     fn mass_matrix_parameter_derivatives(&self, _: f64, _: &SVector<f64, 1>) -> [SMatrix<f64, 1, 1>; 1] {
//! #         [SMatrix::<f64, 1, 1>::new(2.0 * self.l)]
//! #     }
//! #     fn forcing_parameter_jacobian(&self, _: f64, q: &SVector<f64, 1>, _: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
//! #         SMatrix::<f64, 1, 1>::new(-9.81 * q[0].sin())
//! #     }
//! #     fn residual_parameter_jacobian(&self, t: f64, q: &SVector<f64, 1>, v: &SVector<f64, 1>, a: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
//! #         self.mass_matrix_parameter_derivatives(t, q)[0] * a - self.forcing_parameter_jacobian(t, q, v)
//! #     }
//! # }
//! // A pendulum of length 0.7 m "measured" at 50 Hz for 4 s (without
//! // noise: the fit must find the length to the runs' tolerance), fitted
//! // from 1 m, its length and its initial angle.
//! let (q0, v0) = (SVector::from([0.5]), SVector::from([0.0]));
//! let times: Vec<f64> = (1..=200).map(|i| i as f64 / 50.0).collect();
//! let truth = Dop853::new().rtol(1e-12).atol(1e-12)
//!     .integrate(&Pendulum { l: 0.7 }, 0.0, q0, v0, &times)?;
//! let data = Measurements::positions(times.clone(), truth.positions().to_vec());
//! let guess = (SVector::from([0.45]), v0);
//! let fitted = fit(
//!     Pendulum { l: 1.0 }, &Dop853::new().rtol(1e-10).atol(1e-10),
//!     ["l", "q0 theta"], 0.0, guess, &data, &FitSettings::default(),
//! )?;
//! assert!((fitted.values[0] - 0.7).abs() < 1e-7);
//! assert!((fitted.values[1] - 0.5).abs() < 1e-7);
//! assert_eq!(fitted.names, ["l", "q0 theta"]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod differentiate;
mod levenberg;

pub use differentiate::savitzky_golay;

use nalgebra::{DMatrix, DVector, SMatrix, SVector};

use crate::integrators::Integrator;
use crate::model::parameters::{Domain, ParameterDerivatives, ParameterError};
use crate::sensitivity::{Augmented, Direction, IntoDirection, Sensitivity, SensitivityError};

/// What was measured at each of `times`: some or all coordinates, and
/// named `let`s of the model (a bob's `x2`, `y2`), or either alone.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurements<const N: usize> {
    /// The sample times, non-decreasing, none before the fit's start.
    pub times: Vec<f64>,
    /// The measured positions at each time; the entries of coordinates not
    /// observed are ignored (all of them where no coordinate was).
    pub positions: Vec<SVector<f64, N>>,
    /// Which coordinates were measured.
    pub observed: [bool; N],
    /// The names of the measured `let`s, as the model's `LETS` writes them.
    pub lets: Vec<String>,
    /// At each time, the measured value of each of [`lets`](Self::lets).
    pub let_values: Vec<Vec<f64>>,
}

impl<const N: usize> Measurements<N> {
    /// Every coordinate measured at each of `times`.
    pub fn positions(times: Vec<f64>, positions: Vec<SVector<f64, N>>) -> Self {
        Self {
            times,
            positions,
            observed: [true; N],
            lets: Vec::new(),
            let_values: Vec::new(),
        }
    }

    /// The named `let`s `names` measured at each of `times` (`values[i][k]`
    /// the value of `names[k]` at `times[i]`), no coordinate.
    pub fn lets(times: Vec<f64>, names: &[&str], values: Vec<Vec<f64>>) -> Self {
        Self {
            positions: vec![SVector::zeros(); times.len()],
            times,
            observed: [false; N],
            lets: names.iter().map(|n| n.to_string()).collect(),
            let_values: values,
        }
    }

    /// The same samples with only the coordinates `observed` measured.
    pub fn observing(mut self, observed: [bool; N]) -> Self {
        self.observed = observed;
        self
    }

    fn residual_count(&self) -> usize {
        self.times.len() * (self.observed.iter().filter(|o| **o).count() + self.lets.len())
    }
}

/// The measured `let`s of a model at one state, and their rows of the
/// Jacobian: `∂ℓ/∂q S + ∂ℓ/∂q̇ Ṡ`, the `let`s' derivatives by central
/// differences (step `ε^{1/3}` relative: about 1e-10 relative error, far
/// inside what a Jacobian for Levenberg–Marquardt and for the standard
/// errors needs; the residuals themselves are exact).
struct LetRows<'a, const N: usize, const D: usize> {
    indices: &'a [usize],
    t: f64,
    q: SVector<f64, N>,
    qdot: SVector<f64, N>,
    s: SMatrix<f64, N, D>,
    sdot: SMatrix<f64, N, D>,
}

impl<const N: usize, const D: usize> crate::model::lets::Visitor<f64, N> for LetRows<'_, N, D> {
    type Output = Vec<(f64, SVector<f64, D>)>;

    fn visit<L, const K: usize>(self, model: &L) -> Self::Output
    where
        L: crate::model::lets::Lets<N, K, Scalar = f64> + ?Sized,
    {
        let at = |q: &SVector<f64, N>, v: &SVector<f64, N>| model.lets(self.t, q, v);
        let values = at(&self.q, &self.qdot);
        let mut rows = vec![SVector::<f64, D>::zeros(); self.indices.len()];
        for (vector, sens) in [(false, &self.s), (true, &self.sdot)] {
            for i in 0..N {
                let x = if vector { self.qdot[i] } else { self.q[i] };
                let h = f64::EPSILON.cbrt() * x.abs().max(1.0);
                let (mut plus, mut minus) = ((self.q, self.qdot), (self.q, self.qdot));
                if vector {
                    plus.1[i] += h;
                    minus.1[i] -= h;
                } else {
                    plus.0[i] += h;
                    minus.0[i] -= h;
                }
                let (up, down) = (at(&plus.0, &plus.1), at(&minus.0, &minus.1));
                for (row, &k) in rows.iter_mut().zip(self.indices) {
                    let slope = (up[k] - down[k]) / (2.0 * h);
                    *row += sens.row(i).transpose() * slope;
                }
            }
        }
        self.indices
            .iter()
            .zip(rows)
            .map(|(&k, row)| (values[k], row))
            .collect()
    }
}

/// The index in `LETS` of each measured `let`, or the names it has.
struct LetIndices<'a>(&'a [String]);

impl<const N: usize> crate::model::lets::Visitor<f64, N> for LetIndices<'_> {
    type Output = Result<Vec<usize>, String>;

    fn visit<L, const K: usize>(self, _: &L) -> Self::Output
    where
        L: crate::model::lets::Lets<N, K, Scalar = f64> + ?Sized,
    {
        self.0
            .iter()
            .map(|name| {
                L::LETS.iter().position(|l| l == name).ok_or_else(|| {
                    format!(
                        "name `{name}`, which is not a `let` of the model (it names: {})",
                        L::LETS.join(", ")
                    )
                })
            })
            .collect()
    }
}

/// How far to iterate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitSettings {
    /// At most this many Levenberg–Marquardt iterations (100).
    pub max_iterations: usize,
    /// Stop when no value moves by more than this, relative (1e-10).
    pub x_tol: f64,
    /// Stop when the cost falls by less than this, relative (1e-12).
    pub f_tol: f64,
    /// The directions are refused as not identifiable where the smallest
    /// singular value of the relatively scaled Jacobian is below this
    /// times the largest (1e-7: far above the runs' tolerances, at which
    /// an exact symmetry shows, and far below the conditioning of a
    /// well-posed fit).
    pub identifiability: f64,
}

impl Default for FitSettings {
    fn default() -> Self {
        Self {
            max_iterations: 100,
            x_tol: 1e-10,
            f_tol: 1e-12,
            identifiability: 1e-7,
        }
    }
}

/// A fitted model, its fitted values and their statistics.
#[derive(Debug, Clone)]
pub struct Fit<L, const N: usize, const D: usize> {
    /// The model with the fitted parameters set.
    pub model: L,
    /// The fitted initial state (the start given, where it was not fitted).
    pub start: (SVector<f64, N>, SVector<f64, N>),
    /// The directions' names: a parameter scalar's (`m2`, `l[0]`), `q0 x`
    /// or `v0 x` for an initial position or velocity of coordinate `x`.
    pub names: [String; D],
    /// The fitted value along each direction.
    pub values: SVector<f64, D>,
    /// The values at which the fit started.
    pub initial_values: SVector<f64, D>,
    /// Each value's standard error.
    pub standard_errors: SVector<f64, D>,
    /// The values' covariance, `σ̂² (JᵀJ)⁻¹`.
    pub covariance: SMatrix<f64, D, D>,
    /// The noise's standard deviation as the residuals show it,
    /// `|r| / √(m − D)`.
    pub sigma: f64,
    /// The singular values of the Jacobian scaled to relative changes,
    /// largest first: their spread is the fit's conditioning.
    pub singular_values: SVector<f64, D>,
    /// The fitted model's positions at the sample times.
    pub fitted: Vec<SVector<f64, N>>,
    /// Levenberg–Marquardt iterations, and sensitivity runs (one per
    /// trial step, rejected ones included).
    pub iterations: usize,
    /// Sensitivity runs.
    pub runs: usize,
}

impl<L, const N: usize, const D: usize> Fit<L, N, D> {
    /// The 95 % interval of value `k`: `value ± 1.96 standard errors`.
    pub fn interval(&self, k: usize) -> (f64, f64) {
        let half = 1.96 * self.standard_errors[k];
        (self.values[k] - half, self.values[k] + half)
    }
}

/// Why a fit did not give values. No size in its type: a helper that
/// returns a fit's error names `FitError`.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FitError {
    /// The measurements cannot be fitted as given.
    #[error("the measurements {0}")]
    Data(String),
    /// The sensitivity model cannot be built.
    #[error(transparent)]
    Sensitivity(#[from] SensitivityError),
    /// A parameter of the model at the start lies outside its declared
    /// domain (`parameters: l1 > 0;`): the fit is refused before any run.
    #[error("the fit cannot start there: {0}")]
    OutsideDomain(#[from] ParameterError),
    /// The run from the starting values failed: the sensitivity run's
    /// [`Failure`](crate::error::Failure) (`Failure<f64, NA>`, `NA = N·(1 + D)`, which
    /// `downcast_ref` reaches), the trajectory so far and where it stopped.
    #[error("the run from the starting values failed: {0}")]
    Run(Box<dyn std::error::Error + Send + Sync>),
    /// Some combination of the directions leaves the measured motion
    /// unchanged (to `ratio` of the best-seen combination).
    #[error(
        "the data cannot tell these apart: changing them together by these relative amounts \
         leaves the measured motion unchanged (to {ratio:.1e} of the best-determined \
         combination): {}; fix one of them, or record a motion (an input) that separates them",
        .combination.iter().map(|(n, c)| format!("{n} {c:+.3}")).collect::<Vec<_>>().join(", ")
    )]
    NotIdentifiable {
        /// Each direction's name and its share of the combination (a unit
        /// vector of relative changes).
        combination: Vec<(String, f64)>,
        /// The smallest singular value over the largest.
        ratio: f64,
    },
    /// The iterations ran out before the values settled.
    #[error("the fit did not converge in {iterations} iterations (last values: {values:?})")]
    NotConverged {
        /// The iterations taken.
        iterations: usize,
        /// The last values.
        values: Vec<f64>,
    },
}

/// Fits `directions` of `model` (parameters and, optionally, initial
/// positions and velocities) to `data`, each run from `t0` and `start` by
/// `method`. The starting values are the model's parameters and `start`.
/// The directions are a list of names (`["m2", "l1", "q0 theta1"]`, as
/// [`Direction::named`] reads them) or of [`Direction`]s; every size is
/// inferred (`D` from the list, the sensitivities' through
/// [`Augmented`]). See the [module's docs](self) for what is computed,
/// how the parameters' domains are kept, and the conditions the
/// statistics hold under.
#[allow(clippy::too_many_arguments)]
pub fn fit<L, I, T, const N: usize, const P: usize, const D: usize, const NA: usize>(
    model: L,
    method: &I,
    directions: [T; D],
    t0: f64,
    start: (SVector<f64, N>, SVector<f64, N>),
    data: &Measurements<N>,
    settings: &FitSettings,
) -> Result<Fit<L, N, D>, FitError>
where
    L: ParameterDerivatives<N, P, Scalar = f64> + Augmented<D, NA> + Clone,
    I: Integrator<f64>,
    T: IntoDirection,
{
    let directions = crate::sensitivity::directions::<L, T, N, P, D>(directions)?;
    check_data(data, t0, D)?;
    // A start outside a parameter's domain is refused, fitted or not.
    let p = model.parameter_values();
    for (k, domain) in L::DOMAINS.iter().enumerate() {
        domain.check(L::PARAMETERS[k], None, p[k])?;
    }
    let domains: Vec<Domain> = directions
        .iter()
        .map(|d| match *d {
            Direction::Parameter(k) => L::DOMAINS[k],
            _ => Domain::REAL,
        })
        .collect();
    let let_indices = if data.lets.is_empty() {
        Vec::new()
    } else {
        model
            .visit_lets(LetIndices(&data.lets))
            .unwrap_or_else(|| Err("name `let`s, but the model names none".to_string()))
            .map_err(FitError::Data)?
    };
    // Refuses bad directions and models before any run.
    Sensitivity::<L, N, P, D, NA>::new(model.clone(), directions)?;
    let names: [String; D] = std::array::from_fn(|j| directions[j].name::<L, N, P>());
    let values_of = |model: &L, start: &(SVector<f64, N>, SVector<f64, N>)| {
        let p = model.parameter_values();
        SVector::<f64, D>::from_fn(|j, _| match directions[j] {
            Direction::Parameter(k) => p[k],
            Direction::Position(i) => start.0[i],
            Direction::Velocity(i) => start.1[i],
        })
    };
    let with_values = |x: &DVector<f64>| {
        let (mut model, mut start) = (model.clone(), start);
        let mut p = model.parameter_values();
        for (j, d) in directions.iter().enumerate() {
            match *d {
                Direction::Parameter(k) => p[k] = x[j],
                Direction::Position(i) => start.0[i] = x[j],
                Direction::Velocity(i) => start.1[i] = x[j],
            }
        }
        model.set_parameter_values(&p);
        (model, start)
    };
    let observed: Vec<usize> = (0..N).filter(|&c| data.observed[c]).collect();
    let mut fitted = Vec::new();
    let mut evaluate = |x: &DVector<f64>| -> Result<levenberg::Evaluation, FitError> {
        let (model, start) = with_values(x);
        let sensitivity = Sensitivity::<L, N, P, D, NA>::new(model, directions)?;
        let (x0, w0) = sensitivity.initial_state(&start.0, &start.1);
        let run = method
            .integrate(&sensitivity, t0, x0, w0, &data.times)
            .map_err(|failure| FitError::Run(failure))?;
        let m = data.residual_count();
        let mut residual = DVector::<f64>::zeros(m);
        let mut jacobian = DMatrix::<f64>::zeros(m, D);
        fitted.clear();
        let mut row = 0;
        for (i, (x, w)) in run.positions().iter().zip(run.velocities()).enumerate() {
            let q = sensitivity.state(x);
            let s = sensitivity.sensitivities(x);
            for &c in &observed {
                residual[row] = q[c] - data.positions[i][c];
                jacobian.row_mut(row).copy_from(&s.row(c));
                row += 1;
            }
            if !let_indices.is_empty() {
                let rows = LetRows {
                    indices: &let_indices,
                    t: data.times[i],
                    q,
                    qdot: sensitivity.state(w),
                    s,
                    sdot: sensitivity.sensitivities(w),
                };
                let lets = sensitivity.model().visit_lets(rows).unwrap_or_default();
                for (k, (value, derivative)) in lets.into_iter().enumerate() {
                    residual[row] = value - data.let_values[i][k];
                    jacobian.row_mut(row).copy_from(&derivative.transpose());
                    row += 1;
                }
            }
            fitted.push(q);
        }
        Ok(levenberg::Evaluation { residual, jacobian })
    };
    let x0 = DVector::from_column_slice(values_of(&model, &start).as_slice());
    // The directions the data cannot tell apart, at the starting values.
    let first = evaluate(&x0)?;
    let relative = |x: &DVector<f64>| x.map(|v| if v != 0.0 { v.abs() } else { 1.0 });
    let spectrum = levenberg::spectrum(&first.jacobian, &relative(&x0));
    let ratio = spectrum.singular_values[D - 1] / spectrum.singular_values[0];
    // A NaN ratio (a Jacobian with no finite singular values) is refused too.
    if ratio.is_nan() || ratio < settings.identifiability {
        let sign = spectrum.weakest.iter().fold(
            0.0,
            |best: f64, c| {
                if c.abs() > best.abs() { *c } else { best }
            },
        );
        let combination = names
            .iter()
            .zip(spectrum.weakest.iter())
            .map(|(n, c)| (n.clone(), c * sign.signum()))
            .collect();
        return Err(FitError::NotIdentifiable { combination, ratio });
    }
    let stop = levenberg::Stop {
        max_iterations: settings.max_iterations,
        x_tol: settings.x_tol,
        f_tol: settings.f_tol,
    };
    let mut first = Some(first);
    let solution = levenberg::minimize(x0.clone(), stop, &domains, |x| match first.take() {
        Some(at) => Ok(at),
        None => evaluate(x),
    })?;
    if !solution.converged {
        return Err(FitError::NotConverged {
            iterations: solution.iterations,
            values: solution.x.iter().copied().collect(),
        });
    }
    // The fitted trajectory of the accepted point: evaluate once more
    // (the last run may have been a rejected trial).
    let at = evaluate(&solution.x)?;
    let m = data.residual_count();
    let sigma = (at.residual.norm_squared() / (m - D) as f64).sqrt();
    let spectrum = levenberg::spectrum(&at.jacobian, &relative(&solution.x));
    let covariance =
        SMatrix::<f64, D, D>::from_fn(|i, j| sigma * sigma * spectrum.inverse_normal[(i, j)]);
    let (model, start) = with_values(&solution.x);
    Ok(Fit {
        model,
        start,
        names,
        values: SVector::from_fn(|j, _| solution.x[j]),
        initial_values: SVector::from_fn(|j, _| x0[j]),
        standard_errors: SVector::from_fn(|j, _| covariance[(j, j)].sqrt()),
        covariance,
        sigma,
        singular_values: SVector::from_fn(|j, _| spectrum.singular_values[j]),
        fitted: std::mem::take(&mut fitted),
        iterations: solution.iterations,
        runs: solution.evaluations + 1,
    })
}

fn check_data<const N: usize>(
    data: &Measurements<N>,
    t0: f64,
    directions: usize,
) -> Result<(), FitError> {
    let bad = |what: String| Err(FitError::Data(what));
    if data.times.len() != data.positions.len() {
        return bad(format!(
            "have {} times but {} positions",
            data.times.len(),
            data.positions.len()
        ));
    }
    if !data.observed.contains(&true) && data.lets.is_empty() {
        return bad("observe no coordinate and no `let`".into());
    }
    if !data.lets.is_empty() && data.let_values.len() != data.times.len() {
        return bad(format!(
            "have {} times but {} samples of the `let`s",
            data.times.len(),
            data.let_values.len()
        ));
    }
    if data.residual_count() <= directions {
        return bad(format!(
            "give {} residuals for {directions} directions: a fit needs more residuals \
             than unknowns",
            data.residual_count()
        ));
    }
    for (i, (&t, q)) in data.times.iter().zip(&data.positions).enumerate() {
        if !t.is_finite() || t < t0 {
            return bad(format!(
                "time {i} is {t}, not a finite time at or after {t0}"
            ));
        }
        if i > 0 && t < data.times[i - 1] {
            return bad(format!("times decrease at sample {i} ({t})"));
        }
        if (0..N).any(|c| data.observed[c] && !q[c].is_finite()) {
            return bad(format!(
                "sample {i} (t = {t}) has a position that is not finite"
            ));
        }
    }
    Ok(())
}
