//! The tracker on a fuzzed stream of samples from Table III's home start: every accepted
//! sample keeps the invariants (finite, the next Newton correction within the tolerance, det B
//! of the start's sign), and a refused sample leaves the tracker's state as it was.
//!
//! Input: samples of 7 bytes: a mode byte, then six signed bytes. Mode 0 moves every leg from
//! the last sample by the bytes / 8 mm (coarse steps that may cross folds); mode 1 puts a raw
//! NaN, infinity, zero or huge value in one leg; other modes move by the bytes / 256 mm (a
//! dense trajectory).
#![no_main]

use linkage::{Options, Tracker};
use linkage_examples::stewart::{home_start, Stewart};
use linkage_tests::invariants::point_violation;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let s = Stewart::new();
    let start = home_start(&s).expect("Table III's home start");
    let mut tracker = Tracker::new(s.clone(), start, Options::TIGHT);
    let (v0, x0) = (*tracker.state().0, *tracker.state().1);
    let det0 = linkage::det_b(&s, &v0, &x0);
    let mut x = x0;
    for chunk in data.chunks_exact(7).take(256) {
        let step = |b: u8, per: f64| (b as i8) as f64 / per;
        match chunk[0] {
            0 => (0..6).for_each(|j| x[j] += step(chunk[1 + j], 8.0)),
            1 => {
                let bad = [
                    f64::NAN,
                    f64::INFINITY,
                    -f64::INFINITY,
                    0.0,
                    -1.0,
                    1e154,
                    1e300,
                    f64::MAX,
                ];
                x[chunk[1] as usize % 6] = bad[chunk[2] as usize % bad.len()];
            }
            _ => (0..6).for_each(|j| x[j] += step(chunk[1 + j], 256.0)),
        }
        let before = (*tracker.state().0, *tracker.state().1);
        match tracker.update(&x) {
            Ok(sample) => {
                if let Some(v) = point_violation(&s, det0, &x, &sample.v, Options::TIGHT.tolerance)
                {
                    panic!("accepted legs {x:?}: {v}");
                }
            }
            Err(_) => {
                assert_eq!(
                    (*tracker.state().0, *tracker.state().1),
                    before,
                    "a refused sample changed the tracker's state"
                );
                // Continue from the last accepted legs, as a caller would.
                x = *tracker.state().1;
            }
        }
    }
});
