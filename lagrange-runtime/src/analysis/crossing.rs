//! Where a family of linearized motions turns stable or unstable:
//! [`stability_crossing`], the parameter (a speed, a gain) at which an
//! eigenvalue of the state matrix crosses the imaginary axis.
//!
//! # Bisection on the sign, to the last bit
//!
//! The crossing is the root of the growth rate `σ(p) = max Re λ(A(p))`.
//! That function is continuous but not smooth: where a complex pair meets
//! a real eigenvalue (the bicycle's weave pair splits into two real
//! eigenvalues near 0.7 m/s), or where another eigenvalue overtakes the
//! largest, `σ` has a kink, and a secant or Brent step built on its
//! values loses its superlinear rate there and may be thrown far off.
//! Nearer the root, `σ` is known only to the rounding of the eigenvalue
//! solver, some `ε ‖A‖`. Bisection needs neither: it reads only the sign
//! of `σ`, halves the bracket each time whatever the shape, and stops
//! where the bracket's two ends are adjacent floating-point numbers. That
//! costs about 52 evaluations for a bracket of order 1 in `f64`, against
//! some 10 for Brent on a smooth `σ`; a state matrix is cheap beside a run
//! (the bicycle's, by [`linearize_steady_motion`](super::linearize_steady_motion),
//! is 4 × 6 saddle solves and some small factorizations), and the answer
//! is exact in the sense that matters: the last bit at which the computed
//! `σ` changes sign. Its distance to the true crossing is the rounding of
//! `σ` over its slope, the condition of the problem, not of the method.
//!
//! # One crossing in the bracket
//!
//! The ends' signs cannot see a pair of crossings between them, so the
//! bracket is first sampled at [`SAMPLES`] equal intervals: no change of
//! sign among the samples is [`CrossingError::NoCrossing`], more than one
//! is [`CrossingError::Several`] with the sub-brackets where each lies
//! (call again on one). Two crossings within one sample interval stay
//! unseen; narrow the bracket where the eigenvalues are close.

use nalgebra::{Complex, DMatrix, RealField};

/// How many equal intervals the bracket is sampled at before the
/// bisection, to find every change of sign the samples can see.
pub const SAMPLES: usize = 16;

/// Which way the motion's stability changes with the parameter increasing
/// through the crossing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Turns {
    /// Unstable below the crossing, stable above (the bicycle's weave).
    Stable,
    /// Stable below, unstable above (the bicycle's capsize).
    Unstable,
}

/// A parameter value where the largest real part of the state matrix's
/// eigenvalues changes sign, located to the last bit.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing<S: RealField + Copy> {
    /// The crossing: whichever end of [`bracket`](Self::bracket) has the
    /// smaller growth rate in magnitude (no float lies between them).
    pub parameter: S,
    /// Adjacent (or equal) parameter values with growth rates of opposite
    /// signs: the crossing lies between them.
    pub bracket: (S, S),
    /// Which way stability changes.
    pub turns: Turns,
    /// The eigenvalue with the largest real part at
    /// [`parameter`](Self::parameter): its imaginary part says whether an
    /// oscillation (a complex pair, as the weave, a Hopf bifurcation) or a
    /// real mode (as capsize) crosses.
    pub eigenvalue: Complex<S>,
    /// State matrices evaluated, samples included.
    pub evaluations: usize,
}

/// Why [`stability_crossing`] found no crossing.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CrossingError<S: RealField + Copy, E> {
    /// The bracket's ends are not finite numbers with `lo < hi`.
    #[error("the bracket {lo:?}..{hi:?} is not two finite numbers in increasing order")]
    Bracket {
        /// Its lower end.
        lo: S,
        /// Its upper end.
        hi: S,
    },

    /// The largest real part has the same sign at every sample of the
    /// bracket (its values at the ends given).
    #[error(
        "no eigenvalue crosses the imaginary axis in {lo:?}..{hi:?} (at the samples): the largest \
         real part is {growth_lo:?} at the lower end and {growth_hi:?} at the upper"
    )]
    NoCrossing {
        /// The lower end.
        lo: S,
        /// The upper end.
        hi: S,
        /// The largest real part at `lo`.
        growth_lo: S,
        /// The largest real part at `hi`.
        growth_hi: S,
    },

    /// The largest real part changes sign more than once among the
    /// samples: each sub-bracket holds one change of sign; call again on
    /// the one wanted.
    #[error("the largest real part changes sign {} times in the bracket, in {brackets:?}: call on one", brackets.len())]
    Several {
        /// The sample intervals where the sign changes, in order.
        brackets: Vec<(S, S)>,
    },

    /// The closure's state matrix at `parameter` is not square, or is
    /// empty.
    #[error("the state matrix at {parameter:?} is {rows} × {columns}, not square")]
    NotSquare {
        /// Where it was asked for.
        parameter: S,
        /// Its rows.
        rows: usize,
        /// Its columns.
        columns: usize,
    },

    /// The state matrix at `parameter` has a NaN or infinite entry (or
    /// its eigenvalues came out so).
    #[error("the state matrix at {parameter:?} has a NaN or infinite entry or eigenvalue")]
    NonFinite {
        /// Where it was asked for.
        parameter: S,
    },

    /// The closure failed at `parameter`.
    #[error("the state matrix at {parameter:?} could not be formed: {source}")]
    Model {
        /// Where it was asked for.
        parameter: S,
        /// The closure's error.
        source: E,
    },
}

