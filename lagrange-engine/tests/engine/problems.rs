//! The models and helpers the engine's test modules share, defined once.

use lagrange_engine::Derived;

/// The README's double pendulum.
pub const DOUBLE_PENDULUM: &str = "
    pub struct DoublePendulum {
        coordinates: theta1, theta2;
        parameters: m1, m2, l1, l2, g;
        let x1 = l1*sin(theta1);
        let y1 = -l1*cos(theta1);
        let x2 = x1 + l2*sin(theta2);
        let y2 = y1 - l2*cos(theta2);
        kinetic: m1/2*(dot(x1)^2 + dot(y1)^2) + m2/2*(dot(x2)^2 + dot(y2)^2);
        potential: m1*g*y1 + m2*g*y2;
    }";

/// The README's chain of `n` links in the indexed language (the scaling
/// benchmark's too).
pub fn indexed_chain(n: usize) -> String {
    format!(
        "pub struct Chain {{
            const N = {n};
            coordinates: theta[N];
            parameters: m[N], l[N];
            constants: g = 9.81;
            let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
            let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
            kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
            potential: sum(i in 0..N, m[i]*g*y[i]);
        }}"
    )
}

/// The derived equations of `src`, which must derive.
pub fn derive(src: &str) -> Derived {
    match lagrange_engine::derive(src.parse().unwrap()) {
        Ok(d) => d,
        Err(e) => panic!("{e}"),
    }
}

/// The error `src` must give.
pub fn error(src: &str) -> String {
    match lagrange_engine::derive(src.parse().unwrap()) {
        Ok(_) => panic!("expected an error from {src}"),
        Err(e) => e.to_string(),
    }
}

/// The comb: a planar chain of 20 point masses on rods in relative angles,
/// with a branch of two links hanging from the end of every fourth link
/// (5 branches, 30 coordinates); the masses `m[i]` on the chain and `n[k]`
/// on the branches, one length `l`. `attributes` go before the struct.
pub fn comb(attributes: &str) -> String {
    comb_of(20, attributes)
}

/// [`comb`] with `n` links on the chain (a multiple of 4) and a branch on
/// every fourth: `n + n/2` coordinates.
pub fn comb_of(n: usize, attributes: &str) -> String {
    let b = n / 4;
    format!(
        "{attributes} pub struct Comb {{
            const N = {n};
            const B = {b};
            coordinates: theta[N], psi[2*B];
            parameters: m[N], n[2*B], l;
            constants: g = 9.81;
            let a[i in 0..N] = sum(j in 0..=i, theta[j]);
            let x[i in 0..N] = l*sum(j in 0..=i, sin(a[j]));
            let y[i in 0..N] = -l*sum(j in 0..=i, cos(a[j]));
            let b1[k in 0..B] = a[4*k+3] + psi[2*k];
            let b2[k in 0..B] = b1[k] + psi[2*k+1];
            let u1[k in 0..B] = x[4*k+3] + l*sin(b1[k]);
            let v1[k in 0..B] = y[4*k+3] - l*cos(b1[k]);
            let u2[k in 0..B] = u1[k] + l*sin(b2[k]);
            let v2[k in 0..B] = v1[k] - l*cos(b2[k]);
            kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2))
                + sum(k in 0..B, n[2*k]/2*(dot(u1[k])^2 + dot(v1[k])^2) + n[2*k+1]/2*(dot(u2[k])^2 + dot(v2[k])^2));
            potential: g*(sum(i in 0..N, m[i]*y[i]) + sum(k in 0..B, n[2*k]*v1[k] + n[2*k+1]*v2[k]));
        }}"
    )
}

/// A binary tree of 64 links: the complete tree of depth 6 (63 links,
/// link `k` of `1..=63` hanging from the end of link `k/2`, link 1 from
/// the origin) and one more, link 64, below link 32; point masses `m` on
/// rods `l` in relative angles, one coordinate `q[k-1]` per link.
pub fn binary_tree_64(attributes: &str) -> String {
    let mut lets = String::from("let a1 = q[0]; let x1 = l*sin(a1); let y1 = -l*cos(a1);\n");
    for k in 2..=64 {
        let p = k / 2;
        lets += &format!(
            "let a{k} = a{p} + q[{}]; let x{k} = x{p} + l*sin(a{k}); let y{k} = y{p} - l*cos(a{k});\n",
            k - 1
        );
    }
    let kinetic: Vec<String> = (1..=64)
        .map(|k| format!("dot(x{k})^2 + dot(y{k})^2"))
        .collect();
    let potential: Vec<String> = (1..=64).map(|k| format!("y{k}")).collect();
    format!(
        "{attributes} pub struct BinaryTree {{
            coordinates: q[64];
            parameters: m, l;
            constants: g = 9.81;
            {lets}
            kinetic: m/2*({});
            potential: m*g*({});
        }}",
        kinetic.join(" + "),
        potential.join(" + ")
    )
}
