//! Grammar-based models: small, mostly valid programs in the DSL, with every
//! section the language has (`const`, indexed coordinates and parameters,
//! constants, scalar and indexed `let`s, sums, `dot`, repeated sections,
//! dissipation, forces on coordinates and along positions, constraints,
//! control inputs driving a coordinate, the `jacobians`,
//! `parameter_derivatives`, `regressor(..)` and `budget` options, doc comments, visibility). Names are declared before they are
//! drawn and indices stay in range, so that most models expand and the
//! mutator has valid programs to break.

use crate::rng::Rng;

mod sections;

/// A declared name: scalar, or indexed with its length (as written, and its
/// value).
#[derive(Clone)]
struct Name {
    name: String,
    len: Option<(String, i64)>,
}

/// What an expression may refer to.
#[derive(Default)]
struct Scope {
    coordinates: Vec<Name>,
    parameters: Vec<Name>,
    consts: Vec<(String, i64)>,
    constants: Vec<String>,
    lets: Vec<Name>,
    /// Index variables bound by enclosing sums or an indexed `let`: `lo..hi`.
    vars: Vec<(String, i64, i64)>,
}

const FUNCTIONS: [&str; 12] = [
    "sin", "cos", "tan", "atan", "sinh", "cosh", "tanh", "exp", "sqrt", "ln", "asin", "acos",
];

/// A random model, as source text (`pub struct Name { .. }`).
pub fn model(rng: &mut Rng) -> String {
    let mut g = Gen {
        rng,
        scope: Scope::default(),
    };
    g.model()
}

struct Gen<'a> {
    rng: &'a mut Rng,
    scope: Scope,
}

