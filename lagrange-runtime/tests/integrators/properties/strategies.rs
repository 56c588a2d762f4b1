//! Random inputs.

use proptest::prelude::*;

use super::Settings;

/// Values no finite range draws: NaN, the infinities, zeros, the extremes.
fn special() -> impl Strategy<Value = f64> {
    prop::sample::select(vec![
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -0.0,
        f64::MAX,
        -f64::MAX,
        f64::MIN_POSITIVE,
        1e300,
        -1e300,
        1e-300,
        f64::EPSILON,
    ])
}

/// `±10^e`, `e` uniform in `[lo, hi)`: every scale, not only near 1.
fn magnitude(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi, any::<bool>()).prop_map(|(e, negative)| {
        let x = 10f64.powf(e);
        if negative { -x } else { x }
    })
}

/// Mostly `typical`, sometimes any scale, sometimes special.
fn value(typical: impl Strategy<Value = f64>) -> impl Strategy<Value = f64> {
    prop_oneof![
        24 => typical,
        2 => magnitude(-300.0, 300.0),
        1 => special(),
    ]
}

/// A physical parameter: mostly positive and of order one.
pub(super) fn parameter() -> impl Strategy<Value = f64> {
    value(magnitude(-1.0, 1.0).prop_map(f64::abs))
}

pub(super) fn coordinate() -> impl Strategy<Value = f64> {
    value(-5.0..5.0)
}

/// Step sizes and tolerances: mostly positive, from tiny to large.
fn positive(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    value(magnitude(lo, hi).prop_map(f64::abs))
}

pub(super) fn settings() -> impl Strategy<Value = Settings> {
    (
        positive(-4.0, 0.5),
        positive(-16.0, 3.0),
        positive(-16.0, 3.0),
        // Small budgets keep every run short whatever the span asked for.
        prop_oneof![1 => 0usize..4, 9 => 50usize..2000],
    )
        .prop_map(|(h, rtol, atol, max_steps)| Settings {
            h,
            rtol,
            atol,
            max_steps,
        })
}

/// `t0` and sample times: mostly sorted and after `t0`, sometimes not.
pub(super) fn times() -> impl Strategy<Value = (f64, Vec<f64>)> {
    let t0 = value(-10.0..10.0);
    let offset = value(0.0..20.0);
    let shuffled = prop::bool::weighted(0.1);
    (t0, prop::collection::vec(offset, 0..5), shuffled).prop_map(|(t0, offsets, shuffled)| {
        let mut times: Vec<f64> = offsets.iter().map(|d| t0 + d.abs()).collect();
        if !shuffled {
            times.sort_by(f64::total_cmp);
        }
        (t0, times)
    })
}
