//! No solve allocates: a counting global allocator watches every solver, the tracker and the
//! certificates.

use linkage::{arc_length, newton_homotopy, newton_raphson, Options, Tracker};
use linkage_examples::stewart::{home_start, Stewart};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// Counts the calling thread's allocations only: the other tests of this binary run on other
/// threads at the same time and allocate as they please.
struct Counting;

thread_local! {
    // `const` initialisation: reading the counter never allocates itself.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count() {
    // `try_with`: during thread teardown the slot may be gone; such allocations are not ours.
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
}

fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

// SAFETY: forwards to the system allocator unchanged; only counts calls.
unsafe impl GlobalAlloc for Counting {
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
    let mut certified = Tracker::new(s.clone(), start, Options::TIGHT).certified();
    let before = allocations();
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
        // Certificates, and the tracker that proves each step.
        if let Ok(sample) = certified.update(&x) {
            checksum += sample.v[0];
            if let Ok(c) = linkage::certify(&s, &sample.v, &x) {
                checksum += c.radius;
            }
        }
    }
    let after = allocations();
    assert!(checksum.is_finite());
    assert_eq!(after - before, 0, "heap allocations during solves");
}

#[test]
fn all_modes_queries_do_not_allocate() {
    use linkage::modes::Roots;
    // The result storage is the caller's: boxed here only to keep the test's stack small.
    let mut roots = Box::new(Roots::<18, 64>::new());
    let targets = [
        [170.0; 6],
        [190.0, 200.0, 190.0, 180.0, 190.0, 210.0],
        [f64::NAN; 6],
        [-1.0, 170.0, 170.0, 170.0, 170.0, 170.0],
    ];
    let before = allocations();
    // From the embedded start set (checked and refined here) to the answers: no heap at all.
    let modes = linkage_examples::start_sets::table_iii::<64>().unwrap();
    let mut found = 0;
    for x in &targets {
        if modes.solve(x, &mut roots).is_ok() {
            found += roots.real().len();
        }
    }
    let after = allocations();
    assert!(found > 0);
    assert_eq!(
        after - before,
        0,
        "heap allocations during all-modes queries"
    );
}
