//! A start set as Rust source, to compute once and embed: `P0`, `GAMMA` and `STARTS`, read back
//! by [`AllModes::from_starts`](super::AllModes::from_starts), which checks every stored root
//! before it is used. Written through [`core::fmt::Write`], so no heap is needed.

use super::AllModes;
use super::complex::Complex;
use crate::mechanism::Mechanism;
use core::fmt::{self, Write};

impl<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize> AllModes<S, N, M, K> {
    /// Writes the start set as Rust source: the constants `P0: [Complex; M]`,
    /// `GAMMA: Complex` and `STARTS: [[Complex; N]; count]` (v at p₀), every number in the
    /// shortest form that reads back to the same `f64`, after a `//!` header naming `what`.
    /// Commit the file, `include!` or `mod` it, and build the solver with
    /// [`AllModes::from_starts`] — no monodromy at run time.
    ///
    /// ```
    /// use linkage::modes::{AllModes, ModesOptions};
    /// # linkage::mechanism! {
    /// #     pub struct Rps;
    /// #     base {
    /// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
    /// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
    /// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    /// #     }
    /// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
    /// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    /// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    /// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
    /// # }
    /// // Once, in a generator (a build step, an example you run by hand):
    /// let modes = AllModes::<Rps, 9, 3, 32>::new(Rps::new(), &ModesOptions::default()).unwrap();
    /// let mut source = String::new();
    /// modes.write_source(&mut source, "the 3-RPS").unwrap();
    /// assert!(source.contains("pub const STARTS: [[Complex; 9]; 16] = ["));
    /// // std::fs::write("src/rps_starts.rs", source) and commit it; then, at run time, with
    /// // `mod rps_starts;`:
    /// // AllModes::<Rps, 9, 3, 32>::from_starts(Rps::new(), rps_starts::P0, rps_starts::GAMMA,
    /// //     &rps_starts::STARTS, &ModesOptions::default())
    /// ```
    pub fn write_source(&self, out: &mut impl Write, what: &str) -> fmt::Result {
        fn c(out: &mut impl Write, indent: &str, z: &Complex) -> fmt::Result {
            writeln!(out, "{indent}Complex::new({:?}, {:?}),", z.re, z.im)
        }
        writeln!(
            out,
            "//! Start solutions for `linkage::modes`: {what}; v at the base point P0, γ = GAMMA."
        )?;
        writeln!(
            out,
            "//! Written by `AllModes::write_source`; read by `AllModes::from_starts`, which checks them.\n"
        )?;
        writeln!(out, "use linkage::modes::Complex;\n")?;
        writeln!(out, "pub const P0: [Complex; {M}] = [")?;
        for z in &self.p0 {
            c(out, "    ", z)?;
        }
        writeln!(out, "];\n")?;
        writeln!(
            out,
            "pub const GAMMA: Complex = Complex::new({:?}, {:?});\n",
            self.gamma.re, self.gamma.im
        )?;
        let n = self.start_count();
        writeln!(out, "pub const STARTS: [[Complex; {N}]; {n}] = [")?;
        for i in 0..n {
            writeln!(out, "    [")?;
            for z in self.start(i).iter().flatten() {
                c(out, "        ", z)?;
            }
            writeln!(out, "    ],")?;
        }
        writeln!(out, "];")
    }
}
