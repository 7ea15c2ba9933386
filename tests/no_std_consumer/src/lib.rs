//! A `#![no_std]` crate using `linkage` without its `std` feature: a mechanism declared,
//! solved and tracked with no standard library and no allocator.

#![no_std]

use linkage::{arc_length, Mechanism, Options, Pose, Start, Tracker};

linkage::mechanism! {
    /// A 3-RPS.
    pub struct Rps;
    base {
        A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
        A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
        A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    }
    platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
    chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
}

/// Forward kinematics of the 3-RPS from its home pose; `None` on any failure.
pub fn solve(legs: [f64; 3]) -> Option<[f64; 9]> {
    let rps = Rps::new();
    let v0 = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
    let x0 = rps.inverse(&v0, &[0.0; 3]).ok()?;
    let start = Start::new(&rps, v0, x0).ok()?;
    let sol = arc_length(&rps, &start, &legs, &Options::TIGHT).ok()?;
    let mut tracker = Tracker::new(rps, start, Options::TIGHT);
    tracker.update(&legs).ok()?;
    sol.is_ok().then_some(sol.v)
}
