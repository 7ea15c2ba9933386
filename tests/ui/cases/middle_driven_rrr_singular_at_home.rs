// A planar 3-RRR driven at its middle joints, declared with every leg's line A–G through the
// centre at home: with the middle joints held, each leg is a rigid body pinned at A, and the
// platform can turn about the centre — a singularity, found at compile time.
linkage::mechanism! {
    pub struct Planar;
    base { A1 = [200.0, 0.0, 0.0], A1z = [200.0, 0.0, 1.0], A2 = [-100.0, 173.2, 0.0], A2z = [-100.0, 173.2, 1.0], A3 = [-100.0, -173.2, 0.0], A3z = [-100.0, -173.2, 1.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]) { G1 = [40.0, 0.0, 0.0], G1z = [40.0, 0.0, 1.0], G2 = [-20.0, 34.64, 0.0], G2z = [-20.0, 34.64, 1.0], G3 = [-20.0, -34.64, 0.0], G3z = [-20.0, -34.64, 1.0] }
    link c1 { B1 = [150.0, 80.0, 0.0], B1z = [150.0, 80.0, 1.0] }
    link c2 { B2 = [-144.3, 89.9, 0.0], B2z = [-144.3, 89.9, 1.0] }
    link c3 { B3 = [-5.7, -169.9, 0.0], B3z = [-5.7, -169.9, 1.0] }
    link d1 {} link d2 {} link d3 {}
    chain l1 = base - R(passive, axis = A1 -> A1z) - c1 - R(active q1, axis = B1 -> B1z) - d1 - R(passive, axis = G1 -> G1z) - platform;
    chain l2 = base - R(passive, axis = A2 -> A2z) - c2 - R(active q2, axis = B2 -> B2z) - d2 - R(passive, axis = G2 -> G2z) - platform;
    chain l3 = base - R(passive, axis = A3 -> A3z) - c3 - R(active q3, axis = B3 -> B3z) - d3 - R(passive, axis = G3 -> G3z) - platform;
}

fn main() {}
