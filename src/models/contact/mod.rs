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
mod pushed_rod;
mod rough_ladder;
mod sliding_ball;
mod sphere;
mod string;
mod tippe_top;
mod tumbling_box;

pub use ball_on_floor::{BallOnFloor, BallOnFloorParameters};
pub use ball_on_table::{BallOnTable, BallOnTableParameters};
pub use bearing::{Swing, TorsionBearing, TorsionBearingParameters};
pub use belt::{BlockOnBelt, BlockOnBeltParameters, StickSlip};
pub use die::{Die, DieParameters};
pub use incline::{BlockOnIncline, BlockOnInclineParameters};
pub use ladder::{Ladder, LadderParameters};
pub use puck::{PushedPuck, PushedPuckParameters};
pub use pushed_rod::{PushedRod, PushedRodParameters};
pub use rough_ladder::{RoughLadder, RoughLadderParameters};
pub use sliding_ball::{SlidingBall, SlidingBallParameters};
pub use sphere::{ParticleOnSphere, ParticleOnSphereParameters};
pub use string::{BobOnString, BobOnStringParameters};
pub use tippe_top::{TippeTop, TippeTopParameters};
pub use tumbling_box::{TumblingBox, TumblingBoxParameters};
