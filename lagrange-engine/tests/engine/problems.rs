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
