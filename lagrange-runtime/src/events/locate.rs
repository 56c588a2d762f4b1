//! Locating the first crossing on a step's interpolant.
//!
//! The root finder is the Illinois variant of regula falsi, with a
//! bisection safeguard. Why not Brent: the function is `g` composed with an
//! interpolant, smooth on the step, with a bracket known from the step's
//! ends; Illinois keeps that bracket, converges superlinearly (order about
//! 1.44) on a simple root, needs one evaluation per iteration and fits in
//! twenty lines, and the safeguard (a bisection whenever three iterations
//! have not halved the bracket) bounds the worst case by three times
//! bisection's count. Brent's inverse quadratic steps would save an
//! iteration or two on evaluations that cost an interpolant, not a
//! right-hand side.

use nalgebra::RealField;

use super::Events;
use crate::driver::State;
use crate::{IntegrationError, NonFiniteValue};

/// The earliest crossing on a step: the time, the interpolated state there,
/// every event's `g` there, and which events crossed (in the order they
/// were added: the first located and any within the same bracket).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Crossing<S, const N: usize> {
    pub(crate) t: S,
    pub(crate) state: State<S, N>,
    pub(crate) g: Vec<S>,
    pub(crate) events: Vec<usize>,
}

/// Iterations before giving up on shrinking the bracket further (its right
/// end, a time past the crossing, is then returned): far more than the
/// safeguard ever needs, `3 × 64` bisections of an `f64` interval.
const MAX_ITERATIONS: usize = 3000;

/// The first crossing in `(t0, t1]` of any of `events`, on the interpolant
/// `state_at`, or `None` when no event changes sign in its direction
/// between `g0` (every event's value at `t0`) and `g1` (at `t1`).
///
/// Contract: `state_at(t)` is the state at any `t` in `(t0, t1]`, and
/// `state_at(t1)` is the state `g1` was computed from. Each event that
/// changes sign is located to within `tolerance` (the final bracket's
/// width; or adjacent floating-point numbers), and the time returned is the
/// bracket's right end, where `g` has already crossed: continuing from it
/// with its `g` never finds the same crossing again. A function that
/// changes sign twice between `t0` and `t1` is not seen. Evaluations of
/// event functions are added to `evaluations`; a non-finite value is
/// [`NonFiniteEvent`](IntegrationError::NonFiniteEvent) at the state where
/// it was evaluated.
pub(crate) fn first_crossing<S: RealField + Copy, const N: usize>(
    events: &Events<'_, S, N>,
    (t0, g0): (S, &[S]),
    (t1, g1): (S, &[S]),
    tolerance: S,
    mut state_at: impl FnMut(S) -> State<S, N>,
    evaluations: &mut usize,
) -> Result<Option<Crossing<S, N>>, IntegrationError<S, N>> {
    let list = events.list();
    let mut first: Option<(S, usize)> = None;
    for (i, event) in list.iter().enumerate() {
        if !event.crosses(g0[i], g1[i]) {
            continue;
        }
        let mut g = |t: S| {
            let (q, qdot) = state_at(t);
            *evaluations += 1;
            finite(event.value(t, &q, &qdot), event.name(), t, (q, qdot))
        };
        let crossed = |value: S| event.crosses(g0[i], value);
        let t = illinois(&mut g, crossed, (t0, g0[i]), (t1, g1[i]), tolerance)?;
        if first.is_none_or(|(earliest, _)| t < earliest) {
            first = Some((t, i));
        }
    }
    let Some((t, located)) = first else {
        return Ok(None);
    };
    let state = state_at(t);
    let g = evaluate(events, t, &state, evaluations)?;
    let events = (0..list.len())
        .filter(|&i| i == located || list[i].crosses(g0[i], g[i]))
        .collect();
    Ok(Some(Crossing {
        t,
        state,
        g,
        events,
    }))
}

/// [`evaluate`] into `g` (cleared first), so that a buffer kept from step
/// to step is not allocated again.
pub(crate) fn evaluate_into<S: RealField + Copy, const N: usize>(
    events: &Events<'_, S, N>,
    t: S,
    state: &State<S, N>,
    g: &mut Vec<S>,
    evaluations: &mut usize,
) -> Result<(), IntegrationError<S, N>> {
    let (q, qdot) = state;
    g.clear();
    for event in events.list() {
        *evaluations += 1;
        g.push(finite(event.value(t, q, qdot), event.name(), t, *state)?);
    }
    Ok(())
}

/// Every event's `g` at `(t, q, q̇)`; the first non-finite one is an error.
pub(crate) fn evaluate<S: RealField + Copy, const N: usize>(
    events: &Events<'_, S, N>,
    t: S,
    state: &State<S, N>,
    evaluations: &mut usize,
) -> Result<Vec<S>, IntegrationError<S, N>> {
    let mut g = Vec::with_capacity(events.len());
    evaluate_into(events, t, state, &mut g, evaluations)?;
    Ok(g)
}

fn finite<S: RealField + Copy, const N: usize>(
    value: S,
    event: &'static str,
    t: S,
    (q, qdot): State<S, N>,
) -> Result<S, IntegrationError<S, N>> {
    if value.is_finite() {
        Ok(value)
    } else {
        let value = NonFiniteValue::EventFunction;
        Err(IntegrationError::NonFiniteEvent {
            event,
            t,
            q,
            qdot,
            value,
        })
    }
}

