//! The contact examples' runs (`contacts`, `contacts_3d`): Dop853,
//! sampled evenly.

use lagrange::contact::{self, ContactResult, ContactSettings, Contacts};
use lagrange::nalgebra::SVector;
use lagrange::prelude::*;

/// `model` from `(q0, v0)` at `t = 0` to `end`, sampled `samples` times
/// evenly, by Dop853 at `rtol = atol = tolerance`, with `settings`.
pub fn run_with<L, const N: usize, const K: usize>(
    model: &L,
    (q0, v0): ([f64; N], [f64; N]),
    end: f64,
    samples: usize,
    tolerance: f64,
    settings: ContactSettings<f64>,
) -> ContactResult<f64, N, K>
where
    L: Contacts<N, K, Scalar = f64> + Sync,
{
    let times: Vec<f64> = (1..=samples)
        .map(|k| end * k as f64 / samples as f64)
        .collect();
    contact::integrate(
        &Dop853::new().rtol(tolerance).atol(tolerance),
        model,
        0.0,
        SVector::from(q0),
        SVector::from(v0),
        &times,
        settings,
    )
}

/// The same at 1e-12 with the default contact settings.
pub fn run<L, const N: usize, const K: usize>(
    model: &L,
    start: ([f64; N], [f64; N]),
    end: f64,
    samples: usize,
) -> ContactResult<f64, N, K>
where
    L: Contacts<N, K, Scalar = f64> + Sync,
{
    run_with(
        model,
        start,
        end,
        samples,
        1e-12,
        ContactSettings::default(),
    )
}