/// The eigenvalues of `a` with the largest real part first.
fn largest<S: RealField + Copy>(a: &DMatrix<S>) -> Complex<S> {
    a.complex_eigenvalues()
        .iter()
        .copied()
        .fold(None, |best: Option<Complex<S>>, e| match best {
            Some(b) if b.re >= e.re => Some(b),
            _ => Some(e),
        })
        .unwrap_or_else(|| Complex::new(S::zero(), S::zero()))
}

/// The parameter in `lo..=hi` where the largest real part of the
/// eigenvalues of `state_matrix(p)` changes sign: where a mode of the
/// linearized motion crosses from decaying to growing or back.
///
/// `state_matrix` gives the state matrix `A` of the small motions at a
/// parameter value, for instance
/// [`linearize_steady_motion`](super::linearize_steady_motion)'s
/// `state_matrix` for a model built at that value or run at that speed; its
/// error is passed on in [`CrossingError::Model`]. The bracket is sampled
/// at [`SAMPLES`] intervals and must hold exactly one change of sign
/// there; then bisection on the sign (see the module's docs for why not a
/// secant) narrows it until its ends are adjacent numbers. A growth rate
/// of exactly zero counts as stable.
///
/// The bicycle's weave speed, where the oscillating mode turns stable:
///
/// ```
/// use lagrange::models::WhippleBicycle;
/// use lagrange_runtime::analysis::{linearize_steady_motion, stability_crossing, Turns};
///
/// let bike = WhippleBicycle::benchmark();
/// let weave = stability_crossing(3.0, 5.0, |v| {
///     let (q, qdot) = bike.upright(0.0, v);
///     let states = ["phi", "delta"];
///     linearize_steady_motion(&bike, 0.0, &q, &qdot, &states, &states).map(|l| l.state_matrix)
/// })?;
/// assert_eq!(weave.turns, Turns::Stable);
/// assert!(weave.eigenvalue.im.abs() > 1.0); // an oscillation crosses
/// assert!((weave.parameter - 4.29238253634111).abs() < 1e-10);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn stability_crossing<S, E>(
    lo: S,
    hi: S,
    mut state_matrix: impl FnMut(S) -> Result<DMatrix<S>, E>,
) -> Result<Crossing<S>, CrossingError<S, E>>
where
    S: RealField + Copy,
{
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return Err(CrossingError::Bracket { lo, hi });
    }
    let mut evaluations = 0;
    let mut largest_at = |p: S| -> Result<Complex<S>, CrossingError<S, E>> {
        evaluations += 1;
        let a = state_matrix(p).map_err(|source| CrossingError::Model {
            parameter: p,
            source,
        })?;
        if a.nrows() != a.ncols() || a.is_empty() {
            return Err(CrossingError::NotSquare {
                parameter: p,
                rows: a.nrows(),
                columns: a.ncols(),
            });
        }
        if !a.iter().all(|x| x.is_finite()) {
            return Err(CrossingError::NonFinite { parameter: p });
        }
        let e = largest(&a);
        if !(e.re.is_finite() && e.im.is_finite()) {
            return Err(CrossingError::NonFinite { parameter: p });
        }
        Ok(e)
    };
    let unstable = |e: &Complex<S>| e.re > S::zero();

    // The samples: every change of sign they can see.
    let width = hi - lo;
    let at = |k: usize| {
        if k == SAMPLES {
            hi
        } else {
            lo + width * nalgebra::convert::<f64, S>(k as f64 / SAMPLES as f64)
        }
    };
    let mut previous = (lo, largest_at(lo)?);
    let first = previous.1;
    let mut changes = Vec::new();
    for k in 1..=SAMPLES {
        let p = at(k);
        let here = (p, largest_at(p)?);
        if unstable(&here.1) != unstable(&previous.1) {
            changes.push((previous, here));
        }
        previous = here;
    }
    let ((mut below, mut e_below), (mut above, mut e_above)) = match changes.as_slice() {
        [] => {
            return Err(CrossingError::NoCrossing {
                lo,
                hi,
                growth_lo: first.re,
                growth_hi: previous.1.re,
            });
        }
        [one] => *one,
        several => {
            return Err(CrossingError::Several {
                brackets: several.iter().map(|(a, b)| (a.0, b.0)).collect(),
            });
        }
    };
    let turns = if unstable(&e_below) {
        Turns::Stable
    } else {
        Turns::Unstable
    };

    // Bisection on the sign until the ends are adjacent: the midpoint
    // rounds to one of them.
    let two: S = nalgebra::convert(2.0);
    loop {
        let mid = below + (above - below) / two;
        if mid <= below || mid >= above {
            break;
        }
        let e = largest_at(mid)?;
        if unstable(&e) == unstable(&e_below) {
            (below, e_below) = (mid, e);
        } else {
            (above, e_above) = (mid, e);
        }
    }
    let (parameter, eigenvalue) = if e_below.re.abs() <= e_above.re.abs() {
        (below, e_below)
    } else {
        (above, e_above)
    };
    Ok(Crossing {
        parameter,
        bracket: (below, above),
        turns,
        eigenvalue,
        evaluations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A damped oscillator `ẍ + c(p) ẋ + x = 0` with `c(p) = p − 0.3`:
    /// its pair crosses at exactly `p = 0.3` (the nearest `f64`), turning
    /// unstable as `p` decreases, so stable as it increases.
    fn oscillator(p: f64) -> Result<DMatrix<f64>, std::convert::Infallible> {
        Ok(DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.3 - p]))
    }

    /// The crossing's bracket is two adjacent floats around the exact
    /// root: `c(p)` is computed exactly near 0.3 (Sterbenz), and the
    /// eigenvalues' real part of a 2 × 2 companion matrix is `−c/2` to a
    /// few ulps of `c`, so the computed sign changes within an ulp or two
    /// of 0.3.
    #[test]
    fn an_oscillator_turns_stable_at_its_exact_damping_zero() {
        let crossing = stability_crossing(0.0, 1.0, oscillator).expect("one crossing");
        assert_eq!(crossing.turns, Turns::Stable);
        assert!((crossing.parameter - 0.3).abs() <= 2.0 * f64::EPSILON * 0.3);
        let (a, b) = crossing.bracket;
        assert!(b - a <= f64::EPSILON * 0.3, "{a} {b}");
        assert!((crossing.eigenvalue.im - 1.0).abs() < 1e-7);
    }

    #[test]
    fn a_bracket_without_or_with_two_crossings_is_refused() {
        let none = stability_crossing(0.5, 1.0, oscillator).unwrap_err();
        assert!(
            matches!(none, CrossingError::NoCrossing { growth_lo, growth_hi, .. }
            if growth_lo < 0.0 && growth_hi < 0.0)
        );
        // c(p) = (p − 0.3)(p − 0.7): stable outside, unstable between.
        let twice = stability_crossing(0.0, 1.0, |p: f64| {
            let c = (p - 0.3) * (p - 0.7);
            Ok::<_, ()>(DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -c]))
        })
        .unwrap_err();
        let CrossingError::Several { brackets } = twice else {
            panic!("{twice:?}")
        };
        assert_eq!(brackets.len(), 2);
        assert!(brackets[0].0 <= 0.3 && 0.3 <= brackets[0].1);
        assert!(brackets[1].0 <= 0.7 && 0.7 <= brackets[1].1);
    }

    #[test]
    fn nan_brackets_matrices_and_errors_are_typed() {
        assert!(matches!(
            stability_crossing(f64::NAN, 1.0, oscillator),
            Err(CrossingError::Bracket { .. })
        ));
        assert!(matches!(
            stability_crossing(1.0, 0.0, oscillator),
            Err(CrossingError::Bracket { .. })
        ));
        let nan = stability_crossing(0.0, 1.0, |p: f64| {
            Ok::<_, ()>(DMatrix::from_element(
                2,
                2,
                if p > 0.5 { f64::NAN } else { 0.0 },
            ))
        });
        assert!(matches!(nan, Err(CrossingError::NonFinite { parameter }) if parameter > 0.5));
        let wide = stability_crossing(0.0, 1.0, |_: f64| Ok::<_, ()>(DMatrix::zeros(2, 3)));
        assert!(matches!(
            wide,
            Err(CrossingError::NotSquare {
                rows: 2,
                columns: 3,
                ..
            })
        ));
        let failed = stability_crossing(0.0, 1.0, |p: f64| {
            if p > 0.2 {
                Err("no model here")
            } else {
                oscillator(p).map_err(|e| match e {})
            }
        });
        assert!(matches!(
            failed,
            Err(CrossingError::Model {
                source: "no model here",
                ..
            })
        ));
    }
}
