//! Each solver entry point of `linkage`, wrapped in a function marked `#[no_panic]` for five
//! mechanisms (a 3-RPS, the 18-unknown Stewart platform of the paper, a 6-RSS rotary hexapod,
//! whose crank angles enter through sin and cos, an Exechon tripod: overconstrained, 36
//! unknowns, symmetry candidates for the all-modes query; and a planar five-bar whose platform
//! is a point, 3 unknowns and 2 inputs): if any panic path
//! (an index out of bounds, an `unwrap`, an assertion, a `clamp` with a NaN bound) survives
//! the optimiser in one of them, linking `src/main.rs` fails and names the function. The
//! runtime's promise is that bad input is a typed error, never a panic; this checks it for
//! every input at once, not for the inputs a test happens to try. The same for every call of
//! the C interface (`linkage-ffi`), where a panic would abort LinuxCNC's motion controller.
//!
//! Every wrapper must be called from `main`: one the binary never calls is dropped before
//! linking, and proves nothing.
//!
//! ```text
//! cargo run --release --manifest-path tests/no_panic/Cargo.toml
//! ```

#![no_std]

use linkage::velocity::{self, VelocityError};
use linkage::{
    arc_length, arc_length_detour, certify, newton_homotopy, newton_raphson, Certificate,
    CertifyError, Detoured, NewtonRaphson, Options, Solution, SolveError, Start, TrackError,
    Tracker,
};
use no_panic::no_panic;

linkage::mechanism! {
    /// A 3-RPS.
    pub struct Rps;
    base {
        A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
        A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
        A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    }
    platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
    chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
}

// The Stewart platform of the paper (Table III) and a 6-RSS rotary hexapod, whose crank angles
// enter through sin and cos: the crates the examples and the C interface use, as they are.
pub use linkage_rss_hexapod::RssHexapod;
pub use linkage_stewart::Stewart;

/// The entry points for one mechanism type, each in a `#[no_panic]` function.
macro_rules! proven {
    ($module:ident, $sys:ty, $n:literal, $m:literal) => {
        pub mod $module {
            use super::*;

            #[no_panic]
            pub fn start(
                sys: &$sys,
                v: [f64; $n],
                x: [f64; $m],
            ) -> Result<Start<$n, $m>, SolveError> {
                Start::new(sys, v, x)
            }

            #[no_panic]
            pub fn nr(
                sys: &$sys,
                s: &Start<$n, $m>,
                x: &[f64; $m],
                o: &Options,
            ) -> Result<Solution<$n>, SolveError> {
                newton_raphson(sys, s, x, o)
            }

            /// Newton–Raphson prepared for one start (B factored there once where it serves
            /// every target).
            #[no_panic]
            pub fn nr_prepared(
                nr: &NewtonRaphson<$sys, $n, $m>,
                x: &[f64; $m],
                o: &Options,
            ) -> Result<Solution<$n>, SolveError> {
                nr.solve(x, o)
            }

            #[no_panic]
            pub fn nh(
                sys: &$sys,
                s: &Start<$n, $m>,
                x: &[f64; $m],
                o: &Options,
            ) -> Result<Solution<$n>, SolveError> {
                newton_homotopy(sys, s, x, o)
            }

            #[no_panic]
            pub fn ph(
                sys: &$sys,
                s: &Start<$n, $m>,
                x: &[f64; $m],
                o: &Options,
            ) -> Result<Solution<$n>, SolveError> {
                arc_length(sys, s, x, o)
            }

            #[no_panic]
            pub fn detour(
                sys: &$sys,
                s: &Start<$n, $m>,
                x: &[f64; $m],
                o: &Options,
            ) -> Result<Detoured<$n, $m>, SolveError> {
                arc_length_detour(sys, s, x, o)
            }

            #[no_panic]
            pub fn proof(
                sys: &$sys,
                v: &[f64; $n],
                x: &[f64; $m],
            ) -> Result<Certificate<$n>, CertifyError> {
                certify(sys, v, x)
            }

            #[no_panic]
            pub fn track(
                t: &mut Tracker<$sys, $n, $m>,
                x: &[f64; $m],
            ) -> Result<[f64; $n], TrackError> {
                t.update(x).map(|s| s.v)
            }

            /// Velocity kinematics: the platform's twist for input rates, then the input
            /// rates back from it (every function of `linkage::velocity` on the way).
            #[no_panic]
            pub fn rates(
                sys: &$sys,
                v: &[f64; $n],
                x: &[f64; $m],
                xdot: &[f64; $m],
            ) -> Result<[f64; $m], VelocityError> {
                let t = velocity::twist(sys, v, x, xdot)?;
                velocity::input_rates(sys, v, x, &t).map(|r| r.rates)
            }

            /// Statics: the actuator efforts of a load on the platform.
            #[no_panic]
            pub fn efforts(
                sys: &$sys,
                v: &[f64; $n],
                x: &[f64; $m],
                load: &velocity::Wrench,
            ) -> Result<[f64; $m], VelocityError> {
                velocity::input_efforts(sys, v, x, load)
            }
        }
    };
}

