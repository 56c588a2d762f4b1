//! A trajectory written as CSV through the `csv` crate.

use crate::dynamics::saddle::Multipliers as _;
use crate::model::settings::ConstraintSettings;
use std::io;

use nalgebra::{RealField, SVector};

use crate::error::IntegrationError;
use crate::model::Lagrangian;
use crate::model::constraints::{Holonomic, Visitor};
use crate::trajectory::Trajectory;

/// Why a trajectory could not be written (feature `csv`).
#[derive(Debug, thiserror::Error)]
pub enum CsvError<S: RealField + Copy, const N: usize> {
    /// The writer failed (I/O) or the CSV encoder did.
    #[error("writing the CSV failed: {0}")]
    Write(#[from] ::csv::Error),
    /// A constrained model's multipliers could not be computed at a sample
    /// (a dead centre, say): the saddle-point solve's error, with that
    /// sample's time and state.
    #[error("the multipliers at a sample could not be computed: {0}")]
    Multipliers(IntegrationError<S, N>),
}

/// Writes `trajectory` as CSV to `writer` (feature `csv`): a header from the model's names,
/// then one row per sample (see [the module](super)), and for a run with
/// [events](crate::events) one row per event among them, named in a last
/// `event` column. Numbers are written
/// in Rust's shortest round-trip form, so reading them back gives the same
/// `f64` values.
///
/// ```
/// # #[cfg(feature = "csv")] {
/// use lagrange_runtime::export::write_csv;
/// use lagrange_runtime::prelude::*;
/// use lagrange_runtime::nalgebra::{SMatrix, SVector, Vector1};
///
/// struct Spring;
/// impl Lagrangian<1> for Spring {
///     type Scalar = f64;
///     const COORDINATES: [&'static str; 1] = ["x"];
///     fn mass_matrix(&self, _t: f64, _q: &SVector<f64, 1>) -> SMatrix<f64, 1, 1> {
///         SMatrix::<f64, 1, 1>::new(1.0)
///     }
///     fn forcing(&self, _t: f64, q: &SVector<f64, 1>, _qd: &SVector<f64, 1>) -> SVector<f64, 1> {
///         -q
///     }
///     fn kinetic_energy(&self, _t: f64, _q: &SVector<f64, 1>, qd: &SVector<f64, 1>) -> f64 {
///         0.5 * qd[0] * qd[0]
///     }
///     fn potential_energy(&self, _t: f64, q: &SVector<f64, 1>) -> f64 {
///         0.5 * q[0] * q[0]
///     }
/// }
///
/// let run = Rk4::new(0.5).integrate(&Spring, 0.0, Vector1::new(1.0), Vector1::new(0.0), &[0.0, 1.0])?;
/// let mut out = Vec::new();
/// write_csv(&Spring, &run, &mut out)?;
/// let text = String::from_utf8(out)?;
/// assert_eq!(text.lines().next(), Some("t,x,x_dot,energy"));
/// assert_eq!(text.lines().nth(1), Some("0,1,0,0.5"));
/// # }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_csv<L, W, const N: usize>(
    model: &L,
    trajectory: &Trajectory<L::Scalar, N>,
    writer: W,
) -> Result<(), CsvError<L::Scalar, N>>
where
    L: Lagrangian<N>,
    W: io::Write,
{
    let multipliers = model
        .visit_constraints(Multipliers { trajectory })
        .transpose()
        .map_err(CsvError::Multipliers)?;
    let mut out = ::csv::Writer::from_writer(writer);
    let mut header: Vec<String> = vec!["t".into()];
    header.extend(L::COORDINATES.iter().map(|q| q.to_string()));
    header.extend(L::COORDINATES.iter().map(|q| format!("{q}_dot")));
    header.push("energy".into());
    if let Some((names, _)) = &multipliers {
        header.extend(names.iter().map(|c| format!("lambda_{c}")));
    }
    // A run with events: their rows among the samples', in time order (an
    // event before a sample at the same time), named in an `event` column
    // that samples leave empty; a reset's row is the state before it.
    let events = trajectory.events();
    if !events.is_empty() {
        header.push("event".into());
    }
    out.write_record(&header)?;
    let mut row: Vec<String> = Vec::with_capacity(header.len());
    type Vector<L, const N: usize> = SVector<S<L, N>, N>;
    let mut write = |t: S<L, N>,
                     q: Vector<L, N>,
                     qdot: Vector<L, N>,
                     lambda: Option<&Vec<S<L, N>>>,
                     event: Option<&str>| {
        row.clear();
        row.push(t.to_string());
        row.extend(q.iter().map(ToString::to_string));
        row.extend(qdot.iter().map(ToString::to_string));
        row.push(model.energy(t, &q, &qdot).to_string());
        if multipliers.is_some() {
            match lambda {
                Some(lambda) => row.extend(lambda.iter().map(ToString::to_string)),
                None => {
                    let lambda = model
                        .visit_constraints(AtState { t, q, qdot })
                        .transpose()
                        .map_err(CsvError::Multipliers)?
                        .unwrap_or_default();
                    row.extend(lambda.iter().map(ToString::to_string));
                }
            }
        }
        if !events.is_empty() {
            row.push(event.unwrap_or("").to_string());
        }
        out.write_record(&row).map_err(CsvError::Write)
    };
    let mut next_event = 0;
    for (k, s) in trajectory.iter().enumerate() {
        while let Some(e) = events.get(next_event).filter(|e| e.t <= s.t) {
            write(e.t, e.q, e.qdot, None, Some(e.name))?;
            next_event += 1;
        }
        let lambda = multipliers.as_ref().map(|(_, values)| &values[k]);
        write(s.t, s.q, s.qdot, lambda, None)?;
    }
    for e in &events[next_event..] {
        write(e.t, e.q, e.qdot, None, Some(e.name))?;
    }
    out.flush().map_err(::csv::Error::from)?;
    Ok(())
}

