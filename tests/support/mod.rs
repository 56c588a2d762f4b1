//! What the test groups share besides the problems of `lagrange::models`
//! and its list of methods: the references of `tests/data/`, closed forms
//! and seeded random states, Jacobi elliptic functions, fits.
#![allow(dead_code)]

pub mod closed_form;
pub mod elliptic;
pub mod fit;
pub mod reference;
