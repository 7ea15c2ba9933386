//! Serial arms, one chain each, whose inverse kinematics has no closed form, so that the
//! generated `inverse` is the numerical one: a pan-tilt head (R, R), a SCARA (R, R, a vertical
//! P, R) and the SCARA with a wrist that tilts the tool (R). Declared once, for the integration
//! tests (against the product of exponentials), the inverse's criterion benchmark and the
//! link-time no-panic proof.

#![no_std]

linkage::mechanism! {
    /// The tilt axis T→Tx is 50 above the base along the pan axis; Q is a camera point.
    pub struct PanTilt;
    base { O = [0.0, 0.0, 0.0], Oz = [0.0, 0.0, 1.0] }
    platform { T = [0.0, 0.0, 50.0], Tx = [10.0, 0.0, 50.0], Ty = [0.0, 10.0, 50.0], Q = [0.0, 50.0, 60.0] }
    link yoke { }
    chain head = base - R(active pan, axis = O -> Oz) - yoke - R(active tilt, axis = T -> Tx) - platform;
}

linkage::mechanism! {
    /// Shoulder at O, elbow at E (200 out), quill at W (350 out) sliding along +z, the tool
    /// turning about the quill's axis through T.
    pub struct Scara;
    base { O = [0.0, 0.0, 0.0], Oz = [0.0, 0.0, 1.0] }
    platform { T = [350.0, 0.0, -50.0], Tx = [360.0, 0.0, -50.0], Tz = [350.0, 0.0, -49.0] }
    link arm1 { E = [200.0, 0.0, 0.0], Ez = [200.0, 0.0, 1.0] }
    link arm2 { W = [350.0, 0.0, 0.0], Wz = [350.0, 0.0, 1.0] }
    // A pivot off the quill's axis, so that the quill's own turn (and with it the tool's
    // angle relative to it) is defined.
    link quill { K = [360.0, 0.0, -20.0] }
    chain arm = base - R(active q1, axis = O -> Oz) - arm1 - R(active q2, axis = E -> Ez) - arm2
        - P(active d, axis = W -> Wz) - quill - R(active q4, axis = T -> Tz) - platform;
}

linkage::mechanism! {
    /// The SCARA with a wrist: after the quill's turn, the tool tilts about T→Tx.
    pub struct ScaraWrist;
    base { O = [0.0, 0.0, 0.0], Oz = [0.0, 0.0, 1.0] }
    // The quill's axis point Tz is the quill's (the wrist shares it), not the tool's: the tool
    // tilts away from it.
    platform { T = [350.0, 0.0, -50.0], Tx = [360.0, 0.0, -50.0], Q = [350.0, 30.0, -80.0] }
    link arm1 { E = [200.0, 0.0, 0.0], Ez = [200.0, 0.0, 1.0] }
    link arm2 { W = [350.0, 0.0, 0.0], Wz = [350.0, 0.0, 1.0] }
    link quill { K = [360.0, 0.0, -20.0], Tz = [350.0, 0.0, -49.0] }
    link wrist { Kw = [350.0, 20.0, -50.0] }
    chain arm = base - R(active q1, axis = O -> Oz) - arm1 - R(active q2, axis = E -> Ez) - arm2
        - P(active d, axis = W -> Wz) - quill - R(active q4, axis = T -> Tz) - wrist
        - R(active q5, axis = T -> Tx) - platform;
}
