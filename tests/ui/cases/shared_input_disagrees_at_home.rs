// Two sliders on one rail share their input, but their offsets make it read 10 on one and
// 20 on the other at the declared configuration.
linkage::mechanism! {
    pub struct Sliders;
    base {
        A1 = [100.0, 0.0, 0.0], B1 = [100.0, 0.0, 1.0],
        A2 = [-50.0, 86.6, 0.0], B2 = [-50.0, 86.6, 1.0],
        A3 = [-50.0, -86.6, 0.0], B3 = [-50.0, -86.6, 1.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 250.0]) { G1 = [50.0, 0.0, 0.0], G2 = [-25.0, 43.3, 0.0], G3 = [-25.0, -43.3, 0.0], G4 = [60.0, 10.0, 0.0] }
    link slider1 { C1 = [100.0, 0.0, 100.0], D1 = [100.0, 1.0, 100.0] }
    link slider4 { C4 = [100.0, 10.0, 120.0], D4 = [100.0, 11.0, 120.0] }
    link slider2 { C2 = [-50.0, 86.6, 100.0], D2 = [-50.866, 86.1, 100.0] }
    link slider3 { C3 = [-50.0, -86.6, 100.0], D3 = [-49.134, -87.1, 100.0] }
    link leg1 { } link leg2 { } link leg3 { } link leg4 { }
    chain c1 = base - P(active shared s, axis = A1 -> B1, offset = 10.0) - slider1 - R(passive, axis = C1 -> D1) - leg1 - S(G1) - platform;
    chain c4 = base - P(active shared s, axis = A1 -> B1, offset = 20.0) - slider4 - R(passive, axis = C4 -> D4) - leg4 - S(G4) - platform;
    chain c2 = base - P(active s2, axis = A2 -> B2) - slider2 - R(passive, axis = C2 -> D2) - leg2 - S(G2) - platform;
    chain c3 = base - P(active s3, axis = A3 -> B3) - slider3 - R(passive, axis = C3 -> D3) - leg3 - S(G3) - platform;
}

fn main() {}
