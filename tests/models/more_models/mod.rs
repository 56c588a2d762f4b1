//! More models from the textbooks, several of them rheonomic (positions that
//! depend on `t` explicitly), against closed forms derived by hand. Each model
//! is written the way a student would: Cartesian positions of the masses,
//! then `T` and `V`; the engine does the rest.
//!
//! The models whose constraints stand still are in `scleronomic.rs`, those
//! whose constraints move with `t` in `rheonomic.rs`.

use crate::support::closed_form::*;
use lagrange::nalgebra::Vector1;
use rand::rngs::StdRng;

mod rheonomic;
mod scleronomic;

fn state1(rng: &mut StdRng) -> (f64, Vector1<f64>, Vector1<f64>, Vector1<f64>) {
    (
        time(rng),
        Vector1::new(angle(rng)),
        Vector1::new(rate(rng)),
        Vector1::new(rate(rng)),
    )
}

/// Over all samples, the largest share of the scale that one term takes:
/// if a test's point is that term, it must be far above `TOL`, or a model
/// that dropped it would pass.
#[track_caller]
fn assert_term_matters(what: &str, largest_share: f64) {
    assert!(
        largest_share > 0.1,
        "{what} is never more than {largest_share:e} of the scale"
    );
}
