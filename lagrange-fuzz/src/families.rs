//! Pathological families: the shapes that reach a recursion's depth, an
//! integer's range or a loop's length (issue 10). Each is drawn with a size
//! log-uniform up to a few times what broke the engine, so that most stay
//! small and every decade is visited; the fuzzer weights them low.

use crate::rng::Rng;

/// Integers at the edges of what index arithmetic holds: `2^21` cubed is
/// `2^63`, so `-2097152*2097152*2097152` is `i64::MIN`.
pub const INTEGERS: [&str; 16] = [
    "0",
    "1",
    "2",
    "10000",
    "10001",
    "65536",
    "2097152",
    "2147483647",
    "2147483648",
    "4294967296",
    "3037000500",
    "9223372036854775807",
    "9223372036854775808",
    "18446744073709551616",
    "1000000000000",
    "340282366920938463463374607431768211456",
];

/// `(name, weight in the family draw, largest size)`.
const FAMILIES: [(&str, u32, usize); 17] = [
    ("flat-sum", 6, 30_000),
    ("flat-product", 6, 30_000),
    ("parens", 6, 10_000),
    ("unary-minus", 6, 60_000),
    ("nested-calls", 6, 8_000),
    ("power-tower", 6, 12_000),
    ("method-chain", 6, 40_000),
    ("exp-ln", 4, 4_000),
    ("index-arithmetic", 6, 30_000),
    ("extreme-integers", 16, 0),
    ("nested-sums", 3, 10_000),
    ("large-n", 2, 10_000),
    ("wide-sum", 2, 3_000),
    ("chain", 2, 200),
    ("polynomial", 2, 5_000),
    ("let-chain", 3, 3_000),
    ("many-sections", 3, 10_000),
];

/// A pathological model and its family, with its size: `("flat-sum n=120", text)`.
pub fn family(rng: &mut Rng) -> (String, String) {
    let weights: Vec<u32> = FAMILIES.iter().map(|f| f.1).collect();
    let (name, _, max) = FAMILIES[rng.weighted(&weights)];
    let n = rng.log_size(max.max(1));
    let x = "x";
    let text = match name {
        "flat-sum" => {
            let op = if rng.chance(0.5) { " + " } else { " - " };
            energy(&vec![x; n].join(op))
        }
        "flat-product" => energy(&vec![x; n].join("*")),
        "parens" => energy(&format!("{}{x}{}", "(".repeat(n), ")".repeat(n))),
        "unary-minus" => energy(&format!("{}{x}", "-".repeat(n))),
        "nested-calls" => {
            let fixed = rng
                .chance(0.5)
                .then(|| *rng.pick(&["sin", "cos", "sqrt", "tanh"]));
            let mut open = String::new();
            for _ in 0..n {
                open.push_str(fixed.unwrap_or_else(|| *rng.pick(&["sin", "cos", "exp", "atan"])));
                open.push('(');
            }
            energy(&format!("{open}{x}{}", ")".repeat(n)))
        }
        "power-tower" => energy(&vec![x; n].join("^")),
        "method-chain" => {
            let m = if rng.chance(0.5) { ".sin()" } else { ".cos()" };
            energy(&format!("{x}{}", m.repeat(n)))
        }
        "exp-ln" => energy(&format!("{}{x}{}", "exp(ln(".repeat(n), "))".repeat(n))),
        "index-arithmetic" => {
            let index = match rng.below(3) {
                0 => vec!["0"; n].join(" + "),
                1 => format!("{}0{}", "(".repeat(n), ")".repeat(n)),
                _ => format!("{}0", "-".repeat(n)),
            };
            format!(
                "struct M {{ coordinates: q[2]; kinetic: dot(q[0])^2 + dot(q[1])^2; potential: q[{index}]; }}"
            )
        }
        "extreme-integers" => return (name.into(), extreme_integers(rng)),
        "nested-sums" => {
            let depth = rng.range(1, 4);
            let mut body = x.to_string();
            for k in (0..depth).rev() {
                let hi = rng.log_size(max);
                body = format!("sum(i{k} in 0..{hi}, {body})");
            }
            energy(&body)
        }
        "large-n" => format!(
            "struct M {{ const N = {n}; coordinates: q[N]; parameters: k; \
             kinetic: sum(i in 0..N, dot(q[i])^2); potential: sum(i in 0..N, k*q[i]^2); }}"
        ),
        "wide-sum" => format!(
            "struct M {{ const N = {n}; coordinates: x; parameters: a[N], b[N]; \
             let y[i in 0..N] = sum(j in 0..N, a[j]) + b[i]; \
             kinetic: dot(x)^2; potential: sum(i in 0..N, y[i]*x); }}"
        ),
        "chain" => format!(
            "pub struct Chain {{ const N = {n}; coordinates: theta[N]; parameters: m[N], l[N]; \
             constants: g = 9.81; \
             let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j])); \
             let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j])); \
             kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2)); \
             potential: sum(i in 0..N, m[i]*g*y[i]); }}"
        ),
        "polynomial" => {
            let terms: Vec<String> = (1..=n).map(|k| format!("{k}*{x}^{k}")).collect();
            energy(&terms.join(" + "))
        }
        "let-chain" => {
            let mut lets = format!("let a0 = sin({x});");
            for k in 1..n {
                let op = *rng.pick(&["*", "+", "/"]);
                lets.push_str(&format!(" let a{k} = a{} {op} cos(a{});", k - 1, k - 1));
            }
            format!(
                "struct M {{ coordinates: {x}; {lets} kinetic: dot({x})^2; potential: a{}; }}",
                n - 1
            )
        }
        _ => {
            let sections = format!("potential: {x}; ").repeat(n);
            format!("struct M {{ coordinates: {x}; kinetic: dot({x})^2; {sections}}}")
        }
    };
    (format!("{name} n={n}"), text)
}

