//! Known problems, ready to use: shared by the tests, the examples, the
//! benchmarks and anyone who wants a known model to try an integrator on.
//! Behind the `models` feature (`lagrange = { version = "0.1", features =
//! ["models"] }`), off by default: a crate that writes its own models does
//! not expand and compile these.
//! Each is a `lagrangian!` invocation in its own file (read the source),
//! with its usual starting states and, where one exists, its exact
//! solution. Three are constrained models, closed loops in
//! redundant coordinates: [`CartesianPendulum`], [`SliderCrank`] and [`FourBar`]
//! (each with its minimal-coordinate twin). One has a control input:
//! [`CartPole`], pushed by a motor force. Two have impacts, as
//! [events](lagrange_runtime::events): [`BouncingBall`] and
//! [`PendulumWall`]. Two are rigid bodies in 3D, their orientation a unit
//! quaternion whose constraint makes their singular mass matrix regular:
//! [`FreeBody`] and [`HeavyTop`] (the functions of [`quaternion`] convert
//! their states). Three roll, under constraints on their velocities:
//! [`ChaplyginSleigh`], [`RollingDisk`] and [`RollingBall`], the last in
//! quaternions too. Nine have unilateral contacts or friction
//! (`contacts:`) in a plane, run by
//! [`contact::integrate`](lagrange_runtime::contact::integrate):
//! [`BallOnFloor`], [`ParticleOnSphere`], [`Ladder`], [`BobOnString`],
//! [`SlidingBall`], [`BlockOnIncline`], [`BlockOnBelt`], [`TumblingBox`]
//! and [`TorsionBearing`] (friction in a joint, against a given load);
//! four touch a table in 3D, with friction in its plane: [`PushedPuck`],
//! [`BallOnTable`], [`Die`] and [`TippeTop`], the last three in unit
//! quaternions.
//! One is a branched [`Tree`] of ten links in relative angles, whose
//! accelerations the runtime solves in `O(N)` without forming `M`.

mod bicycle;
mod bouncing_ball;
mod cart_pole;
mod cartesian_pendulum;
mod chain;
mod chaplygin_sleigh;
mod contact;
mod damped_double_pendulum;
mod double_pendulum;
mod four_bar;
mod free_body;
mod heavy_top;
mod kepler;
mod oscillator;
mod pendulum;
mod pendulum_wall;
pub mod quaternion;
mod rolling_ball;
mod rolling_disk;
mod slider_crank;
mod stiff_chain;
mod tree;
mod two_mass_chain;

pub use bicycle::WhippleBicycle;
pub use bouncing_ball::BouncingBall;
pub use cart_pole::CartPole;
pub use cartesian_pendulum::CartesianPendulum;
pub use chain::Chain;
pub use chaplygin_sleigh::ChaplyginSleigh;
pub use contact::{
    BallOnFloor, BallOnTable, BlockOnBelt, BlockOnIncline, BobOnString, Die, Ladder,
    ParticleOnSphere, PushedPuck, SlidingBall, StickSlip, Swing, TippeTop, TorsionBearing,
    TumblingBox,
};
pub use damped_double_pendulum::DampedDoublePendulum;
pub use double_pendulum::DoublePendulum;
pub use four_bar::{FourBar, MinimalFourBar};
pub use free_body::FreeBody;
pub use heavy_top::{EulerTop, HeavyTop};
pub use kepler::{Kepler, PolarKepler};
pub use oscillator::Oscillator;
pub use pendulum::Pendulum;
pub use pendulum_wall::PendulumWall;
pub use rolling_ball::RollingBall;
pub use rolling_disk::RollingDisk;
pub use slider_crank::{MinimalSliderCrank, SliderCrank, slider_crank_kinematics};
pub use stiff_chain::StiffChain;
pub use tree::Tree;
pub use two_mass_chain::{RayleighTwoMassChain, TwoMassChain};
