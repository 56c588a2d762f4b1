//! Robots from URDF beside Pinocchio: the UR5, the Panda (fingers locked)
//! and the xArm7 on fixed bases, the Go2 and romeo_small (31 joints) on
//! floating bases, all of `tests/data/robots/`; our generated q̈ (ABA), M
//! (CRBA) and τ (RNEA) timed against Pinocchio's C++
//! (`examples/robots/bench.cpp`, built against the PyPI wheel `pin`'s
//! headers and library with `cmeel-eigen`'s Eigen), in interleaved rounds:
//! ours, then Pinocchio's, five times; the table prints the medians. A
//! floating base is compared in Pinocchio's velocities `ν` (its free
//! flyer's `v`: the base's linear and angular velocity in its own frame,
//! then the joints): `forward_dynamics` is ν̇ by ABA,
//! `velocity_mass_matrix` M in ν by CRBA, `inverse_dynamics` τ by RNEA.
//! "M, f, solve" is `mass_matrix` (on a floating base
//! `velocity_mass_matrix`), `nonlinear_effects` and the generated
//! `solve_mass_matrix` (`solve_velocity_mass_matrix`): Featherstone's
//! sparse `Lᵀ D L` unrolled over the robot's tree, as Pinocchio's CRBA,
//! `nonLinearEffects` and `cholesky::decompose` + `cholesky::solve` (the
//! same factorization, looped over its parent table). Pinocchio's part is
//! skipped, with the reason, where its Python or a C++ compiler is
//! missing. Last, the planar 64-link chain of the project's benches: our
//! q̈ (the energy route's recursion over its links) against Pinocchio's
//! ABA on the same chain, built by the bench. `LAGRANGE_ROBOTS_ROUNDS`
//! sets the interleaved rounds (5).
//!
//! `cargo run --release -p lagrange-studies --example robots`
//! (`LAGRANGE_PEERS_PYTHON` names a Python with `pin`, `example-robot-data`
//! and `cmeel-eigen`; `LAGRANGE_PINOCCHIO_BENCH` names `bench.cpp` built
//! already against the same wheel, as this example builds it: the build
//! takes minutes).

#[path = "support/peers_python.rs"]
mod peers_python;

use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use std::hint::black_box;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

lagrangian! {
    /// The UR5 of example-robot-data.
    #[lagrange(urdf = "../tests/data/robots/ur5.urdf")]
    pub struct Ur5 {}
}

lagrangian! {
    /// The Panda of example-robot-data, its fingers locked closed.
    #[lagrange(urdf = "../tests/data/robots/panda.urdf")]
    pub struct Panda {
        locked: panda_finger_joint1 = 0.0, panda_finger_joint2 = 0.0;
    }
}

lagrangian! {
    /// The xArm7 of example-robot-data.
    #[lagrange(urdf = "../tests/data/robots/xarm7.urdf")]
    pub struct Xarm7 {}
}

lagrangian! {
    /// The Unitree Go2 of example-robot-data on a floating base.
    #[lagrange(urdf = "../tests/data/robots/go2.urdf", floating)]
    pub struct Go2 {}
}

lagrangian! {
    /// The romeo_small humanoid of example-robot-data (31 joints) on a
    /// floating base.
    #[lagrange(urdf = "../tests/data/robots/romeo_small.urdf", floating)]
    pub struct Romeo {}
}

lagrangian! {
    /// The planar chain of the project's benches at 64 links: unit point
    /// masses at the ends of unit rods, in absolute angles (the README's
    /// indexed chain), solved by the recursion over its links: Pinocchio's
    /// bench builds the same chain in relative angles (revolute joints
    /// about z, gravity along −y), the same motion.
    pub struct Chain64 {
        const N = 64;
        coordinates: theta[N];
        parameters: m[N], l[N];
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
    }
}

/// The chain's links.
const CHAIN: usize = 64;

