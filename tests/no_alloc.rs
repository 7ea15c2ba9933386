//! No solve allocates: a counting global allocator watches every solver and the tracker.

use linkage::{arc_length, newton_homotopy, newton_raphson, Options, Tracker};
use linkage_examples::stewart::{home_start, Stewart};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator unchanged; only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn solves_and_tracking_do_not_allocate() {
    let s = Stewart::new();
    let start = home_start(&s).unwrap();
    let targets = [
        [190.0, 200.0, 190.0, 180.0, 190.0, 210.0],
        [170.0, 170.0, 170.0, 170.0, 170.0, 600.0],
        [f64::NAN; 6],
    ];
    let mut tracker = Tracker::new(s.clone(), start, Options::TIGHT);
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let mut checksum = 0.0;
    for x in &targets {
        let solves = [
            arc_length(&s, &start, x, &Options::TIGHT),
            newton_homotopy(&s, &start, x, &Options::PAPER),
            newton_raphson(&s, &start, x, &Options::TIGHT),
        ];
        for sol in solves.into_iter().flatten() {
            checksum += sol.v[0];
        }
    }
    for k in 1..100 {
        let x = [170.0 + 0.01 * k as f64; 6];
        if let Ok(sample) = tracker.update(&x) {
            checksum += sample.v[0];
        }
    }
    let after = ALLOCATIONS.load(Ordering::SeqCst);
    assert!(checksum.is_finite());
    assert_eq!(after - before, 0, "heap allocations during solves");
}
