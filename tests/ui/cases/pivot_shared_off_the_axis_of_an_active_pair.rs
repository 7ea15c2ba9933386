// The quill's axis point Tz is declared on the tool (the platform), which the wrist's active
// R tilts about T -> Tx: Tz would move with the tool and stay with the wrist. (Before this was
// an error, the tool came out non-rigid and its pose wrong.)
linkage::mechanism! {
    pub struct ScaraWrist;
    base { O = [0.0, 0.0, 0.0], Oz = [0.0, 0.0, 1.0] }
    platform { T = [350.0, 0.0, -50.0], Tx = [360.0, 0.0, -50.0], Tz = [350.0, 0.0, -49.0], Q = [350.0, 30.0, -80.0] }
    link arm1 { E = [200.0, 0.0, 0.0], Ez = [200.0, 0.0, 1.0] }
    link arm2 { W = [350.0, 0.0, 0.0], Wz = [350.0, 0.0, 1.0] }
    link quill { K = [360.0, 0.0, -20.0] }
    link wrist { Kw = [350.0, 20.0, -50.0] }
    chain arm = base - R(active q1, axis = O -> Oz) - arm1 - R(active q2, axis = E -> Ez) - arm2
        - P(active d, axis = W -> Wz) - quill - R(active q4, axis = T -> Tz) - wrist
        - R(active q5, axis = T -> Tx) - platform;
}

fn main() {}
