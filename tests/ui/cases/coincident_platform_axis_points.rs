linkage::mechanism! {
    pub struct PlanarRpr;
    base {
        A1 = [200.0, 0.0, 0.0], A1z = [200.0, 0.0, 1.0],
        A2 = [-100.0, 173.2, 0.0], A2z = [-100.0, 173.2, 1.0],
        A3 = [-100.0, -173.2, 0.0], A3z = [-100.0, -173.2, 1.0],
    }
    platform(home = [0.3, 0.0, 0.0, 10.0, 5.0, 0.0]) {
        G1 = [60.0, 0.0, 0.0], G1z = [60.0, 0.0, 1.0],
        G2 = [-30.0, 51.96, 0.0], G2z = [-30.0, 51.96, 1.0],
        G3 = [-30.0, -51.96, 0.0], G3z = [-30.0, -51.96, 0.0],
    }
    chain leg1 = base - R(passive, axis = A1 -> A1z) - P(active L1) - R(passive, axis = G1 -> G1z) - platform;
    chain leg2 = base - R(passive, axis = A2 -> A2z) - P(active L2) - R(passive, axis = G2 -> G2z) - platform;
    chain leg3 = base - R(passive, axis = A3 -> A3z) - P(active L3) - R(passive, axis = G3 -> G3z) - platform;
}

fn main() {}
