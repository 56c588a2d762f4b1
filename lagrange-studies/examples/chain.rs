//! A chain of eight point masses on massless rods, written once with an
//! index: the model is the same dozen lines whatever `N` is, and the macro
//! unrolls it into the equations of all eight links at compile time.
//!
//! Released from horizontal, the chain falls and whips. Without forces the
//! energy must stay put (its drift measures the integrator); with wind on
//! the last mass and a damper on the first joint, the energy gained must
//! equal the work those forces did. Also times one evaluation of `M` and `f`.
//!
//! `cargo run --release -p lagrange-studies --example chain`

use lagrange::nalgebra::SVector;
use lagrange::prelude::*;
use std::error::Error;
use std::hint::black_box;
use std::time::Instant;

lagrangian! {
    /// A chain of N point masses on massless rods, angles from the downward
    /// vertical. Wind pushes the last mass sideways; the first joint is damped.
    pub struct Chain {
        const N = 8;
        coordinates: theta[N];
        parameters: m[N], l[N], wind, c;
        constants: g = 9.81;
        let x[i in 0..N] = sum(j in 0..=i, l[j]*sin(theta[j]));
        let y[i in 0..N] = -sum(j in 0..=i, l[j]*cos(theta[j]));
        kinetic: sum(i in 0..N, m[i]/2*(dot(x[i])^2 + dot(y[i])^2));
        potential: sum(i in 0..N, m[i]*g*y[i]);
        forces: x[N-1] = wind*sin(t), theta[0] = -c*dot(theta[0]);
    }
}

const N: usize = 8;
type State = SVector<f64, N>;

fn main() -> Result<(), Box<dyn Error>> {
    println!(
        "{N} links: {} coordinates, equations of {} lines derived at compile time \
         (`Chain::<f64>::EQUATIONS`).\n",
        Chain::<f64>::COORDINATES.len(),
        Chain::<f64>::EQUATIONS.lines().count()
    );

    // One metre, one kilogram, in eight equal links, released horizontal.
    let free = Chain::new([1.0 / N as f64; N], [1.0 / N as f64; N], 0.0, 0.0);
    let (q0, qdot0) = (State::repeat(std::f64::consts::FRAC_PI_2), State::zeros());
    let e0 = free.energy(0.0, &q0, &qdot0);
    let tip = |q: &State| -> (f64, f64) {
        (0..N).fold((0.0, 0.0), |(x, y), j| {
            (x + free.l[j] * q[j].sin(), y - free.l[j] * q[j].cos())
        })
    };

    let tol = 1e-10;
    let method = Dop853::new().rtol(tol).atol(tol);
    let times: Vec<f64> = (1..=10).map(f64::from).collect();
    let trajectory = method.integrate(&free, 0.0, q0, qdot0, &times)?;
    let fall = e0 - free.potential_energy(0.0, &State::zeros());
    println!(
        "No forces, Dop853 at rtol = atol = {tol:.0e}; hanging, it would have {fall:.3} J less:"
    );
    println!("{:>5} {:>9} {:>9} {:>10}", "t", "tip x", "tip y", "E - E0");
    for s in &trajectory {
        let (x, y) = tip(&s.q);
        let drift = free.energy(s.t, &s.q, &s.qdot) - e0;
        println!("{:>5.1} {x:>9.4} {y:>9.4} {drift:>10.1e}", s.t);
    }
    println!("{:?}\n", trajectory.stats());

    // Wind on the tip and a damper at the top: E − E0 = ∫ (F ẋ_tip − c θ̇₀²) dt.
    let forced = Chain {
        wind: 0.5,
        c: 0.02,
        ..free
    };
    let dt = 2.5e-4;
    let times: Vec<f64> = (1..=40_000).map(|k| dt * k as f64).collect();
    let trajectory = method.integrate(&forced, 0.0, q0, qdot0, &times)?;
    let power = |t: f64, q: &State, qdot: &State| {
        let tip_speed: f64 = (0..N).map(|j| forced.l[j] * q[j].cos() * qdot[j]).sum();
        forced.wind * t.sin() * tip_speed - forced.c * qdot[0] * qdot[0]
    };
    let start = std::iter::once((power(0.0, &q0, &qdot0), 0.0));
    let samples = trajectory.iter().map(|s| {
        let gained = forced.energy(s.t, &s.q, &s.qdot) - e0;
        (power(s.t, &s.q, &s.qdot), gained)
    });
    let samples: Vec<(f64, f64)> = start.chain(samples).collect();
    let (mut work, mut worst) = (0.0, 0.0_f64);
    for k in (2..samples.len()).step_by(2) {
        work += dt / 3.0 * (samples[k - 2].0 + 4.0 * samples[k - 1].0 + samples[k].0);
        worst = worst.max((samples[k].1 - work).abs());
    }
    println!(
        "Wind {} N·sin(t) on the tip, damper c = {} at the top, to t = 10: the forces did \
         {work:.6} J;\nworst |E - E0 - W| = {worst:.1e} J (Simpson's rule, dt = {dt:.1e}).\n",
        forced.wind, forced.c
    );

    // What one right-hand side costs: the derived M and f, without the solve.
    let (q, qdot) = (q0.map(|a| a - 0.3), State::repeat(0.1));
    let evals = 200_000;
    let clock = Instant::now();
    for _ in 0..evals {
        black_box(forced.mass_matrix_and_forcing(black_box(0.5), black_box(&q), black_box(&qdot)));
    }
    let per_eval = clock.elapsed().as_secs_f64() / evals as f64;
    println!(
        "M + f for {N} links: {:.0} ns per evaluation (informational, one run).",
        per_eval * 1e9
    );
    Ok(())
}
