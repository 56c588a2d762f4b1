//! A global allocator that tallies this thread's allocations (each test
//! runs on its own thread), for the tests that count them: Radau5 allocates
//! its workspace once per call, never per step (here); a `Stepper`
//! allocates nothing once built (`stepper.rs`).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use crate::models::ElasticPendulum;
use lagrange_runtime::prelude::*;

struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count() {
    // `try_with`: the slot may be gone while the thread shuts down.
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
}

// SAFETY: forwards every call to the system allocator unchanged.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// The allocations this thread has made so far.
pub fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

#[test]
fn allocations_do_not_grow_with_the_number_of_steps() {
    // Nonlinear and stiff, so every step path runs: Newton, Jacobians by
    // finite differences, refactoring, rejections, dense output.
    let model = ElasticPendulum::stiff();
    let (q0, qdot0) = model.start();
    let times: Vec<f64> = (1..=50).map(|i| 0.1 * i as f64).collect();
    let run = |tol: f64| {
        let before = allocations();
        let trajectory = Radau5::new()
            .rtol(tol)
            .atol(tol)
            .integrate(&model, 0.0, q0, qdot0, &times)
            .unwrap();
        let allocations = allocations() - before;
        (allocations, trajectory.stats())
    };
    let (loose, loose_stats) = run(1e-4);
    let (tight, tight_stats) = run(1e-9);
    // The tight run takes several times the steps, Jacobians and LUs of the
    // loose one; one allocation per step (or per Jacobian) would show.
    assert!(tight_stats.steps_accepted > 4 * loose_stats.steps_accepted);
    assert!(tight_stats.jacobian_evals > 4 * loose_stats.jacobian_evals);
    assert_eq!(loose, tight, "{loose_stats:?} vs {tight_stats:?}");
}
