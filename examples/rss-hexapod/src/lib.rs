//! A 6-RSS rotary hexapod: six motors on the base turn cranks (active revolute pairs), and
//! rods with spherical joints at both ends carry the platform.
//!
//! Shared by the examples, the benchmarks and the link-time no-panic proof; `no_std`, so that
//! the proof needs nothing beyond the runtime.

#![no_std]

use linkage::{Pose, SolveError, Start};

linkage::mechanism! {
    /// A rotary hexapod with 40 mm cranks and 171 mm rods. Motor axes are tangent to a
    /// 100 mm circle; at zero crank angles the cranks point radially outwards.
    pub struct RssHexapod;

    params { rod = 170.986 }

    base {
        A1 = [93.969, -34.202, 0.0],   B1 = [87.129, -52.996, 0.0],
        A2 = [93.969, 34.202, 0.0],    B2 = [87.129, 52.996, 0.0],
        A3 = [-17.365, 98.481, 0.0],   B3 = [2.331, 101.954, 0.0],
        A4 = [-76.604, 64.279, 0.0],   B4 = [-89.46, 48.958, 0.0],
        A5 = [-76.604, -64.279, 0.0],  B5 = [-89.46, -48.958, 0.0],
        A6 = [-17.365, -98.481, 0.0],  B6 = [2.331, -101.954, 0.0],
    }

    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0]) {
        G1 = [49.497, -49.497, 0.0],
        G2 = [49.497, 49.497, 0.0],
        G3 = [18.117, 67.615, 0.0],
        G4 = [-67.615, 18.117, 0.0],
        G5 = [-67.615, -18.117, 0.0],
        G6 = [18.117, -67.615, 0.0],
    }

    link crank1 { C1 = [131.557, -47.883, 0.0] }
    link crank2 { C2 = [131.557, 47.883, 0.0] }
    link crank3 { C3 = [-24.311, 137.873, 0.0] }
    link crank4 { C4 = [-107.246, 89.99, 0.0] }
    link crank5 { C5 = [-107.246, -89.99, 0.0] }
    link crank6 { C6 = [-24.311, -137.873, 0.0] }
    link rod1 { length = rod }
    link rod2 { length = rod }
    link rod3 { length = rod }
    link rod4 { length = rod }
    link rod5 { length = rod }
    link rod6 { length = rod }

    chain arm1 = base - R(active q1, axis = A1 -> B1) - crank1 - S(C1) - rod1 - S(G1) - platform;
    chain arm2 = base - R(active q2, axis = A2 -> B2) - crank2 - S(C2) - rod2 - S(G2) - platform;
    chain arm3 = base - R(active q3, axis = A3 -> B3) - crank3 - S(C3) - rod3 - S(G3) - platform;
    chain arm4 = base - R(active q4, axis = A4 -> B4) - crank4 - S(C4) - rod4 - S(G4) - platform;
    chain arm5 = base - R(active q5, axis = A5 -> B5) - crank5 - S(C5) - rod5 - S(G5) - platform;
    chain arm6 = base - R(active q6, axis = A6 -> B6) - crank6 - S(C6) - rod6 - S(G6) - platform;
}

/// The home pose: platform level, 150 mm above the base (the declaration's `home`).
pub fn home_pose() -> Pose {
    let [yaw, pitch, roll, x, y, z] = RssHexapod::HOME;
    Pose::from_euler(yaw, pitch, roll, [x, y, z])
}

/// The home configuration, crank angles from inverse kinematics (near zero).
pub fn home_start(sys: &RssHexapod) -> Result<Start<18, 6>, SolveError> {
    sys.home_start()
}