/// The right end of a bracket of width at most `tolerance` around the
/// crossing of `g` in `(a, b]`, from `crossed(g(a)) = false`,
/// `crossed(g(b)) = true`. Illinois: regula falsi, with the value at an end
/// kept twice in a row halved, so that the other end moves too; a
/// bisection when the new point is not strictly inside, and whenever three
/// iterations have not halved the bracket.
fn illinois<S: RealField + Copy, E>(
    g: &mut impl FnMut(S) -> Result<S, E>,
    crossed: impl Fn(S) -> bool,
    (mut a, mut fa): (S, S),
    (mut b, mut fb): (S, S),
    tolerance: S,
) -> Result<S, E> {
    let two = S::one() + S::one();
    // +1 when the last iteration moved `b`, −1 when it moved `a`.
    let mut moved = 0i8;
    let mut width_before = b - a;
    for iteration in 1..=MAX_ITERATIONS {
        let mid = a + (b - a) / two;
        if b - a <= tolerance || mid <= a || mid >= b {
            break;
        }
        let falsi = b - fb * (b - a) / (fb - fa);
        let safeguard = iteration % 3 == 0 && b - a > width_before / two;
        if iteration % 3 == 0 {
            width_before = b - a;
        }
        let inside = falsi.is_finite() && falsi > a && falsi < b;
        let t = if inside && !safeguard { falsi } else { mid };
        let value = g(t)?;
        if crossed(value) {
            (b, fb) = (t, value);
            if moved == 1 {
                fa /= two;
            }
            moved = 1;
        } else {
            (a, fa) = (t, value);
            if moved == -1 {
                fb /= two;
            }
            moved = -1;
        }
    }
    Ok(b)
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector1;

    use super::*;
    use crate::events::Event;

    /// `x(t) = cos t` as a "trajectory": its state is exact, so only the
    /// root finder is measured.
    fn cosine(t: f64) -> State<f64, 1> {
        (Vector1::new(t.cos()), Vector1::new(-t.sin()))
    }

    fn on_cosine(
        events: &Events<'_, f64, 1>,
        (t0, t1): (f64, f64),
        tolerance: f64,
    ) -> Option<Crossing<f64, 1>> {
        let mut n = 0;
        let g0 = evaluate(events, t0, &cosine(t0), &mut n).unwrap();
        let g1 = evaluate(events, t1, &cosine(t1), &mut n).unwrap();
        first_crossing(events, (t0, &g0), (t1, &g1), tolerance, cosine, &mut n).unwrap()
    }

    #[test]
    fn locates_a_simple_root_to_the_tolerance() {
        let events = Events::new().with(Event::new("x", |_, q: &Vector1<f64>, _: &_| q[0]));
        for tolerance in [1e-3, 1e-8, 4.0 * f64::EPSILON] {
            let c = on_cosine(&events, (1.0, 2.0), tolerance).unwrap();
            let error = c.t - std::f64::consts::FRAC_PI_2;
            // The right end of a bracket no wider than the tolerance: past
            // the root (cos falls), by at most the tolerance.
            assert!((0.0..=tolerance).contains(&error), "{tolerance}: {error}");
            assert!(c.g[0] <= 0.0);
            assert_eq!(c.events, vec![0]);
        }
    }

    #[test]
    fn direction_decides_which_crossings_count() {
        let rising =
            Events::new().with(Event::new("x", |_, q: &Vector1<f64>, _: &_| q[0]).rising());
        assert!(on_cosine(&rising, (1.0, 2.0), 1e-12).is_none());
        let c = on_cosine(&rising, (4.0, 5.0), 1e-12).unwrap();
        assert!((c.t - 1.5 * std::f64::consts::PI).abs() <= 1e-12);
    }

    #[test]
    fn the_earliest_of_several_events_wins_and_ties_come_together() {
        let events = Events::new()
            .with(Event::new("late", |_, q: &Vector1<f64>, _: &_| q[0] + 0.5))
            .with(Event::new("early", |_, q: &Vector1<f64>, _: &_| q[0]))
            .with(Event::new("same", |_, q: &Vector1<f64>, _: &_| 2.0 * q[0]));
        let c = on_cosine(&events, (1.0, 2.5), 1e-13).unwrap();
        assert!((c.t - std::f64::consts::FRAC_PI_2).abs() <= 1e-13);
        assert_eq!(c.events, vec![1, 2]);
    }

    #[test]
    fn a_nan_event_is_an_error_naming_it() {
        // Finite at the step's ends (given), NaN inside, where it is located.
        let nan = |_, _: &Vector1<f64>, _: &Vector1<f64>| f64::NAN;
        let events = Events::new().with(Event::new("broken", nan));
        let mut n = 0;
        let (start, end) = ((0.5, &[0.5][..]), (2.0, &[-1.0][..]));
        let error = first_crossing(&events, start, end, 1e-12, cosine, &mut n);
        assert!(matches!(
            error,
            Err(IntegrationError::NonFiniteEvent {
                event: "broken",
                ..
            })
        ));
    }
}
