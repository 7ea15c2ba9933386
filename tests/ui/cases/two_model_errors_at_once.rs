// Two independent mistakes that only the model finds (each a U whose first axis is on neither
// of the links it joins, in two legs): both are reported in one build, not the first alone.
linkage::mechanism! {
    pub struct Upu;
    base {
        A1 = [150.0, 0.0, 0.0], A1a = [150.0, 1.0, 0.0],
        A2 = [-75.0, 129.9, 0.0], A2a = [-75.866, 129.4, 0.0],
        A3 = [-75.0, -129.9, 0.0], A3a = [-74.134, -130.4, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 200.0]) {
        G1 = [60.0, 0.0, 0.0], G1a = [60.0, 1.0, 0.0],
        G2 = [-30.0, 51.96, 0.0], G2a = [-30.866, 51.46, 0.0],
        G3 = [-30.0, -51.96, 0.0], G3a = [-29.134, -52.46, 0.0],
    }
    chain leg1 = base - U(A1, axis = A1 -> A1a) - P(active L1) - U(G1, axis = A1 -> A1a) - platform;
    chain leg2 = base - U(A2, axis = A2 -> A2a) - P(active L2) - U(G2, axis = G2 -> G2a) - platform;
    chain leg3 = base - U(A3, axis = G3 -> G3a) - P(active L3) - U(G3, axis = G3 -> G3a) - platform;
}

fn main() {}
