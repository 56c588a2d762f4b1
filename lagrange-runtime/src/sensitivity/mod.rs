//! Forward sensitivities: how a trajectory responds to a model's
//! parameters and to its initial state, integrated with it by any method.
//!
//! A [`Sensitivity`] is a model with `N·(1 + D)` coordinates: the model's
//! `q` and, for each of `D` directions (a parameter scalar, a coordinate's
//! initial position or initial velocity), the derivative `S = ∂q/∂p` of the
//! trajectory along it. Differentiating `r(t, q, q̇, q̈) = M q̈ − f = 0`
//! along a direction gives each `S` its own second-order equation with the
//! model's `M`,
//!
//! ```text
//! M S̈ = −(∂r/∂q S + ∂r/∂q̇ Ṡ + ∂r/∂p),
//! ```
//!
//! `∂r/∂p` from the model's generated parameter derivatives
//! ([`ParameterDerivatives`], `#[lagrange(parameter_derivatives)]`; zero for
//! an initial condition), `∂r/∂q` and `∂r/∂q̇` from its exact Jacobians
//! (`#[lagrange(jacobians)]`) or, without them, from forward differences of
//! `q̈` (accurate to about `√ε` relative, and `2N` more evaluations of the
//! model per evaluation, not counted in [`Stats`]). The
//! sensitivity model solves with the model's `M` once per evaluation
//! ([`Lagrangian::accelerations`]): its `M`, the model's repeated down the
//! diagonal, is never formed on the run's path.
//!
//! It is a model like any other, so it runs through the run loops every model runs through, with
//! every method but the variational one (which needs momenta a sensitivity
//! does not have). The adaptive methods control the error of the whole
//! state, the sensitivities included, with the same tolerances: a
//! sensitivity is then as accurate as the state, at the price of the steps
//! its own error asks for (CVODES's `errconS`). Their entries are in units
//! of `q` per unit of the parameter, so scale parameters of very different
//! size before comparing them. Events are not carried: a reset would need
//! the sensitivities' own jump conditions. The implicit methods take the
//! Jacobians of the whole `N·(1 + D)`-coordinate system by differences
//! and form its matrices on the stack, as for any model of that size: for
//! a large `N·(1 + D)` (hundreds), take an explicit method.
//!
//! ```
//! use lagrange_runtime::nalgebra::SVector;
//! use lagrange_runtime::sensitivity::{Direction, Sensitivity};
//! use lagrange_runtime::{Dop853, Integrator, Lagrangian, ParameterDerivatives};
//! # use lagrange_runtime::nalgebra::SMatrix;
//! # /// `ml²θ̈ = −mgl sin θ`, written by hand with its derivative by `l`.
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
//! // A pendulum of length `l` (its `ParameterDerivatives` impl, which
//! // `#[lagrange(parameter_derivatives)]` would generate, is hidden here),
//! // and how its angle responds to `l` and to the initial angle: two
//! // directions, so 1·(1 + 2) = 3 coordinates, inferred.
//! let pendulum = Pendulum { l: 1.0 };
//! let sensitivity = Sensitivity::new(pendulum, ["l", "q0 theta"])?;
//! assert_eq!(sensitivity.directions(), &[Direction::Parameter(0), Direction::Position(0)]);
//! let (x0, v0) = sensitivity.initial_state(&SVector::from([0.1]), &SVector::from([0.0]));
//! let run = Dop853::new().rtol(1e-10).atol(1e-12).integrate(&sensitivity, 0.0, x0, v0, &[1.0])?;
//! let end = run.last().unwrap();
//! let (theta, dtheta) = (sensitivity.state(&end.q), sensitivity.sensitivities(&end.q));
//! // Small swings: θ = θ0 cos(ωt), ω = √(g/l), so ∂θ/∂θ0 = cos(ωt) and
//! // ∂θ/∂l = θ0 sin(ωt) ωt/(2l); at θ0 = 0.1 rad the swing's own
//! // nonlinearity (θ0²/16 of the frequency) bounds the difference.
//! let w = 9.81_f64.sqrt();
//! assert!((theta[0] - 0.1 * w.cos()).abs() < 1e-3);
//! assert!((dtheta[(0, 0)] - 0.1 * w.sin() * w / 2.0).abs() < 1e-3);
//! assert!((dtheta[(0, 1)] - w.cos()).abs() < 1e-2);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use nalgebra::{SMatrix, SVector};

