//! The 25-digit reference trajectories of `tests/data/` (each computed by
//! two independent high-precision methods; copied from the project's shared
//! references), read in one place for the tests and the work–precision
//! study.

use lagrange::models::{DoublePendulum, TwoMassChain};
use lagrange::nalgebra::{self, RealField, Vector2};
use serde_json::Value;

/// One reference sample.
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    pub t: f64,
    pub q: Vector2<f64>,
    pub qdot: Vector2<f64>,
    pub energy: f64,
    /// `float64_check.perturbation_growth`: `max |δy(t)| / |δy(0)|` for a
    /// 1e-20 kick of every initial coordinate, how much the flow amplifies
    /// an error made at the start. 1 where the file gives none: the damped
    /// chain's flow contracts (linear, damped), so its growth is ≤ 1.
    pub growth: f64,
}

/// A reference: the exact parameters, the start and the samples.
pub struct Reference {
    parameters: Value,
    pub q0: Vector2<f64>,
    pub qdot0: Vector2<f64>,
    pub energy0: f64,
    pub samples: Vec<Sample>,
}

/// A number written as a JSON number or, to keep all 25 digits, a string.
fn number(v: &Value) -> f64 {
    match v {
        Value::String(s) => s.parse().unwrap(),
        v => v.as_f64().unwrap(),
    }
}

fn vector(v: &Value) -> Vector2<f64> {
    Vector2::new(number(&v[0]), number(&v[1]))
}

impl Reference {
    /// `tests/data/{name}.json`, from the facade's tests (built in the
    /// repository's root) or the studies (`lagrange-studies/`, one below).
    pub fn read(name: &str) -> Self {
        let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let root = if here.join("tests/data").is_dir() {
            here
        } else {
            here.parent().expect("the repository's root")
        };
        let path = root.join(format!("tests/data/{name}.json"));
        let json: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let growth = &json["float64_check"]["perturbation_growth"];
        let samples = json["samples"]
            .as_array()
            .unwrap()
            .iter()
            .enumerate()
            .map(|(k, s)| Sample {
                t: number(&s["t"]),
                q: vector(&s["q"]),
                qdot: vector(&s["dq"]),
                energy: number(&s["energy"]),
                growth: growth.get(k).map(number).unwrap_or(1.0),
            })
            .collect();
        Reference {
            parameters: json["parameters_exact"].clone(),
            q0: vector(&json["q0"]),
            qdot0: vector(&json["dq0"]),
            energy0: number(&json["energy0"]),
            samples,
        }
    }

    /// The chaotic double pendulum: `tests/data/double_pendulum.json`.
    pub fn double_pendulum() -> Self {
        Self::read("double_pendulum")
    }

    /// The damped two-mass chain: `tests/data/damped_two_mass_spring.json`.
    pub fn damped_chain() -> Self {
        Self::read("damped_two_mass_spring")
    }

    /// The exact value of parameter `name`, rounded to `S`.
    pub fn parameter<S: RealField + Copy>(&self, name: &str) -> S {
        nalgebra::convert(number(&self.parameters[name]))
    }

    /// The sample times.
    pub fn times(&self) -> Vec<f64> {
        self.samples.iter().map(|s| s.t).collect()
    }

    /// The double pendulum with the reference's parameters.
    pub fn double_pendulum_model<S: RealField + Copy>(&self) -> DoublePendulum<S> {
        let p = |name| self.parameter(name);
        DoublePendulum::new(p("m1"), p("m2"), p("l1"), p("l2"), p("g"))
    }

    /// The two-mass chain with the reference's parameters.
    pub fn two_mass_chain_model<S: RealField + Copy>(&self) -> TwoMassChain<S> {
        let p = |name| self.parameter(name);
        TwoMassChain::new(
            p("m1"),
            p("m2"),
            p("k1"),
            p("k2"),
            p("k3"),
            p("c1"),
            p("c2"),
            p("c3"),
        )
    }
}
