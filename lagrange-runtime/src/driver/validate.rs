//! Input validation: everything about a call that can be checked before the
//! first step is checked here, and refused as [`InvalidInput`] with an
//! empty trajectory.

use nalgebra::{ComplexField, RealField, SVector};

use crate::error::{Failure, InvalidInput};
use crate::model::Lagrangian;
use crate::trajectory::Trajectory;

/// A failure before any work: empty trajectory.
pub(crate) fn invalid<S: RealField + Copy, const N: usize>(
    invalid: InvalidInput<S>,
) -> Box<Failure<S, N>> {
    Failure::boxed(invalid.into(), Trajectory::with_capacity(0))
}

/// A finite initial state, or the first coordinate (of `coordinates`,
/// the model's names) whose position or velocity is not: for a run, and
/// for each lane of an ensemble.
pub(crate) fn finite_start<S: RealField + Copy, const N: usize>(
    coordinates: [&'static str; N],
    q0: &SVector<S, N>,
    qdot0: &SVector<S, N>,
) -> Result<(), InvalidInput<S>> {
    for (i, coordinate) in coordinates.into_iter().enumerate() {
        if !q0[i].is_finite() {
            let value = q0[i];
            return Err(InvalidInput::NonFiniteInitialPosition { coordinate, value });
        }
        if !qdot0[i].is_finite() {
            let value = qdot0[i];
            return Err(InvalidInput::NonFiniteInitialVelocity { coordinate, value });
        }
    }
    Ok(())
}

/// The checks every method shares: a finite start time, finite parameters,
/// control inputs that were set, a finite initial state, and finite,
/// non-decreasing sample times none before `t0`. Unset inputs are NaN
/// fields of the model, but not parameters: `parameters_are_finite` does
/// not look at them, so they are reported in their own words.
pub(super) fn validate<L: Lagrangian<N>, const N: usize>(
    model: &L,
    t0: L::Scalar,
    q0: &SVector<L::Scalar, N>,
    qdot0: &SVector<L::Scalar, N>,
    times: &[L::Scalar],
) -> Result<(), InvalidInput<L::Scalar>> {
    if !t0.is_finite() {
        return Err(InvalidInput::NonFiniteStartTime { t0 });
    }
    crate::model::ready(model)?;
    if L::HAS_CONTACTS {
        return Err(InvalidInput::ContactsNotRun);
    }
    finite_start(L::COORDINATES, q0, qdot0)?;
    // A method without its flag would be ignored in silence: asked once,
    // at the start (a model with constraints is never asked).
    if !L::SOLVES_ACCELERATIONS
        && !crate::model::constraints::is_constrained(model)
        && model.accelerations(t0, q0, qdot0).is_some()
    {
        return Err(InvalidInput::AccelerationsNotFlagged);
    }
    for (index, &time) in times.iter().enumerate() {
        if !time.is_finite() {
            return Err(InvalidInput::NonFiniteSampleTime { index, time });
        }
        if time < t0 {
            return Err(InvalidInput::SampleBeforeStart { index, time, t0 });
        }
        if let Some(&previous) = index.checked_sub(1).and_then(|i| times.get(i)) {
            if time < previous {
                return Err(InvalidInput::UnsortedSampleTimes {
                    index,
                    previous,
                    time,
                });
            }
        }
    }
    Ok(())
}

/// A fixed step size must be positive and finite.
pub(crate) fn check_step_size<S: RealField + Copy>(h: S) -> Result<(), InvalidInput<S>> {
    if h.is_finite() && h > S::zero() {
        Ok(())
    } else {
        Err(InvalidInput::InvalidStepSize { h })
    }
}

/// The tolerances an adaptive method can honour: `rtol` at least `10 ε` of
/// the scalar type, `atol` positive, both finite.
pub(crate) fn check_tolerances<S: RealField + Copy>(
    rtol: S,
    atol: S,
) -> Result<(), InvalidInput<S>> {
    let min = nalgebra::convert::<f64, S>(10.0) * S::default_epsilon();
    if !(rtol.is_finite() && rtol >= min) {
        return Err(InvalidInput::InvalidRelativeTolerance { rtol, min });
    }
    if !(atol.is_finite() && atol > S::zero()) {
        return Err(InvalidInput::InvalidAbsoluteTolerance { atol });
    }
    Ok(())
}