impl Gen<'_> {
    fn model(&mut self) -> String {
        let mut head = String::new();
        if self.rng.chance(0.3) {
            head.push_str("/// A generated model.\n");
        }
        let mut options = Vec::new();
        if self.rng.chance(0.15) {
            options.push("jacobians".to_string());
        }
        if self.rng.chance(0.1) {
            options.push("parameter_derivatives".to_string());
        }
        if self.rng.chance(0.03) {
            let steps = [
                "1",
                "1000",
                "100000",
                "50000000",
                "0",
                "18446744073709551615",
            ];
            options.push(format!("budget = {}", self.rng.pick(&steps)));
        }
        // The options' attribute is written once the parameters are known
        // (`regressor(..)` lists some of them).
        let options_at = head.len();
        let vis = *self.rng.pick(&["pub ", "pub ", "", "pub(crate) "]);
        head.push_str(vis);
        let name = *self
            .rng
            .pick(&["Model", "M", "Pendulum", "Chain", "Oscillator"]);

        let mut early = Vec::new(); // declarations: consts, coordinates, parameters, constants
        for k in 0..self.rng.weighted(&[6, 3, 1]) {
            let (cname, v) = (["N", "K", "P"][k].to_string(), self.small_len());
            early.push(format!("const {cname} = {};", self.int_text(v)));
            self.scope.consts.push((cname, v));
        }
        let coordinates = self.declare(&["x", "y", "theta", "q", "phi"], 1, 3);
        early.push(format!("coordinates: {};", list(&coordinates)));
        self.scope.coordinates = coordinates;
        let n_params = self.rng.weighted(&[2, 3, 3, 2, 1]);
        if n_params > 0 {
            let parameters = self.declare(&["m", "k", "l", "c", "a", "b"], n_params, n_params);
            let declared: Vec<String> = list(&parameters)
                .split(", ")
                .map(|p| format!("{p}{}", self.domain()))
                .collect();
            early.push(format!("parameters: {};", declared.join(", ")));
            if self.rng.chance(0.08) {
                // Some of the parameters' names, now and then one that is not.
                let mut listed: Vec<String> = parameters
                    .iter()
                    .map(|p| p.name.clone())
                    .filter(|_| self.rng.chance(0.6))
                    .collect();
                if listed.is_empty() || self.rng.chance(0.1) {
                    listed.push((*self.rng.pick(&["m", "zeta", "l"])).to_string());
                }
                options.push(format!("regressor({})", listed.join(", ")));
            }
            self.scope.parameters = parameters;
        }
        if !options.is_empty() {
            head.insert_str(
                options_at,
                &format!("#[lagrange({})]\n", options.join(", ")),
            );
        }
        if self.rng.chance(0.3) {
            let mut entries = Vec::new();
            for cname in ["g", "h"].iter().take(self.rng.range(1, 2)) {
                let value = match self.rng.below(4) {
                    0 => "9.81".to_string(),
                    1 => format!("{} / 2", self.number()),
                    2 if !self.scope.consts.is_empty() => {
                        format!("2*{}", self.scope.consts[0].0)
                    }
                    _ => self.number(),
                };
                entries.push(format!("{cname} = {value}"));
                self.scope.constants.push(cname.to_string());
            }
            early.push(format!("constants: {};", entries.join(", ")));
        }

        let mut lets = Vec::new();
        for lname in ["p1", "p2", "p3"]
            .iter()
            .take(self.rng.weighted(&[4, 3, 2, 1]))
        {
            lets.push(self.let_item(lname));
        }

        let mut energy = Vec::new();
        energy.extend(self.kinetic());
        let potential = if self.rng.chance(0.15) {
            "0".to_string()
        } else {
            let d = self.depth();
            self.expr(d, false)
        };
        energy.push(format!("potential: {potential};"));
        if self.rng.chance(0.1) {
            energy.push(format!("potential: {};", self.expr(1, false)));
        }
        if self.rng.chance(0.2) {
            energy.push(format!("dissipation: {};", self.quadratic_in_velocities()));
        }
        if self.rng.chance(0.25) {
            energy.push(self.forces());
        }
        if self.rng.chance(0.2) {
            energy.push(self.constraints());
        }
        if self.rng.chance(0.15) {
            energy.push(self.inputs());
        }
        if self.rng.chance(0.1) {
            energy.push(self.contacts());
        }

        // Sections may come in any order, `let`s in theirs.
        let mut items = early;
        items.extend(lets);
        items.extend(energy);
        if self.rng.chance(0.2) {
            let lets_start = items.iter().position(|s| s.starts_with("let"));
            let a = self.rng.below(items.len());
            let b = self.rng.below(items.len());
            let both_lets = lets_start
                .is_some_and(|_| items[a].starts_with("let") && items[b].starts_with("let"));
            if !both_lets {
                items.swap(a, b);
            }
        }
        format!("{head}struct {name} {{\n    {}\n}}", items.join("\n    "))
    }

    fn depth(&mut self) -> u32 {
        self.rng.weighted(&[2, 5, 4, 2]) as u32
    }

    /// A small length: mostly 1 to 4, rarely up to 12.
    fn small_len(&mut self) -> i64 {
        if self.rng.chance(0.9) {
            self.rng.range(1, 4) as i64
        } else {
            self.rng.range(5, 12) as i64
        }
    }

    fn int_text(&mut self, v: i64) -> String {
        match self.rng.below(8) {
            0 if v > 1 => format!("{} + 1", v - 1),
            1 => format!("2*{v}/2"),
            _ => v.to_string(),
        }
    }

    /// `count` distinct names from `pool` (suffixed when it runs out), some
    /// indexed by a `const` or a literal length.
    /// A parameter's domain after its name, mostly none; now and then a
    /// malformed one (a missing bound, an empty interval, a name for a
    /// bound), which must be one spanned error.
    fn domain(&mut self) -> &'static str {
        if !self.rng.chance(0.3) {
            return "";
        }
        const MALFORMED: [&str; 5] = [" > ", " in [1, 0]", " > m", " in [2, 2]", " in 0"];
        const WELL_FORMED: [&str; 7] = [
            " > 0",
            " >= 0",
            " < 1",
            " <= 2.5",
            " in [0, 1]",
            " in (-1, 1)",
            " > -1e-3",
        ];
        if self.rng.chance(0.1) {
            return self.rng.pick::<&str>(&MALFORMED);
        }
        self.rng.pick::<&str>(&WELL_FORMED)
    }

    fn declare(&mut self, pool: &[&str], min: usize, max: usize) -> Vec<Name> {
        let n = self.rng.range(min, max);
        let start = self.rng.below(pool.len());
        (0..n)
            .map(|k| {
                let base = pool[(start + k) % pool.len()];
                let name = if k < pool.len() {
                    base.to_string()
                } else {
                    format!("{base}{k}")
                };
                let len = if self.rng.chance(0.2) {
                    Some(if !self.scope.consts.is_empty() && self.rng.chance(0.7) {
                        let (c, v) = self.rng.pick(&self.scope.consts).clone();
                        (c, v)
                    } else {
                        let v = self.small_len();
                        (v.to_string(), v)
                    })
                } else {
                    None
                };
                Name { name, len }
            })
            .collect()
    }

    fn let_item(&mut self, name: &str) -> String {
        if self.rng.chance(0.75) {
            let d = self.depth();
            let item = format!("let {name} = {};", self.expr(d, false));
            self.scope.lets.push(Name {
                name: name.into(),
                len: None,
            });
            return item;
        }
        let (len_text, len) = match self.scope.consts.first() {
            Some((c, v)) if self.rng.chance(0.6) => (c.clone(), *v),
            _ => {
                let v = self.small_len();
                (v.to_string(), v)
            }
        };
        self.scope.vars.push(("i".into(), 0, len));
        let d = self.depth();
        let value = self.expr(d, false);
        self.scope.vars.pop();
        let item = format!("let {name}[i in 0..{len_text}] = {value};");
        self.scope.lets.push(Name {
            name: name.into(),
            len: Some((len_text, len)),
        });
        item
    }

    /// One or two `kinetic:` sections giving every coordinate a mass, plus
    /// sometimes velocities of positions.
    fn kinetic(&mut self) -> Vec<String> {
        let mut terms = Vec::new();
        for c in self.scope.coordinates.clone() {
            let coefficient = self.coefficient();
            terms.push(match &c.len {
                None => format!("{coefficient}*dot({})^2", c.name),
                Some((len, _)) => {
                    format!("sum(i in 0..{len}, {coefficient}*dot({}[i])^2)", c.name)
                }
            });
        }
        if self.rng.chance(0.3) {
            let position = self.expr(1, false);
            terms.push(format!("{}*dot({position})^2", self.coefficient()));
        }
        if self.rng.chance(0.1) {
            let (a, b) = (self.velocity(), self.velocity());
            terms.push(format!("{a}*{b}/10"));
        }
        if terms.len() > 1 && self.rng.chance(0.2) {
            let split = self.rng.range(1, terms.len() - 1);
            let rest = terms.split_off(split);
            return vec![
                format!("kinetic: {};", terms.join(" + ")),
                format!("kinetic: {};", rest.join(" + ")),
            ];
        }
        vec![format!("kinetic: {};", terms.join(" + "))]
    }

    /// A positive factor: a number, a parameter, or one half of one.
    fn coefficient(&mut self) -> String {
        let scalars: Vec<String> = self
            .scope
            .parameters
            .iter()
            .filter(|p| p.len.is_none())
            .map(|p| p.name.clone())
            .collect();
        match self.rng.below(4) {
            0 if !scalars.is_empty() => format!("{}/2", self.rng.pick(&scalars)),
            1 if !scalars.is_empty() => self.rng.pick(&scalars).clone(),
            2 => "1/2".into(),
            _ => self.rng.range(1, 5).to_string(),
        }
    }

    /// `dot` of a coordinate or element.
    fn velocity(&mut self) -> String {
        let c = self.rng.pick(&self.scope.coordinates).clone();
        format!("dot({})", self.reference(&c))
    }

    fn quadratic_in_velocities(&mut self) -> String {
        let v = self.velocity();
        format!("{}*{v}^2", self.coefficient())
    }

    fn forces(&mut self) -> String {
        let mut entries = Vec::new();
        let mut targets: Vec<Name> = self.scope.coordinates.clone();
        targets.extend(self.scope.lets.iter().cloned());
        for _ in 0..self.rng.range(1, 2) {
            let target = self.rng.pick(&targets).clone();
            let d = self.depth();
            let value = self.expr(d, true);
            entries.push(format!("{} = {value}", self.reference(&target)));
        }
        format!("forces: {};", entries.join(", "))
    }

    /// `name` or one element of it, with an index in range.
    fn reference(&mut self, n: &Name) -> String {
        match &n.len {
            None => n.name.clone(),
            Some((len_text, len)) => format!("{}[{}]", n.name, self.index(len_text, *len)),
        }
    }

    /// An index into `0..len`: a literal, an index variable whose range fits,
    /// `i - 1`, or `N - 1`.
    fn index(&mut self, len_text: &str, len: i64) -> String {
        let fitting: Vec<(String, i64)> = self
            .scope
            .vars
            .iter()
            .filter(|(_, lo, hi)| *lo >= 0 && *hi <= len)
            .map(|(v, lo, _)| (v.clone(), *lo))
            .collect();
        match self.rng.below(5) {
            0 | 1 if !fitting.is_empty() => self.rng.pick(&fitting).0.clone(),
            2 if fitting.iter().any(|(_, lo)| *lo >= 1) => {
                let v = fitting.iter().find(|(_, lo)| *lo >= 1).unwrap();
                format!("{} - 1", v.0)
            }
            3 if len_text.parse::<i64>().is_err() => format!("{len_text} - 1"),
            _ => self.rng.below(len as usize).to_string(),
        }
    }

    fn number(&mut self) -> String {
        match self.rng.below(10) {
            0..=4 => self.rng.range(0, 9).to_string(),
            5 => "0.5".into(),
            6 => "2.0".into(),
            7 => "1e-3".into(),
            8 => "3.25".into(),
            _ => "100".into(),
        }
    }

    /// Any real-valued name in scope (not `dot`-wrapped).
    fn atom(&mut self, allow_dot: bool) -> String {
        let mut names: Vec<Name> = Vec::new();
        names.extend(self.scope.coordinates.iter().cloned());
        names.extend(self.scope.parameters.iter().cloned());
        names.extend(self.scope.lets.iter().cloned());
        names.extend(self.scope.constants.iter().map(|c| Name {
            name: c.clone(),
            len: None,
        }));
        match self.rng.below(12) {
            0..=2 => self.number(),
            3 => "t".into(),
            4 if !self.scope.vars.is_empty() => self.rng.pick(&self.scope.vars).0.clone(),
            5 if !self.scope.consts.is_empty() => self.rng.pick(&self.scope.consts).0.clone(),
            6 if allow_dot => self.velocity(),
            _ => {
                let n = self.rng.pick(&names).clone();
                self.reference(&n)
            }
        }
    }

    /// An expression of at most `depth` levels; `dot` only where velocities
    /// may appear.
    fn expr(&mut self, depth: u32, allow_dot: bool) -> String {
        if depth == 0 {
            return self.atom(allow_dot);
        }
        let d = depth - 1;
        match self.rng.weighted(&[6, 10, 2, 4, 6, 2, 2, 2, 2, 2, 2]) {
            0 => self.atom(allow_dot),
            1 => {
                let op = *self.rng.pick(&["+", "-", "*", "/", "*"]);
                format!(
                    "{} {op} {}",
                    self.expr(d, allow_dot),
                    self.expr(d, allow_dot)
                )
            }
            2 => format!("-{}", self.expr(d, allow_dot)),
            3 => {
                let exponent = match self.rng.below(4) {
                    0 => "-1".to_string(),
                    1 => self.expr(d, allow_dot),
                    _ => self.rng.range(2, 3).to_string(),
                };
                format!("({})^{exponent}", self.expr(d, allow_dot))
            }
            4 => {
                let f = *self.rng.pick(&FUNCTIONS);
                format!("{f}({})", self.expr(d, allow_dot))
            }
            5 => {
                let f = *self.rng.pick(&FUNCTIONS);
                format!("({}).{f}()", self.expr(d, allow_dot))
            }
            6 => match self.rng.below(3) {
                0 => format!(
                    "atan2({}, {})",
                    self.expr(d, allow_dot),
                    self.expr(d, allow_dot)
                ),
                1 => format!(
                    "({}).powi({})",
                    self.expr(d, allow_dot),
                    self.rng.range(2, 4)
                ),
                _ => format!("powf({}, 0.5)", self.expr(d, allow_dot)),
            },
            7 => self.sum(d, allow_dot),
            8 => format!("({})", self.expr(d, allow_dot)),
            _ if allow_dot => {
                let position = self.expr(d, false);
                format!("dot({position})")
            }
            9 => match self.rng.below(2) {
                0 => format!(
                    "inner({}, {})",
                    self.vector(d, allow_dot),
                    self.vector(d, allow_dot)
                ),
                _ => format!("norm({})", self.vector(d, allow_dot)),
            },
            _ => self.atom(false),
        }
    }

    /// A vector of 3 components, from the vector functions
    /// (`docs/language.md`, "Vectors and rotations").
    fn vector(&mut self, depth: u32, allow_dot: bool) -> String {
        if depth == 0 {
            return format!(
                "vector({}, {}, {})",
                self.atom(allow_dot),
                self.atom(allow_dot),
                self.atom(allow_dot)
            );
        }
        let d = depth - 1;
        match self.rng.below(7) {
            0 => format!(
                "vector({}, {}, {})",
                self.expr(d, allow_dot),
                self.expr(d, allow_dot),
                self.expr(d, allow_dot)
            ),
            1 => format!(
                "cross({}, {})",
                self.vector(d, allow_dot),
                self.vector(d, allow_dot)
            ),
            2 => {
                let f = *self.rng.pick(&["rotate_x", "rotate_y", "rotate_z"]);
                format!(
                    "{f}({}, {})",
                    self.expr(d, false),
                    self.vector(d, allow_dot)
                )
            }
            3 => format!(
                "rotate(vector({}, {}, {}, {}), {})",
                self.atom(false),
                self.atom(false),
                self.atom(false),
                self.atom(false),
                self.vector(d, allow_dot)
            ),
            4 => {
                let op = *self.rng.pick(&["+", "-"]);
                format!(
                    "{} {op} {}",
                    self.vector(d, allow_dot),
                    self.vector(d, allow_dot)
                )
            }
            5 => format!(
                "({})*{}",
                self.expr(d, allow_dot),
                self.vector(d, allow_dot)
            ),
            _ if allow_dot => format!("dot({})", self.vector(d, false)),
            _ => format!("-{}", self.vector(d, allow_dot)),
        }
    }

    /// `sum(j in lo..hi, body)`, with `j` in scope in the body.
    fn sum(&mut self, depth: u32, allow_dot: bool) -> String {
        let var = ["j", "k", "l2", "j2"][self.scope.vars.len().min(3)].to_string();
        let arrays: Vec<Name> = (self.scope.coordinates.iter())
            .chain(&self.scope.parameters)
            .chain(&self.scope.lets)
            .filter(|n| n.len.is_some())
            .cloned()
            .collect();
        let (range, lo, hi) = match (arrays.is_empty(), self.rng.below(3)) {
            (false, 0 | 1) => {
                let (len_text, len) = self.rng.pick(&arrays).len.clone().unwrap();
                (format!("0..{len_text}"), 0, len)
            }
            (_, 2) if !self.scope.vars.is_empty() => {
                // A triangular range on an outer index.
                let (outer, lo, hi) = self.scope.vars.last().unwrap().clone();
                (format!("{lo}..={outer}"), lo, hi)
            }
            _ => {
                let hi = self.rng.range(0, 4) as i64;
                (format!("1..{}", hi + 1), 1, hi + 1)
            }
        };
        self.scope.vars.push((var.clone(), lo, hi));
        let body = self.expr(depth, allow_dot);
        self.scope.vars.pop();
        format!("sum({var} in {range}, {body})")
    }
}

fn list(names: &[Name]) -> String {
    names
        .iter()
        .map(|n| match &n.len {
            None => n.name.clone(),
            Some((len, _)) => format!("{}[{len}]", n.name),
        })
        .collect::<Vec<_>>()
        .join(", ")
}
