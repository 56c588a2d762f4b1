//! Known problems, ready to use: shared by the tests, the examples, the
//! benchmarks and anyone who wants a known model to try an integrator on.
//! Each is a `lagrangian!` invocation in its own file (read the source),
//! with its usual starting states and, where one exists, its exact
//! solution. Also every integrator by name ([`Method`]), for studies that
//! run them all, and [`WithoutJacobians`], for the finite-difference path
//! of the implicit methods.

mod chain;
mod double_pendulum;
mod kepler;
mod methods;
mod oscillator;
mod pendulum;
mod stiff_chain;
mod two_mass_chain;
mod without_jacobians;

pub use chain::Chain;
pub use double_pendulum::DoublePendulum;
pub use kepler::{Kepler, PolarKepler};
pub use methods::{AnyIntegrator, Method};
pub use oscillator::Oscillator;
pub use pendulum::Pendulum;
pub use stiff_chain::StiffChain;
pub use two_mass_chain::{RayleighTwoMassChain, TwoMassChain};
pub use without_jacobians::WithoutJacobians;
