// Pivot names are global: `C` on both cranks would leave an axis `C -> ...` ambiguous.
linkage::mechanism! {
    pub struct FiveBar;
    base { A1 = [-40.0, 0.0, 0.0], A1z = [-40.0, 0.0, 1.0], A2 = [40.0, 0.0, 0.0], A2z = [40.0, 0.0, 1.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, 170.0, 0.0]) { P = [0.0, 0.0, 0.0] }
    link crank1 { C = [-100.0, 80.0, 0.0], C1z = [-100.0, 80.0, 1.0] }
    link crank2 { C = [100.0, 80.0, 0.0], C2z = [100.0, 80.0, 1.0] }
    link distal1 { }
    link distal2 { }
    chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - R(passive, axis = C -> C1z) - distal1 - S(P) - platform;
    chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - R(passive, axis = C -> C2z) - distal2 - S(P) - platform;
}

fn main() {}