use crate::dynamics::blame::blame;
use crate::dynamics::{acceleration_jacobians, mass_error};
use crate::error::{IntegrationError, NonFiniteValue};
use crate::linalg::mass::factor_mass_matrix;
use crate::model::constraints::is_constrained;
use crate::model::inputs::{self, Inputs};
use crate::model::layer::Layered;
use crate::model::{Lagrangian, ParameterDerivatives};
use crate::trajectory::Stats;

/// The number of coordinates of a [`Sensitivity`] of a model with `n`
/// coordinates along `d` directions, `n·(1 + d)`: its type's last
/// parameter, `Sensitivity<M, 2, 7, 5, { coordinates(2, 5) }>`, where a
/// type is written out (it is inferred through [`Augmented`] otherwise).
pub const fn coordinates(n: usize, d: usize) -> usize {
    n * (1 + d)
}

/// A model whose sensitivities along `D` directions have `NA = N·(1 + D)`
/// coordinates: what lets [`Sensitivity::new`] and
/// [`identify::fit`](crate::identify::fit) infer `NA`, which stable Rust
/// cannot compute from `N` and `D` in a generic type.
///
/// `lagrangian!` implements it for a model written with
/// `#[lagrange(parameter_derivatives)]`, for every `D` from 1 to its
/// number of directions (`P + 2N`: each parameter scalar, each initial
/// position and velocity), and every layer passes it on. A model written
/// by hand states the sizes it is used at, one line each:
/// `impl Augmented<2, 3> for Pendulum {}` (one coordinate, two
/// directions). A wrong `NA` is a compile error where the sensitivity is
/// built ("`NA` must be `N·(1 + D)`").
#[diagnostic::on_unimplemented(
    message = "`{Self}` does not state the size of its sensitivities along `{D}` directions",
    note = "a model with `#[lagrange(parameter_derivatives)]` states it for every number of \
            directions it has (its parameter scalars, initial positions and velocities); a \
            model written by hand states it itself: `impl Augmented<D, {{ N * (1 + D) }}> for Model {{}}`"
)]
pub trait Augmented<const D: usize, const NA: usize> {}

impl<M, A, const D: usize, const NA: usize> Augmented<D, NA> for Layered<M, A> where
    M: Augmented<D, NA>
{
}

/// What a sensitivity is taken along.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// The parameter scalar of this index in
    /// [`ParameterDerivatives::PARAMETERS`].
    Parameter(usize),
    /// The initial position of this coordinate.
    Position(usize),
    /// The initial velocity of this coordinate.
    Velocity(usize),
}

impl Direction {
    /// The parameter scalar named `name` of the model `L`.
    pub fn parameter<L, const N: usize, const P: usize>(
        name: &str,
    ) -> Result<Self, SensitivityError>
    where
        L: ParameterDerivatives<N, P>,
    {
        L::parameter_index(name)
            .map(Direction::Parameter)
            .ok_or_else(|| unknown::<L, N, P>(name))
    }

    /// The direction named `name` of the model `L`: a parameter scalar as
    /// `PARAMETER_SCALARS` writes it (`m2`, `l[0]`), or `q0 x` (`v0 x`)
    /// for the initial position (velocity) of coordinate `x`, the names a
    /// [`Fit`](crate::identify::Fit) gives its values.
    pub fn named<L, const N: usize, const P: usize>(name: &str) -> Result<Self, SensitivityError>
    where
        L: ParameterDerivatives<N, P>,
    {
        let initial = |prefix: &str| {
            let coordinate = name.strip_prefix(prefix)?.trim_start();
            L::COORDINATES.iter().position(|c| *c == coordinate)
        };
        if let Some(i) = initial("q0 ") {
            return Ok(Direction::Position(i));
        }
        if let Some(i) = initial("v0 ") {
            return Ok(Direction::Velocity(i));
        }
        Self::parameter::<L, N, P>(name)
    }

