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
//! Sections, indices and `sum`, expressions, the equations derived, the
//! limits and every generated item: [`language`], the one reference (also
//! `docs/language.md` in the repository).
//!
//! ## Closed loops
//!
//! A `constraints:` section holds a model in redundant coordinates on its
//! holonomic constraints (`rod: x^2 + y^2 = l^2`): the macro derives their
//! Jacobian and bias beside `M` and `f`, every integrator runs the
//! saddle-point system with the state projected back after each step, and
//! the multipliers are the constraint forces: [`language`](language#constraints),
//! [`constraints`].
//!
//! ## Control, events, frames
//!
//! - Control inputs (`inputs:`), linearization, equilibria and modes:
//!   [`Actuated`], [`analysis`].
//! - Events and impacts (record, stop, reset; Zeno guard) and an observer
//!   at every step: [`events`], [`Integrator::integrate_with_events`].
//! - Per-frame stepping without allocation, for games and control loops:
//!   [`Stepper`].
//! - Drawing: every model's `LETS` and `lets(t, q, q̇)`; its equations as
//!   text (`EQUATIONS`) and LaTeX (`LATEX`).
//!
//! ## Cargo features
//!
//! None is on by default.
//!
//! | feature | what it adds |
//! |---|---|
//! | `models` | `lagrange::models`: the known problems (pendulums, chains, linkages, rigid bodies, rolling, contacts, the bicycle), ready to integrate |
//! | `serde` | `Serialize`/`Deserialize` for trajectories, statistics, errors and failures; `#[lagrange(serde)]` models through `lagrange::serde` |
//! | `csv` | `export::write_csv`: a trajectory with the model's names as the header, energy, multipliers, events |
//! | `ode_solvers` | `interop::ode_solvers::FirstOrder`: a model as that crate's `System`; `lagrange::ode_solvers` is the crate |
//! | `diffsol` | `interop::diffsol::problem`: a model as a diffsol `OdeSolverProblem`; `lagrange::diffsol` is the crate |
//!
//! ## Mistakes are compile errors that speak physics
//!
//! A model that is not mechanics (a coordinate without kinetic energy, a
//! potential holding a velocity, an index out of range) is one compile error
//! on the offending tokens: [`language`](language#mistakes-are-compile-errors).
//!
//! ## Where things live
//!
//! The macro is a thin shell over the engine (`lagrange-engine`, an ordinary
//! library); the runtime (`lagrange-runtime`, re-exported here) holds the
//! [`Lagrangian`] trait, the integrators and their results. `ARCHITECTURE.md`
//! in the repository is the map.

#![deny(missing_docs)]

extern crate self as lagrange;

pub use lagrange_macros::lagrangian;
/// The sine and cosine kernel the generated code calls
/// (`lagrange_runtime::trig`): reached by `lagrangian!`'s expansion, not
/// part of a model's or a simulation's API, so hidden here.
#[doc(hidden)]
pub use lagrange_runtime::trig;
pub use lagrange_runtime::*;
pub use nalgebra;
/// The serde that `#[lagrange(serde)]` models derive through (feature
/// `serde`), so that a model crate needs no serde dependency of its own.
#[cfg(feature = "serde")]
pub use serde;

#[cfg(feature = "models")]
pub mod models;

#[doc = include_str!("../docs/language.md")]
pub mod language {}

#[doc = include_str!("../docs/guides/README.md")]
pub mod guide {
    #[doc = include_str!("../docs/guides/constraints.md")]
    pub mod constraints {}
    #[doc = include_str!("../docs/guides/rigid_bodies.md")]
    pub mod rigid_bodies {}
    #[doc = include_str!("../docs/guides/contacts.md")]
    pub mod contacts {}
    #[doc = include_str!("../docs/guides/control.md")]
    pub mod control {}
    #[doc = include_str!("../docs/guides/robots.md")]
    pub mod robots {}
    #[doc = include_str!("../docs/guides/identify.md")]
    pub mod identify {}
    #[doc = include_str!("../docs/guides/events.md")]
    pub mod events {}
    #[doc = include_str!("../docs/guides/stepper.md")]
    pub mod stepper {}
    #[doc = include_str!("../docs/guides/methods.md")]
    pub mod methods {}
    #[doc = include_str!("../docs/guides/results.md")]
    pub mod results {}
    #[doc = include_str!("../docs/guides/speed.md")]
    pub mod speed {}
}

/// Everything a model and a simulation need: the macro, the [`Lagrangian`]
/// trait, the integrators and their results.
pub mod prelude {
    pub use crate::lagrangian;
    pub use lagrange_runtime::prelude::*;
}
