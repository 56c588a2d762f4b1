//! Scenes with unilateral contacts and friction (`contacts:`), each with
//! its closed form: run them with
//! [`contact::integrate`](lagrange_runtime::contact::integrate).

mod ball_on_floor;
mod ball_on_table;
mod bearing;
mod belt;
mod die;
mod incline;
mod ladder;
mod puck;
mod sliding_ball;
mod sphere;
mod string;
mod tippe_top;
mod tumbling_box;

pub use ball_on_floor::BallOnFloor;
pub use ball_on_table::BallOnTable;
pub use bearing::{Swing, TorsionBearing};
pub use belt::{BlockOnBelt, StickSlip};
pub use die::Die;
pub use incline::BlockOnIncline;
pub use ladder::Ladder;
pub use puck::PushedPuck;
pub use sliding_ball::SlidingBall;
pub use sphere::ParticleOnSphere;
pub use string::BobOnString;
pub use tippe_top::TippeTop;
pub use tumbling_box::TumblingBox;