const CALLS: u32 = 200_000;

/// q̈ of the 64-link chain (the model's `accelerations`, the recursion),
/// ns per call, the median of 7 rounds of `CALLS / 10` calls. Not inlined:
/// with its loop in `main`, the robots' closures there compiled otherwise
/// (the Go2's RNEA measured 1078 against 728 ns).
#[inline(never)]
fn ours_chain() -> f64 {
    let chain = Chain64::new([1.0; CHAIN], [1.0; CHAIN]);
    let q = SVector::<f64, CHAIN>::from_fn(|i, _| 0.3 * (i as f64 * 1.7).sin());
    let v = SVector::<f64, CHAIN>::from_fn(|i, _| (i as f64 * 2.3).cos());
    let mut rounds: Vec<f64> = (0..7)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..CALLS / 10 {
                black_box(chain.accelerations(0.0, black_box(&q), black_box(&v)));
            }
            start.elapsed().as_secs_f64() * 1e9 / f64::from(CALLS / 10)
        })
        .collect();
    rounds.sort_by(f64::total_cmp);
    rounds[3]
}

/// ns per call of `f`, the median of 7 rounds of `CALLS` calls.
fn time_ns(mut f: impl FnMut()) -> f64 {
    let mut rounds: Vec<f64> = (0..7)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..CALLS {
                f();
            }
            start.elapsed().as_secs_f64() * 1e9 / f64::from(CALLS)
        })
        .collect();
    rounds.sort_by(f64::total_cmp);
    rounds[3]
}

/// Our figures: q̈ (ABA), M (CRBA), M and f then the generated sparse
/// solve, τ (RNEA).
macro_rules! ours {
    ($robot:expr, $n:literal) => {{
        let robot = $robot;
        let q = SVector::<f64, $n>::from_fn(|i, _| 0.3 * (i as f64 * 1.7).sin());
        let v = SVector::<f64, $n>::from_fn(|i, _| (i as f64 * 2.3).cos());
        let a = SVector::<f64, $n>::from_fn(|i, _| 0.5 - 0.1 * i as f64);
        let tau = SVector::<f64, $n>::zeros();
        [
            time_ns(|| {
                black_box(robot.forward_dynamics(black_box(&q), black_box(&v), black_box(&tau)));
            }),
            time_ns(|| {
                black_box(robot.mass_matrix(0.0, black_box(&q)));
            }),
            time_ns(|| {
                let m = robot.mass_matrix(0.0, black_box(&q));
                let f = -robot.nonlinear_effects(black_box(&q), black_box(&v));
                black_box(robot.solve_mass_matrix(&m, &f));
            }),
            time_ns(|| {
                black_box(robot.inverse_dynamics(black_box(&q), black_box(&v), black_box(&a)));
            }),
        ]
    }};
}

/// Our figures on a floating base, in the velocities `ν`: ν̇ (ABA), M in ν
/// (CRBA), M and the nonlinear effects then the generated sparse solve, τ
/// (RNEA).
macro_rules! ours_floating {
    ($robot:expr, $nq:literal, $nv:literal) => {{
        let robot = $robot;
        let mut q = SVector::<f64, $nq>::from_fn(|i, _| 0.3 * (i as f64 * 1.7).sin());
        let norm = q.fixed_rows::<4>(3).norm();
        for k in 3..7 {
            q[k] /= norm;
        }
        let v = SVector::<f64, $nv>::from_fn(|i, _| (i as f64 * 2.3).cos());
        let a = SVector::<f64, $nv>::from_fn(|i, _| 0.5 - 0.1 * i as f64);
        let tau = SVector::<f64, $nv>::zeros();
        [
            time_ns(|| {
                black_box(robot.forward_dynamics(black_box(&q), black_box(&v), black_box(&tau)));
            }),
            time_ns(|| {
                black_box(robot.velocity_mass_matrix(black_box(&q)));
            }),
            time_ns(|| {
                let m = robot.velocity_mass_matrix(black_box(&q));
                let f = -robot.nonlinear_effects(black_box(&q), black_box(&v));
                black_box(robot.solve_velocity_mass_matrix(&m, &f));
            }),
            time_ns(|| {
                black_box(robot.inverse_dynamics(black_box(&q), black_box(&v), black_box(&a)));
            }),
        ]
    }};
}

