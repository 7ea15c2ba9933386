//! Start solutions found as the conjugates of roots at a real parameter point.
//!
//! The equations have real coefficients, so at real inputs the complex conjugate of a root is
//! a root. Over the complex numbers the solutions can split into several irreducible
//! components, and a component that is not real comes with its conjugate component. Monodromy
//! loops never leave a component, and fresh seeds land on a small one seldom: the RCCC's model
//! settled on 3 starts, its two real modes and one complex root about 5 000 mm out, whose
//! conjugate — the fourth root — no loop or seed reached. So every known start is tracked to a
//! real point; where the root it reaches is not real, its conjugate is tracked back, and if that
//! comes back as a start not yet known it is one (with its orbit under the symmetries), and the
//! loops then carry it.
//!
//! Where the starts are already closed under conjugation this finds nothing and costs about two
//! paths per start: the conjugate of a pair's member is the other member, whose path back ends
//! on a known start.

use super::complex::Complex;
use super::found::{Found, carry};
use super::inputs::Inputs;
use super::path::ParameterPath;
use super::polish::{SAME, contains, polish};
use super::rng::Rng;
use super::symmetry::Symmetries;
use super::track::{Model, Outcome, Settings, Workspace};
use crate::mechanism::Mechanism;

/// The real point's distance from the home inputs: this many times the scale for a length,
/// this many radians for an angle (random in direction). Near home the real roots are the
/// mechanism's own modes; off it by a little, the point is generic (a symmetric design's home
/// can have roots that meet).
const FROM_HOME: f64 = 0.05;

/// The seed of the real points' random numbers (with the count of known starts).
const STREAM: u64 = 0xC0_4A_06_A7;

/// A real parameter point: near the home inputs where the mechanism has a home, otherwise the
/// real part of a random point of the loops' size.
fn real_point<S: Mechanism<N, M>, const N: usize, const M: usize>(
    model: &Model<'_, S, N>,
    inputs: &Inputs<M>,
    size: f64,
    rng: &mut Rng,
) -> [Complex; M] {
    let home = model
        .sys
        .home_configuration()
        .map(|(_, x)| x)
        .filter(|x| x.iter().all(|c| c.is_finite()));
    match home {
        Some(x) => core::array::from_fn(|j| {
            Complex::real(x[j] + FROM_HOME * inputs.unit(j) * rng.complex_normal().re)
        }),
        None => inputs.random(rng, size, 0.0).map(|c| Complex::real(c.re)),
    }
}

/// Tracks the known starts `out[..found.count]` from `p0` to a real point; each root reached
/// there that is not its own conjugate has its conjugate tracked back to `p0` and added if new
/// (see the module docs). `true` if a start was added.
#[allow(clippy::too_many_arguments)]
pub(super) fn conjugates<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize>(
    model: &Model<'_, S, N>,
    inputs: &Inputs<M>,
    p0: &[Complex; M],
    size: f64,
    sym: &Symmetries,
    out: &mut [[Complex; N]; K],
    orbit: &mut [usize; K],
    found: &mut Found,
    ws: &mut Workspace<N>,
) -> bool {
    // Its own random numbers: monodromy's stream, and so every start set that conjugation
    // does not change, stays as it was.
    let mut rng = Rng::new(STREAM ^ found.count as u64);
    let real = real_point(model, inputs, size, &mut rng);
    let there = ParameterPath::new(*p0, real, Complex::ONE);
    let mut new = false;
    // The starts added here are conjugates already: only the ones known before are carried.
    let known = found.count;
    for i in 0..known {
        // i < count ≤ K: `get` only spells that out for the no-panic proof.
        let Some(mut z) = out.get(i).copied() else {
            break;
        };
        let reached = model.track(&there, &mut z, ws, &Settings::DEFAULT).outcome
            == Outcome::Reached
            && polish(model, &mut z, &real, ws, true);
        if !reached {
            found.failed_paths += 1;
            continue;
        }
        let v = model.leave(&z);
        if !v.iter().all(|c| c.is_finite()) {
            continue;
        }
        let conjugate = v.map(Complex::conj);
        if contains(model, &[z], &model.enter(&conjugate), SAME) {
            // A real root: its own conjugate.
            continue;
        }
        new |= carry(model, ws, (conjugate, real), p0, sym, out, orbit, found);
        if found.overflow {
            break;
        }
    }
    new
}
