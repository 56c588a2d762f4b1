//! `-- --csv FILE`: an example's run written as CSV
//! (`lagrange::export::write_csv`, feature `csv`). Shared by the examples
//! that print tables.

use lagrange::prelude::*;
use std::error::Error;

/// The file after `--csv` on the command line, if any.
pub fn path() -> Option<String> {
    std::env::args().skip_while(|a| a != "--csv").nth(1)
}

/// Writes `run` of `model` to the file given after `--csv`, if one was.
#[cfg(feature = "csv")]
pub fn write<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    model: &L,
    run: &Trajectory<f64, N>,
) -> Result<(), Box<dyn Error>> {
    if let Some(path) = path() {
        lagrange::export::write_csv(model, run, std::fs::File::create(&path)?)?;
        println!("Wrote {path}\n");
    }
    Ok(())
}

/// Without the `csv` feature, `--csv` is refused with how to get it.
#[cfg(not(feature = "csv"))]
pub fn write<L: Lagrangian<N, Scalar = f64>, const N: usize>(
    _: &L,
    _: &Trajectory<f64, N>,
) -> Result<(), Box<dyn Error>> {
    match path() {
        Some(_) => Err("--csv needs the csv feature: \
                        cargo run --release -p lagrange-studies --features csv --example NAME -- --csv FILE"
            .into()),
        None => Ok(()),
    }
}