/// The robots, in the table's order: name, file, its arguments to
/// `dump_model.py` (locked joints, `--floating`).
const ROBOTS: [(&str, &str, &[&str]); 5] = [
    ("ur5", "ur5.urdf", &[]),
    (
        "panda",
        "panda.urdf",
        &["panda_finger_joint1", "panda_finger_joint2"],
    ),
    ("xarm7", "xarm7.urdf", &[]),
    ("go2", "go2.urdf", &["--floating"]),
    ("romeo", "romeo_small.urdf", &["--floating"]),
];

/// Pinocchio's bench built against the wheel, its dumps of our URDFs.
fn pinocchio(dir: &Path) -> Result<(std::path::PathBuf, Vec<String>), String> {
    let python = peers_python::importing("pinocchio")?;
    let out = Command::new(&python)
        .args([
            "-c",
            "import sysconfig; print(sysconfig.get_paths()['purelib'])",
        ])
        .output()
        .map_err(|e| e.to_string())?;
    let prefix = format!(
        "{}/cmeel.prefix",
        String::from_utf8_lossy(&out.stdout).trim()
    );
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let robots = here.join("../tests/data/robots");
    let mut args = Vec::new();
    for (name, file, locked) in ROBOTS {
        let dump = dir.join(format!("{name}.txt"));
        let ok = Command::new(&python)
            .arg(here.join("examples/robots/dump_model.py"))
            .arg(robots.join(file))
            .arg(&dump)
            .args(locked)
            .output()
            .is_ok_and(|o| o.status.success());
        if !ok {
            return Err(format!("dump_model.py failed on {file}"));
        }
        args.push(name.to_string());
        args.push(dump.display().to_string());
    }
    // The planar chain, built by the bench itself.
    args.push("chain64".to_string());
    args.push(CHAIN.to_string());
    if let Ok(bin) = std::env::var("LAGRANGE_PINOCCHIO_BENCH") {
        return Ok((bin.into(), args));
    }
    let bin = dir.join("bench");
    let built = Command::new("g++")
        .args(["-O3", "-march=native", "-DNDEBUG", "-std=c++17"])
        .args([
            "-DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS",
            "-DBOOST_MPL_LIMIT_LIST_SIZE=30",
            "-DBOOST_MPL_LIMIT_VECTOR_SIZE=30",
            "-DBOOST_FUSION_INVOKE_MAX_ARITY=12",
            "-DBOOST_FUSION_INVOKE_PROCEDURE_MAX_ARITY=12",
            "-DBOOST_FUSION_INVOKE_FUNCTION_OBJECT_MAX_ARITY=12",
        ])
        .arg(format!("-I{prefix}/include"))
        .arg(format!("-I{prefix}/include/eigen3"))
        .arg(here.join("examples/robots/bench.cpp"))
        .arg("-o")
        .arg(&bin)
        .arg(format!("-L{prefix}/lib"))
        .arg("-lpinocchio_default")
        .arg(format!("-Wl,-rpath,{prefix}/lib"))
        .arg("-w")
        .output()
        .map_err(|e| format!("g++: {e}"))?;
    if !built.status.success() {
        return Err(format!(
            "bench.cpp did not build: {}",
            String::from_utf8_lossy(&built.stderr)
                .lines()
                .next()
                .unwrap_or("")
        ));
    }
    Ok((bin, args))
}

