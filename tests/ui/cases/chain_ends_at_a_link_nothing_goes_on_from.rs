// The rocker's chain ends at `coupler`, but no chain passes through the coupler or begins at
// it: nothing joins it to the platform.
linkage::mechanism! {
    pub struct FourBar;
    base { A = [0.0, 0.0, 0.0], Az = [0.0, 0.0, 1.0], D = [100.0, 0.0, 0.0], Dz = [100.0, 0.0, 1.0] }
    platform { P = [60.0, 80.0, 0.0] }
    link crank { B = [0.0, 40.0, 0.0], Bz = [0.0, 40.0, 1.0] }
    link rocker { C = [100.0, 60.0, 0.0], Cz = [100.0, 60.0, 1.0] }
    link coupler { }
    chain driven = base - R(active q, axis = A -> Az) - crank - R(passive, axis = B -> Bz) - S(P) - platform;
    chain follower = base - R(passive, axis = D -> Dz) - rocker - R(passive, axis = C -> Cz) - coupler;
}

fn main() {}
