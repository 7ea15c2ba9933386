// One input cannot be a crank's angle on one pair and a slider's travel on another.
linkage::mechanism! {
    pub struct Mixed;
    base {
        A1 = [100.0, 0.0, 0.0], B1 = [100.0, 1.0, 0.0], A1z = [100.0, 0.0, 1.0],
        A2 = [-50.0, 86.6, 0.0], B2 = [-50.866, 86.1, 0.0],
        A3 = [-50.0, -86.6, 0.0], B3 = [-49.134, -87.1, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0]) { G1 = [50.0, 0.0, 0.0], G2 = [-25.0, 43.3, 0.0], G3 = [-25.0, -43.3, 0.0] }
    link crank1 { C1 = [150.0, 0.0, 0.0] }
    link slider1 { D1 = [100.0, 0.0, 20.0] }
    link crank2 { C2 = [-75.0, 129.9, 0.0] }
    link crank3 { C3 = [-75.0, -129.9, 0.0] }
    link rod1 { length = 158.1 } link rod1b { length = 141.4 } link rod2 { length = 158.1 } link rod3 { length = 158.1 }
    chain c1 = base - R(active shared q, axis = A1 -> B1) - crank1 - S(C1) - rod1 - S(G1) - platform;
    chain c1b = base - P(active shared q, axis = A1 -> A1z) - slider1 - S(D1) - rod1b - S(G1) - platform;
    chain c2 = base - R(active q2, axis = A2 -> B2) - crank2 - S(C2) - rod2 - S(G2) - platform;
    chain c3 = base - R(active q3, axis = A3 -> B3) - crank3 - S(C3) - rod3 - S(G3) - platform;
}

fn main() {}