/// Pinocchio's figures per robot: ABA, CRBA, CRBA + solve, RNEA.
fn run_pinocchio(bin: &Path, args: &[String]) -> Vec<(String, [f64; 4])> {
    let out = Command::new(bin)
        .args(args)
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
        .unwrap_or_default();
    out.lines()
        .filter_map(|line| {
            // `NAME nv N aba_ns X crba_ns Y crba_solve_ns Z rnea_ns W`:
            // each figure read after its key.
            let w: Vec<&str> = line.split_whitespace().collect();
            let num = |key: &str| {
                let at = w.iter().position(|x| *x == key)?;
                w.get(at + 1)?.parse::<f64>().ok()
            };
            let name = w.first()?.to_string();
            // A bench built before the chain was added reads `64` as a
            // dump: its line would not be the chain's.
            if name.starts_with("chain") && num("nv")? != CHAIN as f64 {
                return None;
            }
            Some((
                name,
                [
                    num("aba_ns")?,
                    num("crba_ns")?,
                    num("crba_solve_ns")?,
                    num("rnea_ns")?,
                ],
            ))
        })
        .collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let dir = std::env::temp_dir().join(format!("lagrange-robots-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    let peer = pinocchio(&dir);
    if let Err(why) = &peer {
        println!("Pinocchio skipped: {why}");
    }
    let mut ours_runs: Vec<[[f64; 4]; 5]> = Vec::new();
    let mut chain_runs: Vec<f64> = Vec::new();
    let mut theirs_runs: Vec<Vec<(String, [f64; 4])>> = Vec::new();
    let rounds: usize = std::env::var("LAGRANGE_ROBOTS_ROUNDS")
        .ok()
        .and_then(|r| r.parse().ok())
        .filter(|&r| r > 0)
        .unwrap_or(5);
    for _ in 0..rounds {
        ours_runs.push([
            ours!(Ur5::new(), 6),
            ours!(Panda::new(), 7),
            ours!(Xarm7::new(), 7),
            ours_floating!(Go2::new(), 19, 18),
            ours_floating!(Romeo::new(), 38, 37),
        ]);
        chain_runs.push(ours_chain());
        if let Ok((bin, args)) = &peer {
            theirs_runs.push(run_pinocchio(bin, args));
        }
    }
    let what = ["q̈ (ABA)", "M (CRBA)", "M, f, solve", "τ (RNEA)"];
    println!(
        "\nns per call, medians of {rounds} interleaved rounds (each the median of 7 × {CALLS} calls)\n"
    );
    println!("| robot | quantity | ours | Pinocchio | ours / Pinocchio |");
    println!("|---|---|---:|---:|---:|");
    for (r, (robot, _, _)) in ROBOTS.iter().enumerate() {
        for (k, w) in what.iter().enumerate() {
            let ours = median(ours_runs.iter().map(|x| x[r][k]).collect());
            let theirs: Vec<f64> = theirs_runs
                .iter()
                .filter_map(|run| run.iter().find(|(n, _)| n == robot).map(|(_, x)| x[k]))
                .collect();
            if theirs.is_empty() {
                println!("| {robot} | {w} | {ours:.1} | – | – |");
            } else {
                let theirs = median(theirs);
                println!(
                    "| {robot} | {w} | {ours:.1} | {theirs:.1} | {:.2} |",
                    ours / theirs
                );
            }
        }
    }
    // The chain: q̈ alone (no M is formed: the recursion solves it).
    let ours = median(chain_runs);
    let theirs: Vec<f64> = theirs_runs
        .iter()
        .filter_map(|run| run.iter().find(|(n, _)| n == "chain64").map(|(_, x)| x[0]))
        .collect();
    if theirs.is_empty() {
        println!("| chain64 | q̈ (recursion; ABA) | {ours:.1} | – | – |");
    } else {
        let theirs = median(theirs);
        println!(
            "| chain64 | q̈ (recursion; ABA) | {ours:.1} | {theirs:.1} | {:.2} |",
            ours / theirs
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
