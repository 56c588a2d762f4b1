//! [`ParameterDerivatives<N, P>`]: a model's parameter scalars, read and
//! set by index, and its derivatives by them, for models written with
//! `#[lagrange(parameter_derivatives)]`. What forward sensitivities
//! ([`sensitivity`](crate::sensitivity)) and fits to measurements are built
//! on. And the parameters' [`Domain`]s (`parameters: m > 0, e in [0, 1];`),
//! which the generated checked constructors and the fits keep.

use std::fmt;

use nalgebra::{RealField, SMatrix, SVector};

use super::Lagrangian;

/// A model with its parameters' derivatives: `∂M/∂p`, `∂f/∂p` and the
/// residual's `∂r/∂p`, `P` the number of parameter scalars (an indexed
/// parameter `m[N]` counts `N`).
///
/// `lagrangian!` implements it for a model written with
/// `#[lagrange(parameter_derivatives)]`, each derivative derived at compile
/// time like `M` and `f` (the language reference, `lagrange::language`,
/// "Options"). A constrained model implements it too; the derivatives of
/// its constraints are the generated struct's inherent methods
/// (`constraint_parameter_jacobian` and its two siblings).
pub trait ParameterDerivatives<const N: usize, const P: usize>: Lagrangian<N> {
    /// The parameter scalars' names (`m1`, `l[0]`, …), the columns of the
    /// derivatives below: the generated struct's `PARAMETER_SCALARS`.
    const PARAMETERS: [&'static str; P];

    /// The parameter scalars' values, in the order of
    /// [`PARAMETERS`](Self::PARAMETERS).
    fn parameter_values(&self) -> SVector<Self::Scalar, P>;

    /// Sets every parameter scalar, in the order of
    /// [`PARAMETERS`](Self::PARAMETERS).
    fn set_parameter_values(&mut self, values: &SVector<Self::Scalar, P>);

    /// `∂M/∂p_k` at `(t, q)`, one `N × N` matrix per parameter scalar.
    fn mass_matrix_parameter_derivatives(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
    ) -> [SMatrix<Self::Scalar, N, N>; P];

    /// `∂f/∂p`, `N × P`, at `(t, q, q̇)`.
    fn forcing_parameter_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, P>;

    /// `∂r/∂p = (∂M/∂p) q̈ − ∂f/∂p`, `N × P`, of the residual
    /// `r = M(t, q) q̈ − f(t, q, q̇)`.
    fn residual_parameter_jacobian(
        &self,
        t: Self::Scalar,
        q: &SVector<Self::Scalar, N>,
        qdot: &SVector<Self::Scalar, N>,
        qddot: &SVector<Self::Scalar, N>,
    ) -> SMatrix<Self::Scalar, N, P>;

    /// The index of the parameter scalar named `name` (as
    /// [`PARAMETERS`](Self::PARAMETERS) writes it), if there is one.
    fn parameter_index(name: &str) -> Option<usize> {
        Self::PARAMETERS.iter().position(|p| *p == name)
    }

    /// Each parameter scalar's domain, in the order of
    /// [`PARAMETERS`](Self::PARAMETERS): what the model declares
    /// (`parameters: l > 0;`), [`Domain::REAL`] where it declares none. A
    /// fit ([`identify`](crate::identify)) refuses a start outside them and
    /// keeps its values inside.
    const DOMAINS: [Domain; P] = [Domain::REAL; P];
}

/// The values a parameter may take, as a model declares them
/// (`parameters: m > 0, c >= 0, e in [0, 1], x in (0, 1), u <= 2;`): an
/// interval whose ends are each open or closed, infinite where there is no
/// bound (then open).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Domain {
    /// The lower end (`-∞` where there is none).
    pub lower: f64,
    /// The upper end (`+∞` where there is none).
    pub upper: f64,
    /// Whether `lower` itself is inside (`>=`, `[`).
    pub lower_closed: bool,
    /// Whether `upper` itself is inside (`<=`, `]`).
    pub upper_closed: bool,
}

