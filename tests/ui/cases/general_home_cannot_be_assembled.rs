linkage::mechanism! {
    pub struct Arm;
    base { A1 = [-40.0, 0.0, 0.0], A1z = [-40.0, 0.0, 1.0], A2 = [40.0, 0.0, 0.0], A2z = [40.0, 0.0, 1.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, 150.0, 0.0]) { P = [0.0, 0.0, 0.0] }
    link crank1 { C1 = [-90.0, 86.6, 0.0] }
    link crank2 { C2 = [90.0, 86.6, 0.0] }
    link rod1 { length = 300.0 }
    link rod2 { length = 300.0 }
    chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - S(C1) - rod1 - S(P) - platform;
    chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - S(C2) - rod2 - S(P) - platform;
}

fn main() {}
