extern crate self as lagrange;
pub use lagrange_macros::lagrangian;
pub use lagrange_runtime::*;
pub use nalgebra;
pub mod prelude {
    pub use crate::lagrangian;
    pub use crate::Lagrangian;
}
