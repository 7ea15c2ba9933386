// One mistake in the declaration, one error: the program's uses of `Rps` (its constructor, its
// listing, the solvers over it) add none of their own.
use linkage::{arc_length, Options, Pose, Start};

linkage::mechanism! {
    pub struct Rps;
    base {
        A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
        A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
        A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    }
    platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
    chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3);
}

mod elsewhere {
    pub fn listing() -> &'static str {
        super::Rps::LISTING
    }
}

fn main() {
    println!("{}", elsewhere::listing());
    let rps = Rps::new();
    let home = Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]);
    let v0 = linkage::unknowns_from_pose(&rps, &home);
    let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
    let start = Start::new(&rps, v0, x0).unwrap();
    let sol = arc_length(&rps, &start, &[165.0, 150.0, 160.0], &Options::TIGHT).unwrap();
    println!("{:?}", sol.status);
}