proven!(rps, Rps, 9, 3);
proven!(stewart, Stewart, 18, 6);
proven!(hexapod, RssHexapod, 18, 6);

/// A SCARA with a wrist that tilts the tool: its chain has no closed-form inverse, so
/// `inverse` is the numerical one (`linkage`'s inverse.rs and inverse/).
pub use linkage_serial_arms::ScaraWrist;

linkage::mechanism! {
    /// A 3-RRS: no closed-form inverse either, and equations on its platform's points alone
    /// (their distances), which the numerical inverse checks before its search.
    pub struct Rrs;
    params { rb = 200.0, rc = 100.0, rp = 100.0, c2 = cos(2.0 * pi / 3.0), s2 = sin(2.0 * pi / 3.0) }
    base {
        A1 = [rb, 0.0, 0.0], B1 = [rb, 1.0, 0.0],
        A2 = [rb * c2, rb * s2, 0.0], B2 = [rb * c2 - s2, rb * s2 + c2, 0.0],
        A3 = [rb * c2, -rb * s2, 0.0], B3 = [rb * c2 + s2, -rb * s2 + c2, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0]) {
        G1 = [rp, 0.0, 0.0], G2 = [rp * c2, rp * s2, 0.0], G3 = [rp * c2, -rp * s2, 0.0],
    }
    link crank1 { C1 = [rb - rc, 0.0, 0.0], D1 = [rb - rc, 1.0, 0.0] }
    link crank2 { C2 = [(rb - rc) * c2, (rb - rc) * s2, 0.0], D2 = [(rb - rc) * c2 - s2, (rb - rc) * s2 + c2, 0.0] }
    link crank3 { C3 = [(rb - rc) * c2, -(rb - rc) * s2, 0.0], D3 = [(rb - rc) * c2 + s2, -(rb - rc) * s2 + c2, 0.0] }
    link leg1 { } link leg2 { } link leg3 { }
    chain c1 = base - R(active q1, axis = A1 -> B1) - crank1 - R(passive, axis = C1 -> D1) - leg1 - S(G1) - platform;
    chain c2 = base - R(active q2, axis = A2 -> B2) - crank2 - R(passive, axis = C2 -> D2) - leg2 - S(G2) - platform;
    chain c3 = base - R(active q3, axis = A3 -> B3) - crank3 - R(passive, axis = C3 -> D3) - leg3 - S(G3) - platform;
}

/// Inverse kinematics: the closed forms (the 3-RPS's legs, the Stewart platform's, the
/// hexapod's cranks) and the numerical inverse (the SCARA with a wrist, the 3-RRS).
pub mod inverse {
    use super::*;
    use linkage::{InverseError, Mechanism};

    #[no_panic]
    pub fn rps(sys: &Rps, v: &[f64; 9], x0: &[f64; 3]) -> Result<[f64; 3], InverseError> {
        sys.inverse(v, x0)
    }

    #[no_panic]
    pub fn stewart(sys: &Stewart, v: &[f64; 18], x0: &[f64; 6]) -> Result<[f64; 6], InverseError> {
        sys.inverse(v, x0)
    }

    #[no_panic]
    pub fn hexapod(
        sys: &RssHexapod,
        v: &[f64; 18],
        x0: &[f64; 6],
    ) -> Result<[f64; 6], InverseError> {
        sys.inverse(v, x0)
    }

    #[no_panic]
    pub fn rrs<const N: usize>(
        sys: &Rrs,
        v: &[f64; N],
        x0: &[f64; 3],
    ) -> Result<[f64; 3], InverseError>
    where
        Rrs: Mechanism<N, 3>,
    {
        sys.inverse(v, x0)
    }

    /// The inverse for a platform that is a single point.
    #[no_panic]
    pub fn five_bar(sys: &FiveBar, v: &[f64; 3], x0: &[f64; 2]) -> Result<[f64; 2], InverseError> {
        sys.inverse(v, x0)
    }

    /// The numerical inverse of an overconstrained mechanism (36 unknowns, three inputs).
    #[no_panic]
    pub fn exechon(sys: &Exechon, v: &[f64; 36], x0: &[f64; 3]) -> Result<[f64; 3], InverseError> {
        sys.inverse(v, x0)
    }

