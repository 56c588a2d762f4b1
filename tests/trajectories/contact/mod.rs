//! Contacts and friction (`contacts:`) against closed forms: a contact
//! that opens where its force vanishes, a string that goes slack and snaps
//! taut, friction that sticks and slips, bounces that accumulate into a
//! resting contact, a box whose corners switch in any order, a tippe top
//! that turns over, and every method on them.

mod closed_forms;
mod frames;
mod friction;
mod held;
mod ladder;
mod methods;
mod plane;
mod tippe_top;
mod tumbling;

use lagrange::contact::{self, ContactResult, ContactSettings, Contacts};
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;

/// Dop853 at 1e-12: its global error over these runs of a few seconds is
/// about 1e-12 relative (a few 1e-12 absolute at the scales of 1 m and
/// 10 m/s), which bounds what the tests below ask of a located switch.
fn tight() -> Dop853<f64> {
    Dop853::new().rtol(1e-12).atol(1e-12)
}

/// A contact run with Dop853 at 1e-12 and the default contact settings.
fn run<L, const N: usize, const K: usize>(
    model: &L,
    (q0, v0): ([f64; N], [f64; N]),
    times: &[f64],
) -> ContactResult<f64, N, K>
where
    L: Contacts<N, K, Scalar = f64> + Sync,
{
    contact::integrate(
        &tight(),
        model,
        0.0,
        SVector::from(q0),
        SVector::from(v0),
        times,
        ContactSettings::default(),
    )
}

/// `n` sample times spread evenly over `(0, end]`.
fn times(end: f64, n: usize) -> Vec<f64> {
    (1..=n).map(|k| end * k as f64 / n as f64).collect()
}
