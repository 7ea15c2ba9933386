//! Each solver entry point of `linkage`, wrapped in a function marked `#[no_panic]` for two
//! mechanisms (a 3-RPS and the 18-unknown Stewart platform of the paper): if any panic path
//! (an index out of bounds, an `unwrap`, an assertion, a `clamp` with a NaN bound) survives
//! the optimiser in one of them, linking `src/main.rs` fails and names the function. The
//! runtime's promise is that bad input is a typed error, never a panic; this checks it for
//! every input at once, not for the inputs a test happens to try.
//!
//! ```text
//! cargo run --release --manifest-path tests/no_panic/Cargo.toml
//! ```

#![no_std]

use linkage::{
    arc_length, arc_length_detour, certify, newton_homotopy, newton_raphson, Certificate,
    CertifyError, Detoured, Options, Solution, SolveError, Start, TrackError, Tracker,
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

linkage::mechanism! {
    /// Gao & Wu's Stewart platform (Table III).
    pub struct Stewart;
    base {
        D1 = [200.764, 53.795, 0.0], D2 = [169.706, 0.0, 0.0], D3 = [0.0, 0.0, 0.0],
        D4 = [-31.058, 53.795, 0.0], D5 = [53.795, 200.764, 0.0], D6 = [115.911, 200.764, 0.0],
    }
    platform(frame = [G1, G3, G5], form = coplanar, home = [0.0, 0.0, 0.0, 58.971, -11.739, 159.011]) {
        G1 = [122.475, 122.475, 0.0], G2 = [51.764, 0.0, 0.0], G3 = [0.0, 0.0, 0.0],
        G4 = [-70.711, 122.475, 0.0], G5 = [-44.829, 167.303, 0.0], G6 = [96.593, 167.303, 0.0],
    }
    chain leg1 = base - S(D1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - S(D2) - P(active L2) - S(G2) - platform;
    chain leg3 = base - S(D3) - P(active L3) - S(G3) - platform;
    chain leg4 = base - S(D4) - P(active L4) - S(G4) - platform;
    chain leg5 = base - S(D5) - P(active L5) - S(G5) - platform;
    chain leg6 = base - S(D6) - P(active L6) - S(G6) - platform;
}

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
        }
    };
}

proven!(rps, Rps, 9, 3);
proven!(stewart, Stewart, 18, 6);
