// A delta whose cranks are split in two per axis: `q1` drives both of the first pair, but
// only one says so.
linkage::mechanism! {
    pub struct Delta;
    params { rod = 256.12496949731394 }
    base {
        A1 = [100.0, 0.0, 0.0], B1 = [100.0, 1.0, 0.0],
        A2 = [-50.0, 86.6, 0.0], B2 = [-50.866, 86.1, 0.0],
        A3 = [-50.0, -86.6, 0.0], B3 = [-49.134, -87.1, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -200.0]) {
        F11 = [40.0, 30.0, 0.0], F12 = [40.0, -30.0, 0.0],
        F21 = [-45.98, 19.64, 0.0], F22 = [5.98, 49.64, 0.0],
        F31 = [5.98, -49.64, 0.0], F32 = [-45.98, -19.64, 0.0],
    }
    link arm11 { E11 = [200.0, 30.0, 0.0] }
    link arm12 { E12 = [200.0, -30.0, 0.0] }
    link arm2 { E21 = [-125.98, 158.21, 0.0], E22 = [-74.02, 188.21, 0.0] }
    link arm3 { E31 = [-74.02, -188.21, 0.0], E32 = [-125.98, -158.21, 0.0] }
    link rod11 { length = rod } link rod12 { length = rod }
    link rod21 { length = rod } link rod22 { length = rod }
    link rod31 { length = rod } link rod32 { length = rod }
    chain a11 = base - R(active shared q1, axis = A1 -> B1) - arm11 - S(E11) - rod11 - S(F11) - platform;
    chain a12 = base - R(active q1, axis = A1 -> B1) - arm12 - S(E12) - rod12 - S(F12) - platform;
    chain a2 = base - R(active q2, axis = A2 -> B2) - arm2 - S(E21) - rod21 - S(F21) - platform;
    chain a2b = arm2 - S(E22) - rod22 - S(F22) - platform;
    chain a3 = base - R(active q3, axis = A3 -> B3) - arm3 - S(E31) - rod31 - S(F31) - platform;
    chain a3b = arm3 - S(E32) - rod32 - S(F32) - platform;
}

fn main() {}