/// A one-coordinate model whose potential is `v`.
fn energy(v: &str) -> String {
    format!("struct M {{ coordinates: x; parameters: a; kinetic: dot(x)^2; potential: {v}; }}")
}

/// Integer atoms for index arithmetic: small ones, the limits of a literal
/// (`i32::MAX`), and products reaching the limits of `i64` (`2^21` cubed is
/// `2^63`, so `-2097152*2097152*2097152` is `i64::MIN`).
pub const INT_ATOMS: [&str; 16] = [
    "-2097152*2097152*2097152",
    "-2097152*2097152*2097152",
    "-2097152*2097152*2097152",
    "-2097152*2097152*2097152",
    "2097152*2097152*2097152",
    "3037000500*3037000500",
    "2147483647*2147483647*2",
    "-1",
    "-1",
    "-1",
    "1",
    "0",
    "10000",
    "2147483647",
    "2147483648",
    "-2147483647",
];

/// Each one operation away from `i64`'s limits (`i64::MIN / -1`,
/// `-i64::MIN`, `i64::MIN - 1`, ...) or at them.
const EDGES: [&str; 8] = [
    "-2097152*2097152*2097152/-1",
    "-2097152*2097152*2097152",
    "-2097152*2097152*2097152-1",
    "-(-2097152*2097152*2097152)",
    "-2097152*2097152*2097152*-1",
    "2097152*2097152*2097152",
    "3037000500*3037000500",
    "-2097152*2097152*2097152/2097152",
];

/// Integer arithmetic at the edges of `i64` in every place an integer goes:
/// a `const`, a length, a range, an index.
fn extreme_integers(rng: &mut Rng) -> String {
    let int = |rng: &mut Rng| {
        if rng.chance(0.5) {
            return rng.pick(&EDGES).to_string();
        }
        let mut e = rng.pick(&INT_ATOMS).to_string();
        for _ in 0..rng.weighted(&[2, 4, 1]) {
            let (op, atom) = (*rng.pick(&["*", "+", "-", "/", "/"]), *rng.pick(&INT_ATOMS));
            e.push_str(op);
            e.push_str(atom);
        }
        e
    };
    // One extreme slot per model, the others mostly plain, so that an
    // early error elsewhere rarely hides the extreme one.
    let plain = |rng: &mut Rng| {
        if rng.chance(0.7) {
            rng.pick(&["0", "1", "2"]).to_string()
        } else {
            int(rng)
        }
    };
    let a = int(rng);
    let (b, c) = if rng.chance(0.5) {
        (plain(rng), plain(rng))
    } else {
        let b = plain(rng);
        (a.clone(), b)
    };
    let (a, b) = if rng.chance(0.5) { (a, b) } else { (b, a) };
    match rng.below(6) {
        0 => format!(
            "struct M {{ const N = {a}; coordinates: x; kinetic: dot(x)^2; potential: N*x; }}"
        ),
        1 => format!(
            "struct M {{ const N = {a}; coordinates: q[N]; kinetic: sum(i in 0..N, dot(q[i])^2); potential: 0; }}"
        ),
        2 | 3 => {
            let use_it = if rng.chance(0.5) {
                format!("y[{c}]")
            } else {
                "y".into()
            };
            format!(
                "struct M {{ coordinates: x; let y[i in {a}..{b}] = 0; kinetic: dot(x)^2; potential: {use_it}; }}"
            )
        }
        4 => format!(
            "struct M {{ coordinates: q[2]; kinetic: dot(q[0])^2 + dot(q[1])^2; potential: q[{a}]; forces: q[{b}] = 1; }}"
        ),
        _ => format!(
            "struct M {{ coordinates: x; kinetic: dot(x)^2; potential: sum(i in {a}..={b}, x*i); }}"
        ),
    }
}