    #[no_panic]
    pub fn scara_wrist<const N: usize>(
        sys: &ScaraWrist,
        v: &[f64; N],
        x0: &[f64; 5],
    ) -> Result<[f64; 5], InverseError>
    where
        ScaraWrist: Mechanism<N, 5>,
    {
        sys.inverse(v, x0)
    }
}

/// The all-modes query ([`AllModes::solve`](linkage::modes::AllModes::solve): every path from
/// the start set to the target, the refills of failed paths, the real roots' refinement), each
/// mechanism with the capacity its root count needs.
pub mod modes {
    use super::*;
    use linkage::modes::{AllModes, Complex, ModesError, ModesOptions, Roots};

    #[no_panic]
    pub fn rps(
        m: &AllModes<Rps, 9, 3, 32>,
        x: &[f64; 3],
        out: &mut Roots<9, 32>,
    ) -> Result<(), ModesError> {
        m.solve(x, out)
    }

    /// The start set by monodromy ([`AllModes::new`]): seeding, the loops, the symmetries'
    /// images, the sparse factorisation's plan.
    #[no_panic]
    pub fn rps_new(
        sys: Rps,
        options: &ModesOptions,
    ) -> Result<AllModes<Rps, 9, 3, 32>, ModesError> {
        AllModes::new(sys, options)
    }

    /// Start solutions stored before ([`AllModes::from_starts`]), checked and refined.
    #[no_panic]
    pub fn rps_from_starts(
        sys: Rps,
        p0: [Complex; 3],
        gamma: Complex,
        starts: &[[Complex; 9]],
        options: &ModesOptions,
    ) -> Result<AllModes<Rps, 9, 3, 32>, ModesError> {
        AllModes::from_starts(sys, p0, gamma, starts, options)
    }

    /// The start set moved near given inputs ([`AllModes::recenter`]).
    #[no_panic]
    pub fn rps_recenter(
        m: &mut AllModes<Rps, 9, 3, 32>,
        center: &[f64; 3],
        spread: f64,
        seed: u64,
    ) -> Result<(), ModesError> {
        m.recenter(center, spread, seed)
    }

    #[no_panic]
    pub fn stewart_new(
        sys: Stewart,
        options: &ModesOptions,
    ) -> Result<AllModes<Stewart, 18, 6, 64>, ModesError> {
        AllModes::new(sys, options)
    }

    #[no_panic]
    pub fn hexapod_new(
        sys: RssHexapod,
        options: &ModesOptions,
    ) -> Result<AllModes<RssHexapod, 18, 6, 64>, ModesError> {
        AllModes::new(sys, options)
    }

    #[no_panic]
    pub fn stewart(
        m: &AllModes<Stewart, 18, 6, 64>,
        x: &[f64; 6],
        out: &mut Roots<18, 64>,
    ) -> Result<(), ModesError> {
        m.solve(x, out)
    }

    #[no_panic]
    pub fn hexapod(
        m: &AllModes<RssHexapod, 18, 6, 64>,
        x: &[f64; 6],
        out: &mut Roots<18, 64>,
    ) -> Result<(), ModesError> {
        m.solve(x, out)
    }

    #[no_panic]
    pub fn five_bar_new(
        sys: FiveBar,
        options: &ModesOptions,
    ) -> Result<AllModes<FiveBar, 3, 2, 8>, ModesError> {
        AllModes::new(sys, options)
    }

    #[no_panic]
    pub fn five_bar(
        m: &AllModes<FiveBar, 3, 2, 8>,
        x: &[f64; 2],
        out: &mut Roots<3, 8>,
    ) -> Result<(), ModesError> {
        m.solve(x, out)
    }

    #[no_panic]
    pub fn exechon_new(
        sys: Exechon,
        options: &ModesOptions,
    ) -> Result<AllModes<Exechon, 36, 3, 64>, ModesError> {
        AllModes::new(sys, options)
    }

    #[no_panic]
    pub fn exechon(
        m: &AllModes<Exechon, 36, 3, 64>,
        x: &[f64; 3],
        out: &mut Roots<36, 64>,
    ) -> Result<(), ModesError> {
        m.solve(x, out)
    }
}

