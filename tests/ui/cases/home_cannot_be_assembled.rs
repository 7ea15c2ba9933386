linkage::mechanism! {
    pub struct Rss;
    base {
        A1 = [100.000, 0.000, 0.000], B1 = [100.000, 1.000, 0.000],
        A2 = [50.000, 86.603, 0.000], B2 = [49.134, 87.103, 0.000],
        A3 = [-50.000, 86.603, 0.000], B3 = [-50.866, 86.103, 0.000],
        A4 = [-100.000, 0.000, 0.000], B4 = [-100.000, -1.000, 0.000],
        A5 = [-50.000, -86.603, 0.000], B5 = [-49.134, -87.103, 0.000],
        A6 = [50.000, -86.603, 0.000], B6 = [50.866, -86.103, 0.000],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0]) {
        G1 = [50.000, 0.000, 0.000],
        G2 = [25.000, 43.301, 0.000],
        G3 = [-25.000, 43.301, 0.000],
        G4 = [-50.000, 0.000, 0.000],
        G5 = [-25.000, -43.301, 0.000],
        G6 = [25.000, -43.301, 0.000],
    }
    link crank1 { C1 = [150.000, 0.000, 0.000] }
    link rod1 { length = 100.0 }
    link crank2 { C2 = [75.000, 129.904, 0.000] }
    link rod2 { length = 180.0 }
    link crank3 { C3 = [-75.000, 129.904, 0.000] }
    link rod3 { length = 180.0 }
    link crank4 { C4 = [-150.000, 0.000, 0.000] }
    link rod4 { length = 180.0 }
    link crank5 { C5 = [-75.000, -129.904, 0.000] }
    link rod5 { length = 180.0 }
    link crank6 { C6 = [75.000, -129.904, 0.000] }
    link rod6 { length = 180.0 }
    chain leg1 = base - R(active q1, axis = A1 -> B1) - crank1 - S(C1) - rod1 - S(G1) - platform;
    chain leg2 = base - R(active q2, axis = A2 -> B2) - crank2 - S(C2) - rod2 - S(G2) - platform;
    chain leg3 = base - R(active q3, axis = A3 -> B3) - crank3 - S(C3) - rod3 - S(G3) - platform;
    chain leg4 = base - R(active q4, axis = A4 -> B4) - crank4 - S(C4) - rod4 - S(G4) - platform;
    chain leg5 = base - R(active q5, axis = A5 -> B5) - crank5 - S(C5) - rod5 - S(G5) - platform;
    chain leg6 = base - R(active q6, axis = A6 -> B6) - crank6 - S(C6) - rod6 - S(G6) - platform;
}

fn main() {}
