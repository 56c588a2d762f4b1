//! Robots from URDF against Pinocchio: a test binary of its own, left out
//! of the README's `cargo test` (`test = false` in the facade's manifest)
//! and run by CI with `cargo test --test robots`.
//!
//! The robots' generated code (six robots, the humanoid's 1.1 MB among
//! them, in `f64`, `f32` and SIMD lanes) took about 75 s of the suite's
//! build on the critical path of `cargo test` (the suite's binary built in
//! 202 s with them and 128 s without, on the 2-core development machine,
//! idle; ARCHITECTURE.md, "Build time"); here it builds beside the rest
//! only where it is asked for.

mod dynamics;
mod frames;