linkage::mechanism! {
    /// An Exechon tripod (two U-P-R legs and one S-P-R leg): overconstrained, 36 unknowns. Its
    /// all-modes query is also the largest instantiation of the sparse factorisation's plan
    /// built here at opt-level 3, which once kept LLVM busy for more than ten minutes.
    pub struct Exechon;
    base {
        A1 = [0.0, -300.0, 0.0], A1y = [0.0, -299.0, 0.0],
        A3 = [0.0, 300.0, 0.0], A3y = [0.0, 301.0, 0.0],
        A2 = [350.0, 0.0, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 700.0]) {
        B1 = [0.0, -150.0, 0.0], B1x = [1.0, -150.0, 0.0],
        B3 = [0.0, 150.0, 0.0], B3x = [1.0, 150.0, 0.0],
        B2 = [150.0, 0.0, 0.0], B2y = [150.0, 1.0, 0.0],
    }
    link cylinder2 { E2 = [350.0, 100.0, 0.0] }
    chain leg1 = base - U(A1, axis = A1 -> A1y) - P(active L1) - R(passive, axis = B1 -> B1x) - platform;
    chain leg2 = base - S(A2) - cylinder2 - P(active L2) - R(passive, axis = B2 -> B2y) - platform;
    chain leg3 = base - U(A3, axis = A3 -> A3y) - P(active L3) - R(passive, axis = B3 -> B3x) - platform;
}

proven!(exechon, Exechon, 36, 3);

linkage::mechanism! {
    /// A planar five-bar declared in space, its platform a single point (no orientation): two
    /// cranks driven about vertical axes, two distal links meeting at the output point P.
    pub struct FiveBar;
    params { crank = 100.0, distal = 150.0 }
    base { A1 = [-40.0, 0.0, 0.0], A1z = [-40.0, 0.0, 1.0], A2 = [40.0, 0.0, 0.0], A2z = [40.0, 0.0, 1.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, crank * sin(pi / 3.0) + 120.0, 0.0]) { P = [0.0, 0.0, 0.0] }
    link crank1 { C1 = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C1z = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link crank2 { C2 = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C2z = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link distal1 { }
    link distal2 { }
    chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - R(passive, axis = C1 -> C1z) - distal1 - S(P) - platform;
    chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - R(passive, axis = C2 -> C2z) - distal2 - S(P) - platform;
}

proven!(five_bar, FiveBar, 3, 2);

/// The C interface's calls (`linkage-ffi`, which LinuxCNC's kinematics module links), each in
/// a `#[no_panic]` function. They wrap the Rust-ABI functions the `extern "C"` symbols
/// forward to, not the symbols: a panic cannot unwind out of an `extern "C"` function (it
/// aborts), so the optimiser takes a call to one as panic-free and wrapping it proves nothing.
pub mod ffi {
    use core::ffi::c_char;
    use core::mem::MaybeUninit;

    use linkage_ffi::{
        calls, Hexapod, LinkageGeometry, LinkagePose, LinkageReport, LinkageStrutCorrection,
    };
    use no_panic::no_panic;

    #[no_panic]
    pub fn size() -> usize {
        calls::size()
    }

    #[no_panic]
    pub fn init(s: Option<&mut MaybeUninit<Hexapod>>, g: Option<&LinkageGeometry>) -> i32 {
        calls::init(s, g)
    }

    #[no_panic]
    pub fn set_geometry(h: Option<&mut Hexapod>, g: Option<&LinkageGeometry>) -> i32 {
        calls::set_geometry(h, g)
    }

    #[no_panic]
    pub fn set_options(h: Option<&mut Hexapod>, tolerance: f64, max_iterations: u32) -> i32 {
        calls::set_options(h, tolerance, max_iterations)
    }

    #[no_panic]
    pub fn set_strut_correction(
        h: Option<&mut Hexapod>,
        c: Option<&LinkageStrutCorrection>,
    ) -> i32 {
        calls::set_strut_correction(h, c)
    }

    #[no_panic]
    pub fn set_certify(h: Option<&mut Hexapod>, on: i32) -> i32 {
        calls::set_certify(h, on)
    }

    #[no_panic]
    pub fn reset(h: Option<&mut Hexapod>) -> i32 {
        calls::reset(h)
    }

    #[no_panic]
    pub fn is_tracking(h: Option<&Hexapod>) -> i32 {
        calls::is_tracking(h)
    }

    #[no_panic]
    pub fn inverse(
        h: Option<&Hexapod>,
        pose: Option<&LinkagePose>,
        legs: Option<&mut [f64; 6]>,
    ) -> i32 {
        calls::inverse(h, pose, legs)
    }

    #[no_panic]
    pub fn strut_corrections(
        h: Option<&Hexapod>,
        pose: Option<&LinkagePose>,
        out: Option<&mut [f64; 6]>,
    ) -> i32 {
        calls::strut_corrections(h, pose, out)
    }

    #[no_panic]
    pub fn forward(
        h: Option<&mut Hexapod>,
        legs: Option<&[f64; 6]>,
        pose: Option<&mut LinkagePose>,
        report: Option<&mut LinkageReport>,
    ) -> i32 {
        calls::forward(h, legs, pose, report)
    }

    #[no_panic]
    pub fn status_name(code: i32) -> *const c_char {
        calls::status_name(code)
    }
}
