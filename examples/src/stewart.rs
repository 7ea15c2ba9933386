//! The general 6-6 Stewart platform of Gao & Wu (2015), Table III: six S–P–S legs.

use linkage::{Mechanism, Pose, SolveError, Start};

linkage::mechanism! {
    /// Gao & Wu's Stewart platform (Table III), in the coplanar form of Eq. 16: its system is
    /// Eq. 19 (with the distance rows squared, see ERRATA.md).
    pub struct Stewart;

    base {
        D1 = [200.764, 53.795, 0.0],
        D2 = [169.706, 0.0, 0.0],
        D3 = [0.0, 0.0, 0.0],
        D4 = [-31.058, 53.795, 0.0],
        D5 = [53.795, 200.764, 0.0],
        D6 = [115.911, 200.764, 0.0],
    }

    platform(frame = [G1, G3, G5]) {
        G1 = [122.475, 122.475, 0.0],
        G2 = [51.764, 0.0, 0.0],
        G3 = [0.0, 0.0, 0.0],
        G4 = [-70.711, 122.475, 0.0],
        G5 = [-44.829, 167.303, 0.0],
        G6 = [96.593, 167.303, 0.0],
    }

    chain leg1 = base - S(D1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - S(D2) - P(active L2) - S(G2) - platform;
    chain leg3 = base - S(D3) - P(active L3) - S(G3) - platform;
    chain leg4 = base - S(D4) - P(active L4) - S(G4) - platform;
    chain leg5 = base - S(D5) - P(active L5) - S(G5) - platform;
    chain leg6 = base - S(D6) - P(active L6) - S(G6) - platform;
}

/// The paper's initial configuration: all legs 170 mm.
pub const HOME_LEGS: [f64; 6] = [170.0; 6];

/// The home assembly mode: no rotation, platform above the base (see ERRATA.md's check value).
pub const HOME_POSE: [f64; 6] = [0.0, 0.0, 0.0, 58.971, -11.739, 159.011];

/// The start configuration for the home legs, refined from the approximate home pose.
pub fn home_start(sys: &Stewart) -> Result<Start<18, 6>, SolveError> {
    let [yaw, pitch, roll, x, y, z] = HOME_POSE;
    let pose = Pose::from_euler(yaw, pitch, roll, [x, y, z]);
    let v = linkage::unknowns_from_pose(sys, &pose);
    Start::new(sys, v, HOME_LEGS)
}

/// Leg lengths for a platform pose (Appendix B, Eqs. A1–A3).
pub fn legs_for_pose(sys: &Stewart, pose: &Pose) -> Option<([f64; 6], [f64; 18])> {
    let v = linkage::unknowns_from_pose(sys, pose);
    sys.inverse(&v, &HOME_LEGS).ok().map(|x| (x, v))
}
