//! The core's step loop allocates nothing (it is meant to run thousands of landings): a
//! counting global allocator for this test binary, counted per thread so that parallel tests
//! do not interfere.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use touchdown_core::Landing;

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations() -> u64 {
    ALLOCATIONS.with(|c| c.get())
}

/// With every integration scheme (the report's, the report's in long strides, the
/// fourth-order Runge–Kutta method and the adaptive Dormand–Prince pair, which also rejects
/// steps), and either footpad.
#[test]
fn stepping_a_landing_does_not_allocate() {
    let runs = ["report", "strides", "rk4", "dopri5"]
        .into_iter()
        .flat_map(|scheme| ["rigid", "inertial"].map(|footpad| (scheme, footpad)));
    for (scheme, footpad) in runs {
        let path = touchdown_tests::variant(
            "fig-25-26.toml",
            &format!("allocation-{scheme}-{footpad}"),
            &format!("[integrator]\nscheme = \"{scheme}\"\n[footpad]\ndetached = \"{footpad}\"\n"),
        );
        let sc = touchdown_scenario::Scenario::load(path).unwrap();
        let mut sim = touchdown_core::Simulation::new(&sc).unwrap();
        let before = allocations();
        let mut steps = 0;
        while !sim.finished() {
            sim.step().unwrap();
            steps += 1;
        }
        let during = allocations() - before;
        assert!(
            steps > 500,
            "{scheme}, {footpad}: the landing should take many steps, took {steps}"
        );
        // The counter itself must work: the summary allocates.
        let _ = sim.summary();
        assert!(
            allocations() > before,
            "the counting allocator is not counting"
        );
        assert_eq!(
            during, 0,
            "{scheme}, {footpad}: {during} allocations in {steps} steps"
        );
    }
}
