//! Every solver on fuzzed legs and options, from Table III's home start: whatever comes back,
//! an ok keeps the invariants (finite, the tolerance met as reported and as measured again,
//! det B of the start's sign). Not "no panic" alone: a violation panics, and libFuzzer keeps
//! the input.
//!
//! Input: 6 legs of 9 bytes each (a mode byte, then 8 bytes), then an options byte. Mode 0 takes
//! the 8 bytes as an f64 bit pattern (NaN, infinities, subnormals, anything); other modes put
//! the leg near the home legs (the useful part of the space), within ±mode mm.
#![no_main]

use linkage::{
    arc_length, arc_length_detour, newton_homotopy, newton_raphson, Linear, Options, Tracker,
};
use linkage_examples::stewart::{home_start, Stewart};
use linkage_tests::invariants::ok_violation;

fn leg(chunk: &[u8], home: f64) -> f64 {
    let bits = u64::from_le_bytes(chunk[1..9].try_into().unwrap());
    match chunk[0] {
        0 => f64::from_bits(bits),
        mode => home + mode as f64 * ((bits >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0),
    }
}

fn options(byte: u8) -> Options {
    let base = if byte & 1 == 0 {
        Options::TIGHT
    } else {
        Options::PAPER
    };
    let linear = if byte & 2 == 0 {
        Linear::Generated
    } else {
        Linear::Dense
    };
    let tolerance = match byte >> 2 {
        0 => f64::NAN,
        1 => 0.0,
        2 => 5e-324,
        3 => 1e300,
        4 => 1e-14,
        _ => base.tolerance,
    };
    Options {
        tolerance,
        linear,
        ..base
    }
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if data.len() < 6 * 9 + 1 {
        return;
    }
    let s = Stewart::new();
    let start = home_start(&s).expect("Table III's home start");
    // The start's pivots and legs, through a public accessor.
    let tracker = Tracker::new(s.clone(), start, Options::TIGHT);
    let (v0, x0) = (*tracker.state().0, *tracker.state().1);
    let det0 = linkage::det_b(&s, &v0, &x0);
    let x: [f64; 6] = std::array::from_fn(|j| leg(&data[9 * j..9 * j + 9], x0[j]));
    let options = options(data[54]);
    for (name, result) in [
        ("PH", arc_length(&s, &start, &x, &options)),
        (
            "PH detour",
            arc_length_detour(&s, &start, &x, &options).map(|d| d.solution),
        ),
        ("NH", newton_homotopy(&s, &start, &x, &options)),
        ("NR", newton_raphson(&s, &start, &x, &options)),
    ] {
        if let Ok(sol) = result {
            if let Some(v) = ok_violation(&s, det0, &x, &sol, options.tolerance) {
                panic!("{name} at legs {x:?} with {options:?}: {v}");
            }
        }
    }
});
