//! The same M and f by runtime forward-mode AD (num-dual): one Hessian of
//! L(q, q̇) = T − V over z = (q, q̇), which also gives the gradient, then
//!
//!     M = ∂²L/∂q̇²,    f = ∂L/∂q − (∂²L/∂q̇∂q) q̇
//!
//! (the chain has no explicit time dependence). Checks them against the
//! generated code and times both; prints `key value` lines. Exits with an
//! error if they disagree.

use chain::{G, N};
use lagrange::nalgebra::{SMatrix, SVector};
use num_dual::{hessian, Dual2SVec64, DualNum};
use std::hint::black_box;

const D: usize = 2 * N;
const TOLERANCE: f64 = 1e-10;

/// L = T − V of the chain, for any scalar: f64 or a dual number.
fn lagrangian<T: DualNum<Primitive = f64> + Copy>(z: &[T], m: &[f64; N], l: &[f64; N]) -> T {
    let zero = T::from(0.0);
    let (mut y, mut xdot, mut ydot) = (zero, zero, zero);
    let (mut kinetic, mut potential) = (zero, zero);
    for i in 0..N {
        let (s, c) = z[i].sin_cos();
        let w = z[N + i];
        y -= c * l[i];
        xdot += c * w * l[i];
        ydot += s * w * l[i];
        kinetic += (xdot * xdot + ydot * ydot) * (0.5 * m[i]);
        potential += y * (m[i] * G);
    }
    kinetic - potential
}

fn ad_mass_matrix_and_forcing(
    m: &[f64; N],
    l: &[f64; N],
    q: &SVector<f64, N>,
    qdot: &SVector<f64, N>,
) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
    let z = SVector::<f64, D>::from_fn(|k, _| if k < N { q[k] } else { qdot[k - N] });
    let (_, grad, h) = hessian(
        |z: SVector<Dual2SVec64<D>, D>| lagrangian(z.as_slice(), m, l),
        &z,
    );
    let mass = SMatrix::<f64, N, N>::from_fn(|i, j| h[(N + i, N + j)]);
    let forcing = SVector::<f64, N>::from_fn(|i, _| {
        grad[i] - (0..N).map(|j| h[(N + i, j)] * qdot[j]).sum::<f64>()
    });
    (mass, forcing)
}

/// max |a − b| over max |b|: the disagreement relative to the entries' scale.
fn relative_difference<const R: usize, const C: usize>(
    a: &SMatrix<f64, R, C>,
    b: &SMatrix<f64, R, C>,
) -> f64 {
    (a - b).amax() / b.amax().max(f64::MIN_POSITIVE)
}

fn run() -> Result<(), String> {
    let model = chain::model();
    let (m, l) = chain::parameters();
    let mut worst: f64 = 0.0;
    for k in 0..4 {
        let (q, qdot) = chain::state(k);
        let (mass, forcing) = model.mass_matrix_and_forcing(0.0, &q, &qdot);
        let (ad_mass, ad_forcing) = ad_mass_matrix_and_forcing(&m, &l, &q, &qdot);
        let dm = relative_difference(&ad_mass, &mass);
        let df = relative_difference(&ad_forcing, &forcing);
        // NaN must fail too: compare with `!(x <= tol)`.
        if !(dm <= TOLERANCE && df <= TOLERANCE) {
            return Err(format!(
                "AD and generated code disagree for the {N}-link chain at state {k}: \
                 relative difference {dm:e} in M, {df:e} in f\nM generated {mass}\nM AD {ad_mass}\n\
                 f generated {forcing}\nf AD {ad_forcing}"
            ));
        }
        worst = worst.max(dm).max(df);
    }
    println!("max_rel_diff {worst:e}");

    let (q, qdot) = chain::state(0);
    let (gen_ns, ad_ns) = chain::time_ns_pair(
        || {
            black_box(model.mass_matrix_and_forcing(
                black_box(0.0),
                black_box(&q),
                black_box(&qdot),
            ));
        },
        || {
            black_box(ad_mass_matrix_and_forcing(
                black_box(&m),
                black_box(&l),
                black_box(&q),
                black_box(&qdot),
            ));
        },
    );
    println!("gen_ns {gen_ns}");
    println!("ad_ns {ad_ns}");
    Ok(())
}

fn main() {
    // A second-order dual number over 2N variables carries 1 + 2N + 4N²
    // f64s: the AD temporaries need a deep stack for the longer chains.
    let result = std::thread::Builder::new()
        .stack_size(1 << 29)
        .spawn(run)
        .expect("spawn the AD thread")
        .join()
        .expect("the AD thread panicked");
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
