//! Runtime for lagrange models.
mod lagrangian;
pub use lagrangian::Lagrangian;
pub use nalgebra;
