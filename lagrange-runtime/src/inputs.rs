//! Control inputs: models whose forces depend on values `u` that change
//! during a run, set by a controller.
//!
//! A model written with an `inputs:` section implements [`Actuated`]
//! besides [`Lagrangian`](crate::Lagrangian): its `K` inputs are fields of the model that a
//! controller sets before each evaluation, and `∂f/∂u` is generated
//! symbolically beside `M` and `f`.
//!
//! Inputs start unset (NaN), and the integrators refuse a model whose
//! inputs were never set ([`InvalidInput::InputsNotSet`](crate::InvalidInput::InputsNotSet)):
//! no run silently integrates NaN or a zero nobody chose. Two ways to set
//! them:
//!
//! - **constant inputs**: [`model.with_inputs(&u)`](Actuated::with_inputs),
//!   integrated like any model;
//! - **a controller**: [`model.with_controller(|t, q, qdot| u)`](crate::model::WithLayers::with_controller),
//!   a [`Controlled`] model (the model under the [`Controller`] layer) that
//!   calls the controller once per evaluation of the right-hand side and
//!   integrates like any model. A prescribed input
//!   `u(t)` is a controller that ignores `q` and `q̇`; a feedback law reads
//!   them. A controller that returns a NaN or an infinity stops the run
//!   with [`NonFiniteValue::Inputs`](crate::NonFiniteValue::Inputs) at that
//!   `t` and state.
//!
//! Inputs never appear in the mass matrix, the momenta or the constraints
//! (`lagrangian!` refuses them there: their time derivatives would be
//! needed), so `M(t, q)`, `p` and `φ` are evaluated without the controller.
//!
//! The runtime reaches a model's inputs through
//! [`Lagrangian::visit_inputs`](crate::Lagrangian::visit_inputs), which hands a [`Visitor`] the model as
//! [`Inputs<N, K>`] with its `K` known: what the inputs are called, and
//! what they are at a state. That is how a run refuses inputs never set,
//! and blames a controller's NaN, whatever layers the model is under.
//!
//! The compiled example is on `lagrange::models::CartPole`.

pub use crate::model::controller::{Controlled, Controller};
pub use crate::model::inputs::{Actuated, Inputs, KeepsInputs, Visitor, unset, unset_array};