impl Domain {
    /// Every real number: a parameter declared without a domain.
    pub const REAL: Domain = Domain::new(f64::NEG_INFINITY, false, f64::INFINITY, false);

    /// The interval from `lower` to `upper`, each end closed or open.
    pub const fn new(lower: f64, lower_closed: bool, upper: f64, upper_closed: bool) -> Self {
        Domain {
            lower,
            upper,
            lower_closed,
            upper_closed,
        }
    }

    /// Whether `value` lies inside (a NaN never does).
    pub fn contains(&self, value: f64) -> bool {
        let above = if self.lower_closed {
            value >= self.lower
        } else {
            value > self.lower
        };
        let below = if self.upper_closed {
            value <= self.upper
        } else {
            value < self.upper
        };
        above && below
    }

    /// Whether this is every real number (no bound).
    pub fn is_real(&self) -> bool {
        self.lower == f64::NEG_INFINITY && self.upper == f64::INFINITY
    }

    /// `Ok` where `value`, the parameter `name` (element `index` of an
    /// indexed one), lies inside; the error naming them where it does not.
    /// What the generated `check_parameters` calls for each parameter with
    /// a domain.
    pub fn check<S: RealField + Copy>(
        self,
        name: &'static str,
        index: Option<usize>,
        value: S,
    ) -> Result<(), ParameterError> {
        let value = value.to_subset().unwrap_or(f64::NAN);
        if self.contains(value) {
            Ok(())
        } else {
            Err(ParameterError {
                name,
                index,
                value,
                domain: self,
            })
        }
    }

    /// [`check`](Self::check) of every element of an indexed parameter.
    pub fn check_all<S: RealField + Copy, const K: usize>(
        self,
        name: &'static str,
        values: &[S; K],
    ) -> Result<(), ParameterError> {
        values
            .iter()
            .enumerate()
            .try_for_each(|(i, v)| self.check(name, Some(i), *v))
    }
}

/// `x > 0`, `x >= 0`, `x < 1`, `x <= 1`, `x in [0, 1]`, `x in (0, 1)` as the
/// language writes them, `x in [0, 1)` for a mix, `x real` for
/// [`Domain::REAL`].
impl fmt::Display for Domain {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (low, high) = (self.lower.is_finite(), self.upper.is_finite());
        match (low, high) {
            (false, false) => write!(f, "real"),
            (true, false) => {
                let op = if self.lower_closed { ">=" } else { ">" };
                write!(f, "{op} {}", self.lower)
            }
            (false, true) => {
                let op = if self.upper_closed { "<=" } else { "<" };
                write!(f, "{op} {}", self.upper)
            }
            (true, true) => {
                let open = if self.lower_closed { '[' } else { '(' };
                let close = if self.upper_closed { ']' } else { ')' };
                write!(f, "in {open}{}, {}{close}", self.lower, self.upper)
            }
        }
    }
}

/// A parameter's value outside its declared [`Domain`]: what the generated
/// `try_new`, `from_parameters` and `check_parameters` return, and a fit
/// started there (`identify::FitError::OutsideDomain`).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("parameter `{}` is {value}, outside its domain `{} {domain}`", self.label(), self.label())]
pub struct ParameterError {
    /// The parameter's name as declared.
    pub name: &'static str,
    /// The element of an indexed parameter (`l[2]`: `Some(2)`).
    pub index: Option<usize>,
    /// The value given (NaN where the scalar has no `f64` value).
    pub value: f64,
    /// Its domain.
    pub domain: Domain,
}

impl ParameterError {
    /// The parameter as the model's `PARAMETER_SCALARS` writes it: `l1`,
    /// `l[2]`.
    pub fn label(&self) -> String {
        match self.index {
            None => self.name.to_string(),
            Some(i) => format!("{}[{i}]", self.name),
        }
    }
}