    /// The direction's name, as [`named`](Self::named) reads it.
    pub fn name<L, const N: usize, const P: usize>(&self) -> String
    where
        L: ParameterDerivatives<N, P>,
    {
        match *self {
            Direction::Parameter(k) => L::PARAMETERS[k].to_string(),
            Direction::Position(i) => format!("q0 {}", L::COORDINATES[i]),
            Direction::Velocity(i) => format!("v0 {}", L::COORDINATES[i]),
        }
    }
}

fn unknown<L, const N: usize, const P: usize>(name: &str) -> SensitivityError
where
    L: ParameterDerivatives<N, P>,
{
    SensitivityError::UnknownParameter {
        name: name.to_string(),
        known: L::PARAMETERS.iter().map(|p| p.to_string()).collect(),
    }
}

/// A direction as a caller writes it: a [`Direction`], or its name (`"l2"`,
/// `"q0 theta1"`, [`Direction::named`]), so that a list of names is a list
/// of directions.
pub trait IntoDirection {
    /// The direction of the model `L` this names.
    fn into_direction<L, const N: usize, const P: usize>(
        self,
    ) -> Result<Direction, SensitivityError>
    where
        L: ParameterDerivatives<N, P>;
}

impl IntoDirection for Direction {
    fn into_direction<L, const N: usize, const P: usize>(
        self,
    ) -> Result<Direction, SensitivityError>
    where
        L: ParameterDerivatives<N, P>,
    {
        Ok(self)
    }
}

impl IntoDirection for &str {
    fn into_direction<L, const N: usize, const P: usize>(
        self,
    ) -> Result<Direction, SensitivityError>
    where
        L: ParameterDerivatives<N, P>,
    {
        Direction::named::<L, N, P>(self)
    }
}

/// The directions `names` of the model `L`, each read by [`IntoDirection`].
pub(crate) fn directions<L, T, const N: usize, const P: usize, const D: usize>(
    names: [T; D],
) -> Result<[Direction; D], SensitivityError>
where
    L: ParameterDerivatives<N, P>,
    T: IntoDirection,
{
    let mut out = [Direction::Parameter(0); D];
    for (slot, name) in out.iter_mut().zip(names) {
        *slot = name.into_direction::<L, N, P>()?;
    }
    Ok(out)
}

/// Why a [`Sensitivity`] cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SensitivityError {
    /// No parameter scalar (nor initial condition) has this name.
    #[error(
        "the model has no parameter scalar `{name}` (it has: {}; an initial position or velocity \
         is `q0 x` or `v0 x` of a coordinate `x`)",
        known.join(", ")
    )]
    UnknownParameter {
        /// The name asked for.
        name: String,
        /// The model's parameter scalars.
        known: Vec<String>,
    },
    /// A direction's index is out of range.
    #[error("direction {direction} is {value:?}, beyond the model's {limit} {what}")]
    OutOfRange {
        /// The direction's position in the list.
        direction: usize,
        /// The direction.
        value: Direction,
        /// How many there are.
        limit: usize,
        /// Parameters or coordinates.
        what: &'static str,
    },
    /// A direction is listed twice.
    #[error("direction {value:?} is listed twice")]
    Repeated {
        /// The direction.
        value: Direction,
    },
    /// The model has constraints.
    #[error(
        "the model has constraints: sensitivities are built for models in minimal \
         coordinates (a constrained model's would differentiate the saddle-point solve \
         and the drift control too)"
    )]
    Constrained,
    /// A parameter of the model is NaN or infinite.
    #[error("a parameter of the model is NaN or infinite")]
    NonFiniteParameters,
    /// The model has control inputs that were never set.
    #[error(
        "the model has control inputs ({}) that were never set: set them with \
         `model.with_inputs(..)` before taking its sensitivities",
        .inputs.join(", ")
    )]
    InputsNotSet {
        /// The names of the model's inputs.
        inputs: &'static [&'static str],
    },
}

