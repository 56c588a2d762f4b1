//! # lagrange
//!
//! Write a mechanical system's kinetic and potential energy inline in Rust;
//! `lagrangian!` derives the Euler–Lagrange equations symbolically while the
//! crate compiles and expands to plain, allocation-free functions for the
//! mass matrix `M(t, q)` and the forcing `f(t, q, q̇)` with `M q̈ = f`. The
//! runtime integrates them. No CAS session, no code-generation step, no
//! symbolic work at run time.
//!
//! ## A model in a few lines
//!
//! ```
//! use lagrange::prelude::*;
//! use lagrange::nalgebra::Vector2;
//!
//! lagrangian! {
//!     /// The double pendulum, absolute angles from the downward vertical.
//!     pub struct DoublePendulum {
//!         coordinates: theta1, theta2;
//!         parameters: m1, m2, l1, l2, g;
//!         let x1 = l1*sin(theta1);
//!         let y1 = -l1*cos(theta1);
//!         let x2 = x1 + l2*sin(theta2);
//!         let y2 = y1 - l2*cos(theta2);
//!         kinetic: m1/2*(dot(x1)^2 + dot(y1)^2) + m2/2*(dot(x2)^2 + dot(y2)^2);
//!         potential: m1*g*y1 + m2*g*y2;
//!     }
//! }
//!
//! let pendulum = DoublePendulum::new(1.0, 1.0, 1.0, 1.0, 9.81);
//! let (q0, qdot0) = (Vector2::new(2.0, 2.5), Vector2::zeros());
//!
//! // The derived equations, evaluated: M(q) and f(q, q̇).
//! let m = pendulum.mass_matrix(0.0, &q0);
//! assert!((m[(0, 1)] - (2.0f64 - 2.5).cos()).abs() < 1e-15); // m2 l1 l2 cos(θ1 − θ2)
//!
//! // Integrated: adaptive Dormand–Prince, sampled where we ask.
//! let trajectory = Dopri5::new()
//!     .rtol(1e-10)
//!     .atol(1e-10)
//!     .integrate(&pendulum, 0.0, q0, qdot0, &[0.5, 1.0])?;
//! let e0 = pendulum.energy(0.0, &q0, &qdot0);
//! let end = trajectory.last().unwrap();
//! assert!((pendulum.energy(end.t, &end.q, &end.qdot) - e0).abs() < 1e-7);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## The language
//!
//! - `coordinates: a, b;` the generalized coordinates, in the order of `q`;
//!   `theta[N]` declares `N` of them, `theta[0]` … `theta[N-1]`, in index order.
//! - `parameters: m, l;` runtime parameters: public fields of the struct,
//!   and the arguments of `new`, in this order; `m[N]` is a field `m: [S; N]`.
//! - `const N = 6;` a compile-time integer; `constants: g = 9.81;` values
//!   folded into the generated code (no field, no run-time cost).
//! - `let name = expr;` intermediate quantities (positions, lengths) in terms
//!   of coordinates, parameters, `t` and earlier `let`s; `let x[i in 0..N] =
//!   expr;` one per index.
//! - `sum(j in a..b, expr)`, `sum(j in a..=b, expr)`, unrolled at compile
//!   time; ranges may use outer indices, indices may use arithmetic
//!   (`theta[i-1]`, `x[N-1]`); an index out of range is a compile error.
//! - `dot(e)` the total time derivative `Σ ∂e/∂q_i q̇_i + ∂e/∂t`.
//! - `kinetic:` T and `potential:` V (required; V may be `0`),
//!   `dissipation:` a Rayleigh function R(q, q̇), `forces: p = expr, ...`
//!   non-conservative forces (may use t, q, q̇) on a coordinate or along any
//!   position `p` (a `let`): `Q_i += F ∂p/∂q_i`, the virtual work.
//! - Sections may repeat, in any order; repeated `kinetic:`, `potential:` and
//!   `dissipation:` sections add up.
//! - `#[lagrange(jacobians)]` on the struct: also generate the exact
//!   Jacobians of the residual `M q̈ − f`, which implicit integrators use for
//!   Newton's method (opt-in: compile time is paid only where it is used).
//! - `+ - * /`, unary minus, `^` as power with mathematical precedence
//!   (`-x^2` is −x², `a*b^2` is a·b²), real literals (`1/2` is 0.5), and
//!   `sin cos tan asin acos atan atan2 sinh cosh tanh exp ln sqrt powi powf`,
//!   also as methods (`x.sin()`, `x.powi(2)`, `y.atan2(x)`).
//!
//! With `L = T − V`: `M = ∂²T/∂q̇²` and
//! `f = ∂L/∂q − (∂²L/∂q̇∂q) q̇ − ∂²L/∂q̇∂t − ∂R/∂q̇ + Q`.
//!
//! ## What is generated
//!
//! For `struct Name` with `N` coordinates: `Name<S = f64>` (any
//! `S: RealField + Copy`, `f32` included) with the parameters as fields, and
//! `DOF`, `COORDINATES`, `PARAMETERS`, `EQUATIONS` (the derived equations as
//! text), `new`, `mass_matrix`, `forcing`, `mass_matrix_and_forcing`,
//! `kinetic_energy`, `potential_energy`, `energy`, `momentum` (∂L/∂q̇),
//! `lagrangian_gradient` (∂L/∂q), `nonconservative_forces` (Q − ∂R/∂q̇; only
//! for a model with forces or dissipation, others are
//! [`Lagrangian::CONSERVATIVE`] and emit no code for them), and
//! with `#[lagrange(jacobians)]` `residual_jacobians`; plus an implementation of
//! [`Lagrangian`] so the integrators take it.
//!
//! ## Mistakes are compile errors that speak physics
//!
//! ```compile_fail
//! use lagrange::prelude::*;
//! lagrangian! {
//!     pub struct Broken {
//!         coordinates: x, y;
//!         parameters: m, k;
//!         kinetic: m/2*dot(x)^2;            // error: coordinate `y` has no
//!         potential: k/2*(x^2 + y^2);       // kinetic energy: the mass matrix
//!     }                                     // is singular
//! }
//! ```

extern crate self as lagrange;

pub use lagrange_macros::lagrangian;
pub use lagrange_runtime::*;
pub use nalgebra;

pub mod models;

/// Everything a model and a simulation need: the macro, the [`Lagrangian`]
/// trait, the integrators and their results.
pub mod prelude {
    pub use crate::lagrangian;
    pub use lagrange_runtime::prelude::*;
}
