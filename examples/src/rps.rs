//! A 3-RPS parallel manipulator: three legs hinged to the base by revolute pairs, extended by
//! active prismatic pairs, and joined to the platform by spherical pairs. Three degrees of
//! freedom: heave, roll and pitch (with parasitic motions).

use linkage::{Pose, SolveError, Start};

linkage::mechanism! {
    /// A 3-RPS with a 100 mm base triangle and a 50 mm platform triangle (circumradii); each
    /// hinge axis is tangent to the base circle so its leg swings in a radial plane.
    pub struct Rps3;

    base {
        A1 = [0.0, 100.0, 0.0],        B1 = [-10.0, 100.0, 0.0],
        A2 = [-86.603, -50.0, 0.0],    B2 = [-81.603, -58.660, 0.0],
        A3 = [86.603, -50.0, 0.0],     B3 = [91.603, -41.340, 0.0],
    }

    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0]) {
        G1 = [0.0, 50.0, 0.0],
        G2 = [-43.301, -25.0, 0.0],
        G3 = [43.301, -25.0, 0.0],
    }

    chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
}

/// The home pose: platform level, 150 mm above the base (the declaration's `home`).
pub fn home_pose() -> Pose {
    let [yaw, pitch, roll, x, y, z] = Rps3::HOME;
    Pose::from_euler(yaw, pitch, roll, [x, y, z])
}

/// The home configuration (legs ≈ 158.1 mm).
pub fn home_start(sys: &Rps3) -> Result<Start<9, 3>, SolveError> {
    sys.home_start()
}
