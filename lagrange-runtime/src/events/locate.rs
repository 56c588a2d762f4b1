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

use super::{Events, RunData};
use crate::error::{IntegrationError, NonFiniteValue};
use crate::trajectory::State;

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
/// `state_at`, or `None` when no event crosses zero in its direction there.
///
/// Contract: `state_at(t)` is the state at any `t` in `[t0, t1]`, and
/// `state_at(t1)` is the state `g1` was computed from. Each event that
/// crosses is located to within `tolerance` (the final bracket's width; or
/// adjacent floating-point numbers), and the time returned is the
/// bracket's right end, where `g` has already crossed: continuing from it
/// with its `g` never finds the same crossing again.
///
/// A crossing shows as a change of sign between `g0` and `g1`, or, where
/// `g` has the same sign at both ends, as an extremum between them that
/// reaches across zero: a dip through zero and back within the step
/// ([`hidden_extremum`]). Evaluations of event functions are added to
/// `evaluations`; a non-finite value is
/// [`NonFiniteEvent`](IntegrationError::NonFiniteEvent) at the state where
/// it was evaluated.
/// The fraction of a step over which `g`'s rate is differenced, `2⁻²⁰`.
const STEP_FRACTION: f64 = 1.0 / 1_048_576.0;

pub(crate) fn first_crossing<S: RealField + Copy, const N: usize>(
    (events, data): (&Events<'_, S, N>, &RunData),
    (t0, g0): (S, &[S]),
    (t1, g1): (S, &[S]),
    tolerance: S,
    state_at: &mut dyn FnMut(S) -> State<S, N>,
    evaluations: &mut usize,
) -> Result<Option<Crossing<S, N>>, IntegrationError<S, N>> {
    let list = events.list();
    let mut first: Option<(S, usize)> = None;
    for (i, event) in list.iter().enumerate() {
        let mut g = |t: S| {
            let (q, qdot) = state_at(t);
            *evaluations += 1;
            finite(event.value(data, t, &q, &qdot), event.name(), t, (q, qdot))
        };
        // The bracket: from a point not yet crossed to one crossed, and
        // the value crossing is judged from.
        let bracket = if event.crosses(g0[i], g1[i]) {
            Some(((t0, g0[i]), (t1, g1[i]), g0[i]))
        } else if g0[i] == S::zero() && g1[i] != S::zero() {
            // Unarmed at the start (zero there: a restart on the event):
            // `g` may leave zero one way and come back across within the
            // step, as a ball does after a bounce shorter than the step.
            // Just after the start, on the interpolant, it shows which way
            // it left.
            let ta = t0 + (t1 - t0) * nalgebra::convert::<f64, S>(STEP_FRACTION);
            let ga = g(ta)?;
            event
                .crosses(ga, g1[i])
                .then_some(((ta, ga), (t1, g1[i]), ga))
        } else {
            match hidden_extremum(&mut g, (t0, g0[i]), (t1, g1[i]), tolerance)? {
                // Across zero and back: the way there, or the way back.
                Some(e) if event.crosses(g0[i], e.1) => Some(((t0, g0[i]), e, g0[i])),
                Some(e) if event.crosses(e.1, g1[i]) => Some((e, (t1, g1[i]), e.1)),
                _ => None,
            }
        };
        let Some((a, b, from)) = bracket else {
            continue;
        };
        if first.is_some_and(|(earliest, _)| a.0 >= earliest) {
            continue;
        }
        let crossed = |value: S| event.crosses(from, value);
        let t = illinois(&mut g, &crossed, a, b, tolerance)?;
        if first.is_none_or(|(earliest, _)| t < earliest) {
            first = Some((t, i));
        }
    }
    let Some((t, located)) = first else {
        return Ok(None);
    };
    let state = state_at(t);
    let g = evaluate((events, data), t, &state, evaluations)?;
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

/// Where `g` has the same sign at both ends of `[t0, t1]`, the extremum
/// between them that reaches furthest towards zero, if `g`'s rate shows one:
/// `g` moving towards zero at `t0` and away from it at `t1`. Returns a time
/// inside and `g` there: across zero (or at it) when the extremum reaches
/// it, which the caller turns into the brackets of the two crossings.
///
/// The rate is `g`'s own along the interpolant, by differences over
/// `δ = 2⁻²⁰ (t1 − t0)`: one-sided at the ends, central inside, so that it
/// needs nothing of the event but its values. The extremum is the rate's
/// root, located by [`illinois`]; the search stops as soon as a value
/// across zero is met, or when the quadratic model of `g` about the
/// bracket (curvature from the rates at its ends) puts the extremum's value
/// clearly on the same side as the ends. The guarantee that follows: a dip
/// through zero and back is found whenever `g` along the interpolant has
/// one extremum in the step; two or more within one step (an oscillation
/// of `g` faster than the step) can hide one.
fn hidden_extremum<S: RealField + Copy, E>(
    g: &mut dyn FnMut(S) -> Result<S, E>,
    (t0, g0): (S, S),
    (t1, g1): (S, S),
    tolerance: S,
) -> Result<Option<(S, S)>, E> {
    let zero = S::zero();
    // Unarmed (zero at an end), or a change of sign: not this search's.
    if g0 == zero || g1 == zero || (g0 > zero) != (g1 > zero) {
        return Ok(None);
    }
    // Towards zero is down for a positive g, up for a negative one.
    let sign = if g0 > zero { S::one() } else { -S::one() };
    let delta = (t1 - t0) * nalgebra::convert::<f64, S>(STEP_FRACTION);
    if !(t0 + delta > t0 && t1 - delta < t1) {
        return Ok(None);
    }
    let at_start = (g(t0 + delta)? - g0) / delta;
    let at_end = (g1 - g(t1 - delta)?) / delta;
    if !(sign * at_start < zero && sign * at_end > zero) {
        return Ok(None);
    }
    // Illinois on the rate, from towards zero (a) to away from it (b),
    // watching every value of g it passes.
    let (mut a, mut ra) = (t0, sign * at_start);
    let (mut b, mut rb) = (t1, sign * at_end);
    // The rates at the bracket's ends as measured (Illinois halves `ra`
    // or `rb` for its secant, not these).
    let (mut true_a, mut true_b) = (ra, rb);
    let two = S::one() + S::one();
    let mut moved = 0i8;
    let mut width_before = b - a;
    for iteration in 1..=MAX_ITERATIONS {
        let mid = a + (b - a) / two;
        if b - a <= tolerance || mid <= a || mid >= b {
            break;
        }
        let falsi = b - rb * (b - a) / (rb - ra);
        let safeguard = iteration % 3 == 0 && b - a > width_before / two;
        if iteration % 3 == 0 {
            width_before = b - a;
        }
        let inside = falsi.is_finite() && falsi > a + delta && falsi < b - delta;
        let t = if inside && !safeguard { falsi } else { mid };
        let (before, after) = (g(t - delta)?, g(t + delta)?);
        for (s, value) in [(t - delta, before), (t + delta, after)] {
            if sign * value <= zero {
                return Ok(Some((s, value)));
            }
        }
        let rate = sign * (after - before) / (delta + delta);
        // g within the bracket lies above its value at t less about half
        // the rate's change across the bracket times its width (g's
        // quadratic model); clearly above zero, the extremum is too.
        let value = (before + after) / two;
        if sign * value > (true_b - true_a) * (b - a) {
            return Ok(None);
        }
        if rate >= zero {
            true_b = rate;
            (b, rb) = (t, rate);
            if moved == 1 {
                ra /= two;
            }
            moved = 1;
        } else {
            true_a = rate;
            (a, ra) = (t, rate);
            if moved == -1 {
                rb /= two;
            }
            moved = -1;
        }
    }
    let t = a + (b - a) / two;
    let value = g(t)?;
    Ok((sign * value <= zero).then_some((t, value)))
}

/// [`evaluate`] into `g` (cleared first), so that a buffer kept from step
/// to step is not allocated again.
pub(crate) fn evaluate_into<S: RealField + Copy, const N: usize>(
    (events, data): (&Events<'_, S, N>, &RunData),
    t: S,
    state: &State<S, N>,
    g: &mut Vec<S>,
    evaluations: &mut usize,
) -> Result<(), IntegrationError<S, N>> {
    let (q, qdot) = state;
    g.clear();
    for event in events.list() {
        *evaluations += 1;
        g.push(finite(
            event.value(data, t, q, qdot),
            event.name(),
            t,
            *state,
        )?);
    }
    Ok(())
}

/// Every event's `g` at `(t, q, q̇)`; the first non-finite one is an error.
pub(crate) fn evaluate<S: RealField + Copy, const N: usize>(
    (events, data): (&Events<'_, S, N>, &RunData),
    t: S,
    state: &State<S, N>,
    evaluations: &mut usize,
) -> Result<Vec<S>, IntegrationError<S, N>> {
    let mut g = Vec::with_capacity(events.len());
    evaluate_into((events, data), t, state, &mut g, evaluations)?;
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
    g: &mut dyn FnMut(S) -> Result<S, E>,
    crossed: &dyn Fn(S) -> bool,
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
        let bound = (events, &() as &RunData);
        let g0 = evaluate(bound, t0, &cosine(t0), &mut n).unwrap();
        let g1 = evaluate(bound, t1, &cosine(t1), &mut n).unwrap();
        first_crossing(bound, (t0, &g0), (t1, &g1), tolerance, &mut cosine, &mut n).unwrap()
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
        let bound = (&events, &() as &RunData);
        let error = first_crossing(bound, start, end, 1e-12, &mut cosine, &mut n);
        assert!(matches!(
            error,
            Err(IntegrationError::NonFiniteEvent {
                event: "broken",
                ..
            })
        ));
    }
}
