linkage::mechanism! {
    pub struct Bipod;
    base { A1 = [0.0, 100.0, 0.0], A2 = [0.0, -100.0, 0.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 100.0]) { P = [0.0, 0.0, 0.0] }
    chain leg1 = base - S(A1) - P(active L1) - S(P) - platform;
    chain leg2 = base - S(A2) - P(active L2) - S(P) - platform;
}

fn main() {}
