//! lagrange against the strongest alternative a user has: SymPy derives the
//! N-link chain's `M` and `f` (`LagrangesMethod` and plain Euler–Lagrange),
//! `sympy.cse` shares, gcc compiles the C (`-O3 -march=native`, with and
//! without `-ffast-math`); beside it the generated `mass_matrix_and_forcing`,
//! built with cargo's release defaults and for the native CPU, timed the same
//! way, and both texts' operations counted by one counter.
//!
//! The work is `lagrange-studies/benches/peers/chain_codegen_c.py` (its docstring says what it
//! measures and how); this bench finds what it needs and runs it. It needs a
//! Python with sympy (`LAGRANGE_PEERS_PYTHON`, else `python3`) and gcc, and
//! says so and skips when either is missing:
//!
//! ```sh
//! python3 -m venv ../peers-venv && ../peers-venv/bin/pip install sympy numpy
//! LAGRANGE_PEERS_PYTHON=../peers-venv/bin/python cargo bench -p lagrange-studies --bench peers
//! LAGRANGE_PEERS_PYTHON=... cargo bench -p lagrange-studies --bench peers -- --ns 2,5,10   # quicker
//! ```
//!
//! Results in `target/peers/chain_codegen_c.txt` (and `.json`); about 11
//! minutes for N up to 20 on 2 cores, SymPy's derivations most of it.
//! Arguments after `--` go to the script (`--help` lists them). Under
//! `cargo test` (no `--bench` argument) it only says what it would do.

#[path = "../examples/support/peers_python.rs"]
mod peers_python;

use std::path::Path;
use std::process::{Command, ExitCode};

fn main() -> ExitCode {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let benching = args.iter().any(|a| a == "--bench");
    args.retain(|a| a != "--bench");
    let studies = Path::new(env!("CARGO_MANIFEST_DIR"));
    let script = studies.join("benches/peers/chain_codegen_c.py");
    // The repository's root, one above this crate: the script builds the
    // `lagrange` there into scratch crates.
    let root = studies
        .parent()
        .expect("lagrange-studies sits in the repository");
    if !benching {
        println!(
            "peers: run with `cargo bench -p lagrange-studies --bench peers` ({})",
            script.display()
        );
        return ExitCode::SUCCESS;
    }
    let python = match peers_python::importing("sympy") {
        Ok(python) => python,
        Err(why) => {
            println!("peers: skipped: {why}");
            return ExitCode::SUCCESS;
        }
    };
    let has_gcc = Command::new("gcc")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !has_gcc {
        println!("peers: skipped: no gcc on the PATH");
        return ExitCode::SUCCESS;
    }
    let mut command = Command::new(&python);
    command.arg(&script).arg("--lagrange").arg(root);
    let defaults = [
        ("--ns", Some("2,5,10,20")),
        ("--native-rust", None),
        ("--lms-max", Some("5")),
    ];
    for (flag, value) in defaults {
        if !args.iter().any(|a| a == flag) {
            command.arg(flag);
            command.args(value);
        }
    }
    command.args(&args);
    println!("peers: {command:?}");
    match command.status() {
        Ok(s) if s.success() => ExitCode::SUCCESS,
        Ok(s) => {
            eprintln!("peers: the script failed ({s})");
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("peers: could not run `{python}`: {e}");
            ExitCode::FAILURE
        }
    }
}
