//! The bounded fuzz run of CI: a fixed seed, a few thousand inputs, two
//! worker processes, the default limits (10 s and 1 GiB per input, 8 MiB of
//! stack). Every input must expand or give a compile error; the input mix
//! must stay healthy, or the run would prove nothing.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::Command;

#[test]
fn every_input_expands_or_is_a_compile_error() {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz-findings");
    let _ = std::fs::remove_dir_all(&out);
    let run = Command::new(env!("CARGO_BIN_EXE_lagrange-fuzz"))
        .args(["--inputs", "3000", "--seed", "1", "--jobs", "2"])
        .args(["--determinism", "50", "--out"])
        .arg(&out)
        .output()
        .expect("the fuzz binary runs");
    let summary = String::from_utf8_lossy(&run.stdout);
    let result = summary
        .lines()
        .find_map(|l| l.strip_prefix("result "))
        .unwrap_or_else(|| {
            panic!(
                "no result line:\n{summary}\n{}",
                String::from_utf8_lossy(&run.stderr)
            )
        });
    let counts: BTreeMap<&str, usize> = result
        .split_whitespace()
        .filter_map(|kv| kv.split_once('='))
        .map(|(k, v)| (k, v.parse().unwrap()))
        .collect();
    let n = |k: &str| counts[k];

    for failure in [
        "panic",
        "abort",
        "over_time",
        "over_memory",
        "malformed",
        "nondeterministic",
    ] {
        assert_eq!(
            n(failure),
            0,
            "{failure}: see {} and the summary:\n{summary}",
            out.display()
        );
    }
    assert!(run.status.success(), "{summary}");

    // Healthy proportions. Seed 1 gives about 44% expansions and 55%
    // compile errors; a generator that only breaks models, or a mutator
    // that no longer breaks them, falls below a quarter on one side.
    let total: usize = counts.values().sum();
    assert_eq!(total, 3000, "{summary}");
    assert!(n("expansion") * 4 > total, "too few expansions:\n{summary}");
    assert!(
        n("compile_error") * 4 > total,
        "too few compile errors:\n{summary}"
    );
    assert_eq!(n("unlexable"), 0, "the mutator broke tokens:\n{summary}");
    // And varied: seed 1 reaches about 95 distinct error messages (names
    // and numbers blanked); fewer than 40 means the mix lost whole paths.
    let distinct: usize = summary
        .lines()
        .find_map(|l| l.trim().strip_prefix("compile errors: "))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .expect("the summary counts distinct compile errors");
    assert!(distinct >= 40, "{distinct} distinct errors:\n{summary}");
}
