//! The Python the comparisons with other tools run (SymPy, SciPy, MuJoCo):
//! `LAGRANGE_PEERS_PYTHON`, else `python3`.

use std::process::Command;

/// The peers' Python if it can import `modules` (as Python's `import`
/// lists them, `"numpy, scipy"`), else the reason to skip the comparison.
pub fn importing(modules: &str) -> Result<String, String> {
    let python = std::env::var("LAGRANGE_PEERS_PYTHON").unwrap_or_else(|_| "python3".into());
    let ready = Command::new(&python)
        .args(["-c", &format!("import {modules}")])
        .output()
        .is_ok_and(|o| o.status.success());
    if ready {
        Ok(python)
    } else {
        Err(format!(
            "`{python}` cannot import {modules} (set LAGRANGE_PEERS_PYTHON to a Python that can)"
        ))
    }
}
