//! Events and impacts on derived models: the bouncing ball against its
//! closed form and its Zeno limit, the pendulum against a wall against the
//! exact (elliptic) swing.

mod bouncing_ball;
mod observer;
mod pendulum_wall;
