// A chain of one link and no pair.
linkage::mechanism! {
    pub struct Rps;
    base {
        A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
        A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
        A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0]) { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
    chain leg1 = base;
    chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
}

fn main() {}