/// A model with its forward sensitivities along `D` directions: a model
/// with `NA = N·(1 + D)` coordinates, `q` then `∂q/∂d` for each direction
/// `d` in order. `P` is the model's number of parameter scalars. The
/// [module's docs](self) give the equations and an example.
///
/// Every size is inferred where it is built ([`Sensitivity::new`]: `D`
/// from the list of directions, `NA` through [`Augmented`]); written out,
/// the type is `Sensitivity<Pendulum, 2, 7, 5, { coordinates(2, 5) }>`,
/// and a wrong `NA` is a compile error ("`NA` must be `N·(1 + D)`").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensitivity<L, const N: usize, const P: usize, const D: usize, const NA: usize> {
    model: L,
    directions: [Direction; D],
}

impl<L, const N: usize, const P: usize, const D: usize, const NA: usize> Sensitivity<L, N, P, D, NA>
where
    L: ParameterDerivatives<N, P>,
{
    const SIZE: () = assert!(NA == N * (1 + D), "`NA` must be `N·(1 + D)`");

    /// `model` with its sensitivities along `directions`, each a
    /// [`Direction`] or its name (`["l2", "q0 theta1"]`): `D` is the
    /// list's length and `NA` follows ([`Augmented`]). Refuses a
    /// constrained model, a model that cannot be evaluated, and a direction
    /// unknown, out of range or listed twice.
    pub fn new<T: IntoDirection>(model: L, directions: [T; D]) -> Result<Self, SensitivityError>
    where
        L: Augmented<D, NA>,
    {
        let () = Self::SIZE;
        let directions = self::directions::<L, T, N, P, D>(directions)?;
        if is_constrained(&model) {
            return Err(SensitivityError::Constrained);
        }
        if !model.parameters_are_finite() {
            return Err(SensitivityError::NonFiniteParameters);
        }
        if let Some(inputs) = crate::model::inputs::never_set(&model) {
            return Err(SensitivityError::InputsNotSet { inputs });
        }
        for (i, &d) in directions.iter().enumerate() {
            let (index, limit, what) = match d {
                Direction::Parameter(k) => (k, P, "parameter scalars"),
                Direction::Position(k) | Direction::Velocity(k) => (k, N, "coordinates"),
            };
            if index >= limit {
                return Err(SensitivityError::OutOfRange {
                    direction: i,
                    value: d,
                    limit,
                    what,
                });
            }
            if directions[..i].contains(&d) {
                return Err(SensitivityError::Repeated { value: d });
            }
        }
        Ok(Self { model, directions })
    }

    /// The model.
    pub fn model(&self) -> &L {
        &self.model
    }

    /// The model, to change its parameters between runs.
    pub fn model_mut(&mut self) -> &mut L {
        &mut self.model
    }

    /// The directions, in the order of the sensitivities' columns.
    pub fn directions(&self) -> &[Direction; D] {
        &self.directions
    }

    /// The start of a run from `(q0, q̇0)`: the sensitivities to a
    /// parameter start at zero, those to an initial position or velocity
    /// at that unit vector.
    pub fn initial_state(
        &self,
        q0: &SVector<L::Scalar, N>,
        qdot0: &SVector<L::Scalar, N>,
    ) -> (SVector<L::Scalar, NA>, SVector<L::Scalar, NA>) {
        let mut x = SVector::<L::Scalar, NA>::zeros();
        let mut v = SVector::<L::Scalar, NA>::zeros();
        x.fixed_rows_mut::<N>(0).copy_from(q0);
        v.fixed_rows_mut::<N>(0).copy_from(qdot0);
        for (j, d) in self.directions.iter().enumerate() {
            match *d {
                Direction::Parameter(_) => {}
                Direction::Position(i) => {
                    x[N * (1 + j) + i] = nalgebra::convert::<f64, L::Scalar>(1.0)
                }
                Direction::Velocity(i) => {
                    v[N * (1 + j) + i] = nalgebra::convert::<f64, L::Scalar>(1.0)
                }
            }
        }
        (x, v)
    }

    /// The model's part of an augmented position (or velocity): `q` (`q̇`).
    pub fn state(&self, x: &SVector<L::Scalar, NA>) -> SVector<L::Scalar, N> {
        x.fixed_rows::<N>(0).into_owned()
    }

    /// The sensitivities' part of an augmented position (or velocity): the
    /// `N × D` matrix whose column `j` is `∂q/∂d_j` (`∂q̇/∂d_j`).
    pub fn sensitivities(&self, x: &SVector<L::Scalar, NA>) -> SMatrix<L::Scalar, N, D> {
        SMatrix::<L::Scalar, N, D>::from_fn(|i, j| x[N * (1 + j) + i])
    }

    /// The accelerations of the whole augmented state, and `M` (for
    /// [`forcing`](Lagrangian::forcing)).
    #[allow(clippy::type_complexity)]
    fn solve(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> Result<(SVector<L::Scalar, NA>, SMatrix<L::Scalar, N, N>), IntegrationError<L::Scalar, NA>>
    {
        let (q, qdot) = (self.state(x), self.state(v));
        // Errors as `dynamics` reports them for any model, at the whole
        // state, a non-finite value blamed on the model's inputs where they
        // are to blame (a controller's NaN), as a run of the model alone
        // blames it.
        let non_finite = |value| IntegrationError::NonFiniteState {
            t,
            q: *x,
            qdot: *v,
            value: blame(&self.model, value, t, &q, &qdot),
        };
        let solve_error = |error| match mass_error(error, t, x, v) {
            IntegrationError::NonFiniteState { value, .. } => non_finite(value),
            error => error,
        };
        let (m, f) = self.model.mass_matrix_and_forcing(t, &q, &qdot);
        if !crate::linalg::all_finite(f.as_slice()) {
            return Err(non_finite(NonFiniteValue::Forcing));
        }
        let mass = factor_mass_matrix(&m).map_err(solve_error)?;
        let qddot = mass.solve(&f).map_err(solve_error)?;
        let finite = |m: &SMatrix<L::Scalar, N, N>| crate::linalg::all_finite(m.as_slice());
        // `∂r/∂q` and `∂r/∂q̇` exact, or `∂q̈/∂q` and `∂q̈/∂q̇` by differences.
        let exact = self.model.residual_jacobians(t, &q, &qdot, &qddot);
        let differences = match exact {
            Some(_) => None,
            None => Some(
                acceleration_jacobians(&self.model, t, &q, &qdot, &qddot, &mut Stats::default())
                    .map_err(|_| non_finite(NonFiniteValue::Jacobian))?,
            ),
        };
        if exact.is_some_and(|(a, b)| !finite(&a) || !finite(&b))
            || differences.is_some_and(|(a, b)| !finite(&a) || !finite(&b))
        {
            return Err(non_finite(NonFiniteValue::Jacobian));
        }
        let by_parameters = self
            .directions
            .iter()
            .any(|d| matches!(d, Direction::Parameter(_)))
            .then(|| self.model.residual_parameter_jacobian(t, &q, &qdot, &qddot));
        if by_parameters.is_some_and(|r| !crate::linalg::all_finite(r.as_slice())) {
            return Err(non_finite(NonFiniteValue::Jacobian));
        }
        let mut a = SVector::<L::Scalar, NA>::zeros();
        a.fixed_rows_mut::<N>(0).copy_from(&qddot);
        for (j, d) in self.directions.iter().enumerate() {
            let s = x.fixed_rows::<N>(N * (1 + j)).into_owned();
            let sdot = v.fixed_rows::<N>(N * (1 + j)).into_owned();
            let r_p = match (*d, &by_parameters) {
                (Direction::Parameter(k), Some(r)) => r.column(k).into_owned(),
                _ => SVector::zeros(),
            };
            let sddot = match (exact, differences) {
                (Some((r_q, r_v)), _) => mass.solve(&(-(r_q * s + r_v * sdot + r_p))),
                (None, Some((a_q, a_v))) => mass.solve(&r_p).map(|m_r| a_q * s + a_v * sdot - m_r),
                (None, None) => unreachable!("one of the two is taken above"),
            }
            .map_err(solve_error)?;
            a.fixed_rows_mut::<N>(N * (1 + j)).copy_from(&sddot);
        }
        Ok((a, m))
    }
}

// Every method written out (the lint holds it so): a capability added to
// the contract is passed on here, or said not to be.
#[warn(clippy::missing_trait_methods)]
impl<L, const N: usize, const P: usize, const D: usize, const NA: usize> Lagrangian<NA>
    for Sensitivity<L, N, P, D, NA>
where
    L: ParameterDerivatives<N, P>,
{
    type Scalar = L::Scalar;
    /// The model's coordinates, then an empty name for each sensitivity.
    const COORDINATES: [&'static str; NA] = {
        let mut names = [""; NA];
        let mut i = 0;
        while i < N {
            names[i] = L::COORDINATES[i];
            i += 1;
        }
        names
    };
    const HAS_CONTACTS: bool = L::HAS_CONTACTS;
    const SOLVES_ACCELERATIONS: bool = true;

    /// The model's `M` repeated down the diagonal (formed only when asked:
    /// a run solves with the model's own, [`accelerations`](Self::accelerations)).
    fn mass_matrix(&self, t: L::Scalar, x: &SVector<L::Scalar, NA>) -> SMatrix<L::Scalar, NA, NA> {
        let m = self.model.mass_matrix(t, &self.state(x));
        let mut out = SMatrix::<L::Scalar, NA, NA>::zeros();
        for j in 0..=D {
            out.fixed_view_mut::<N, N>(N * j, N * j).copy_from(&m);
        }
        out
    }

    /// `M` times the accelerations, block by block; NaN where they cannot
    /// be solved for.
    fn forcing(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> SVector<L::Scalar, NA> {
        match self.solve(t, x, v) {
            Ok((a, m)) => {
                let mut f = SVector::<L::Scalar, NA>::zeros();
                for j in 0..=D {
                    let block = m * a.fixed_rows::<N>(N * j);
                    f.fixed_rows_mut::<N>(N * j).copy_from(&block);
                }
                f
            }
            Err(_) => SVector::from_element(nalgebra::convert::<f64, L::Scalar>(f64::NAN)),
        }
    }

    /// The model's `T` (the sensitivities carry none).
    fn kinetic_energy(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> L::Scalar {
        self.model.kinetic_energy(t, &self.state(x), &self.state(v))
    }

    /// The model's `V`.
    fn potential_energy(&self, t: L::Scalar, x: &SVector<L::Scalar, NA>) -> L::Scalar {
        self.model.potential_energy(t, &self.state(x))
    }

    #[allow(clippy::type_complexity)]
    fn accelerations(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> Option<Result<SVector<L::Scalar, NA>, IntegrationError<L::Scalar, NA>>> {
        Some(self.solve(t, x, v).map(|(a, _)| a))
    }

    fn parameters_are_finite(&self) -> bool {
        self.model.parameters_are_finite()
    }

    /// The model's inputs, read at the model's part of the state: a run
    /// refuses inputs never set, and blames a controller's NaN, as for the
    /// model alone.
    fn visit_inputs<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: inputs::Visitor<L::Scalar, NA>,
    {
        self.model.visit_inputs(PassInputs {
            sensitivity: self,
            visitor,
        })
    }

    /// `M` and `f` as [`mass_matrix`](Self::mass_matrix) and
    /// [`forcing`](Self::forcing) give them (a run asks
    /// [`accelerations`](Self::accelerations) instead).
    fn mass_matrix_and_forcing(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> (SMatrix<L::Scalar, NA, NA>, SVector<L::Scalar, NA>) {
        (self.mass_matrix(t, x), self.forcing(t, x, v))
    }

    /// The model's `T + V`.
    fn energy(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> L::Scalar {
        self.kinetic_energy(t, x, v) + self.potential_energy(t, x)
    }

    // Not passed on, each for its reason:

    /// None: the implicit methods take differences of the whole system
    /// (the model's exact Jacobians are for its own `q`, not the
    /// sensitivities').
    fn residual_jacobians(
        &self,
        _: L::Scalar,
        _: &SVector<L::Scalar, NA>,
        _: &SVector<L::Scalar, NA>,
        _: &SVector<L::Scalar, NA>,
    ) -> Option<(SMatrix<L::Scalar, NA, NA>, SMatrix<L::Scalar, NA, NA>)> {
        None
    }
    /// None: the variational method refuses the model (its sensitivities
    /// have no Lagrangian of their own).
    fn momentum(
        &self,
        _: L::Scalar,
        _: &SVector<L::Scalar, NA>,
        _: &SVector<L::Scalar, NA>,
    ) -> Option<SVector<L::Scalar, NA>> {
        None
    }
    /// None: as [`momentum`](Self::momentum).
    fn lagrangian_gradient(
        &self,
        _: L::Scalar,
        _: &SVector<L::Scalar, NA>,
        _: &SVector<L::Scalar, NA>,
    ) -> Option<SVector<L::Scalar, NA>> {
        None
    }
    /// None: as [`momentum`](Self::momentum).
    fn nonconservative_forces(
        &self,
        _: L::Scalar,
        _: &SVector<L::Scalar, NA>,
        _: &SVector<L::Scalar, NA>,
    ) -> Option<SVector<L::Scalar, NA>> {
        None
    }
    /// None: [`Sensitivity::new`] refuses a constrained model.
    fn visit_constraints<V>(&self, _: V) -> Option<V::Output>
    where
        V: crate::model::constraints::Visitor<L::Scalar, NA>,
    {
        None
    }
    /// None: the model's `let`s are functions of its own `q`, not of the
    /// augmented state.
    fn visit_lets<V>(&self, _: V) -> Option<V::Output>
    where
        V: crate::model::lets::Visitor<L::Scalar, NA>,
    {
        None
    }
}

/// Hands a visitor of the augmented model the model's inputs, as the
/// augmented model's ([`WithInputs`]).
struct PassInputs<'a, L, V, const N: usize, const P: usize, const D: usize, const NA: usize> {
    sensitivity: &'a Sensitivity<L, N, P, D, NA>,
    visitor: V,
}

impl<L, V, const N: usize, const P: usize, const D: usize, const NA: usize>
    inputs::Visitor<L::Scalar, N> for PassInputs<'_, L, V, N, P, D, NA>
where
    L: ParameterDerivatives<N, P>,
    V: inputs::Visitor<L::Scalar, NA>,
{
    type Output = V::Output;

    fn visit<A, const K: usize>(self, model: &A) -> V::Output
    where
        A: Inputs<N, K, Scalar = L::Scalar> + ?Sized,
    {
        let augmented = WithInputs {
            sensitivity: self.sensitivity,
            inputs: model,
        };
        self.visitor.visit::<_, K>(&augmented)
    }
}

/// The augmented model with the model's `K` inputs (`inputs`, the model
/// or the layer that holds them), read at the model's part of the state.
struct WithInputs<'a, L, A: ?Sized, const N: usize, const P: usize, const D: usize, const NA: usize>
{
    sensitivity: &'a Sensitivity<L, N, P, D, NA>,
    inputs: &'a A,
}

// Every method written out (the lint holds it so): the sensitivity's.
#[warn(clippy::missing_trait_methods)]
impl<L, A, const N: usize, const P: usize, const D: usize, const NA: usize> Lagrangian<NA>
    for WithInputs<'_, L, A, N, P, D, NA>
where
    L: ParameterDerivatives<N, P>,
    A: ?Sized,
{
    type Scalar = L::Scalar;
    const COORDINATES: [&'static str; NA] =
        <Sensitivity<L, N, P, D, NA> as Lagrangian<NA>>::COORDINATES;
    const SOLVES_ACCELERATIONS: bool = true;

    fn mass_matrix(&self, t: L::Scalar, x: &SVector<L::Scalar, NA>) -> SMatrix<L::Scalar, NA, NA> {
        self.sensitivity.mass_matrix(t, x)
    }

    fn forcing(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> SVector<L::Scalar, NA> {
        self.sensitivity.forcing(t, x, v)
    }

    fn kinetic_energy(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> L::Scalar {
        self.sensitivity.kinetic_energy(t, x, v)
    }

    fn potential_energy(&self, t: L::Scalar, x: &SVector<L::Scalar, NA>) -> L::Scalar {
        self.sensitivity.potential_energy(t, x)
    }

    #[allow(clippy::type_complexity)]
    fn accelerations(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> Option<Result<SVector<L::Scalar, NA>, IntegrationError<L::Scalar, NA>>> {
        self.sensitivity.accelerations(t, x, v)
    }

    fn parameters_are_finite(&self) -> bool {
        self.sensitivity.parameters_are_finite()
    }

    fn mass_matrix_and_forcing(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> (SMatrix<L::Scalar, NA, NA>, SVector<L::Scalar, NA>) {
        self.sensitivity.mass_matrix_and_forcing(t, x, v)
    }

    fn energy(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> L::Scalar {
        self.sensitivity.energy(t, x, v)
    }

    fn residual_jacobians(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
        a: &SVector<L::Scalar, NA>,
    ) -> Option<(SMatrix<L::Scalar, NA, NA>, SMatrix<L::Scalar, NA, NA>)> {
        self.sensitivity.residual_jacobians(t, x, v, a)
    }

    fn momentum(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> Option<SVector<L::Scalar, NA>> {
        self.sensitivity.momentum(t, x, v)
    }

    fn lagrangian_gradient(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> Option<SVector<L::Scalar, NA>> {
        self.sensitivity.lagrangian_gradient(t, x, v)
    }

    fn nonconservative_forces(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> Option<SVector<L::Scalar, NA>> {
        self.sensitivity.nonconservative_forces(t, x, v)
    }

    fn visit_constraints<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: crate::model::constraints::Visitor<L::Scalar, NA>,
    {
        self.sensitivity.visit_constraints(visitor)
    }

    fn visit_inputs<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: inputs::Visitor<L::Scalar, NA>,
    {
        self.sensitivity.visit_inputs(visitor)
    }

    fn visit_lets<V>(&self, visitor: V) -> Option<V::Output>
    where
        V: crate::model::lets::Visitor<L::Scalar, NA>,
    {
        self.sensitivity.visit_lets(visitor)
    }
}

impl<L, A, const N: usize, const P: usize, const D: usize, const NA: usize, const K: usize>
    Inputs<NA, K> for WithInputs<'_, L, A, N, P, D, NA>
where
    L: ParameterDerivatives<N, P>,
    A: Inputs<N, K, Scalar = L::Scalar> + ?Sized,
{
    const NAMES: [&'static str; K] = A::NAMES;

    fn inputs_at(
        &self,
        t: L::Scalar,
        x: &SVector<L::Scalar, NA>,
        v: &SVector<L::Scalar, NA>,
    ) -> SVector<L::Scalar, K> {
        let (q, qdot) = (self.sensitivity.state(x), self.sensitivity.state(v));
        self.inputs.inputs_at(t, &q, &qdot)
    }

    fn held_inputs(&self) -> Option<SVector<L::Scalar, K>> {
        self.inputs.held_inputs()
    }
}