/// The scalar of model `L`.
type S<L, const N: usize> = <L as Lagrangian<N>>::Scalar;

/// A constrained model's multipliers at one state (an event's row).
struct AtState<T, const N: usize> {
    t: T,
    q: SVector<T, N>,
    qdot: SVector<T, N>,
}

impl<T: RealField + Copy, const N: usize> Visitor<T, N> for AtState<T, N> {
    type Output = Result<Vec<T>, IntegrationError<T, N>>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<T>) -> Self::Output
    where
        H: Holonomic<N, C, Scalar = T> + ?Sized,
    {
        let lambda = model.multipliers(self.t, &self.q, &self.qdot)?;
        Ok(lambda.iter().copied().collect())
    }
}

/// The constraints' names and each sample's multipliers, for a model with
/// constraints.
struct Multipliers<'t, S: RealField + Copy, const N: usize> {
    trajectory: &'t Trajectory<S, N>,
}

type Named<S, const N: usize> = Result<(Vec<&'static str>, Vec<Vec<S>>), IntegrationError<S, N>>;

impl<S: RealField + Copy, const N: usize> Visitor<S, N> for Multipliers<'_, S, N> {
    type Output = Named<S, N>;

    fn visit<H, const C: usize>(self, model: &H, _: ConstraintSettings<S>) -> Named<S, N>
    where
        H: Holonomic<N, C, Scalar = S> + ?Sized,
    {
        let values = self
            .trajectory
            .iter()
            .map(|s| {
                let lambda: SVector<S, C> = model.multipliers(s.t, &s.q, &s.qdot)?;
                Ok(lambda.iter().copied().collect())
            })
            .collect::<Result<Vec<Vec<S>>, IntegrationError<S, N>>>()?;
        Ok((H::CONSTRAINTS.to_vec(), values))
    }
}
