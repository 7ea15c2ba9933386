linkage::mechanism! {
    pub struct Arm;
    base { A = [0.0, 0.0, 0.0], B = [0.0, 1.0, 0.0] }
    platform { P = [100.0, 0.0, 150.0] }
    link crank { C = [100.0, 0.0, 0.0] }
    link rod { length = -150.0 }
    chain arm = base - R(active q, axis = A -> B) - crank - S(C) - rod - S(P) - platform;
}

fn main() {}
