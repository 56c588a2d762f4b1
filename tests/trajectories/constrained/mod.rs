//! Constrained models: closed loops and redundant coordinates, against
//! what is known of them exactly (the θ pendulum, the slider-crank's
//! kinematics) and over long runs (the four-bar linkage).

mod cartesian_pendulum;
mod four_bar;
mod slider_crank;
