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
//! five touch a table in 3D, with friction in its plane: [`PushedPuck`],
//! [`PushedRod`] (on two supports that share its friction),
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

pub use bicycle::{WhippleBicycle, WhippleBicycleParameters};
pub use bouncing_ball::{BouncingBall, BouncingBallParameters};
pub use cart_pole::{CartPole, CartPoleParameters};
pub use cartesian_pendulum::{CartesianPendulum, CartesianPendulumParameters};
pub use chain::{Chain, ChainParameters};
pub use chaplygin_sleigh::{ChaplyginSleigh, ChaplyginSleighParameters};
pub use contact::{
    BallOnFloor, BallOnFloorParameters, BallOnTable, BallOnTableParameters, BlockOnBelt,
    BlockOnBeltParameters, BlockOnIncline, BlockOnInclineParameters, BobOnString,
    BobOnStringParameters, Die, DieParameters, Ladder, LadderParameters, ParticleOnSphere,
    ParticleOnSphereParameters, PushedPuck, PushedPuckParameters, PushedRod, PushedRodParameters,
    RoughLadder, RoughLadderParameters, SlidingBall, SlidingBallParameters, StickSlip, Swing,
    TippeTop, TippeTopParameters, TorsionBearing, TorsionBearingParameters, TumblingBox,
    TumblingBoxParameters,
};
pub use damped_double_pendulum::{DampedDoublePendulum, DampedDoublePendulumParameters};
pub use double_pendulum::{DoublePendulum, DoublePendulumParameters};
pub use four_bar::{FourBar, FourBarParameters, MinimalFourBar, MinimalFourBarParameters};
pub use free_body::{FreeBody, FreeBodyParameters};
pub use heavy_top::{EulerTop, EulerTopParameters, HeavyTop, HeavyTopParameters};
pub use kepler::{Kepler, KeplerParameters, PolarKepler, PolarKeplerParameters};
pub use oscillator::{Oscillator, OscillatorParameters};
pub use pendulum::{Pendulum, PendulumParameters};
pub use pendulum_wall::PendulumWall;
pub use rolling_ball::{RollingBall, RollingBallParameters};
pub use rolling_disk::{RollingDisk, RollingDiskParameters};
pub use slider_crank::{
    MinimalSliderCrank, MinimalSliderCrankParameters, SliderCrank, SliderCrankParameters,
    slider_crank_kinematics,
};
pub use stiff_chain::{StiffChain, StiffChainParameters};
pub use tree::{Tree, TreeParameters};
pub use two_mass_chain::{
    RayleighTwoMassChain, RayleighTwoMassChainParameters, TwoMassChain, TwoMassChainParameters,
};
