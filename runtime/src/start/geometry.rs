//! A start carried along a change of geometry ([`Start::follow_geometry`]): the mechanism
//! built part of the way from the geometry a configuration solves to the new one, and the
//! configuration followed on its branch, at fixed inputs, as the geometry moves.

use super::Start;
use super::path::{MAX_STEPS, MIN_STEP, PATH_TOLERANCE, correct};
use crate::correction::correction;
use crate::math::{norm, scale_or_one, size};
use crate::mechanism::Mechanism;
use crate::solution::SolveError;

impl<const N: usize, const M: usize> Start<N, M> {
    /// A configuration `v` at inputs `x` of the mechanism as it was (`along(0.0)` builds it)
    /// carried to `sys` as it is now, along the change of geometry itself: `along(s)` builds
    /// the mechanism a share `s` of the way (0 < s < 1; the generated mechanisms'
    /// `from_geometry` with every value moved that share, as their `follow_from` and
    /// `home_start` do), and the configuration is followed from s = 0 to s = 1 with det B of
    /// its sign at `v` all along and the corrector trusted only where it contracts. The start
    /// found is where the machine's configuration goes as its dimensions change: on `v`'s
    /// branch, never one reached across a singularity.
    ///
    /// [`Start::follow`] needs only the new mechanism, but follows the residual, not the
    /// machine: where a change of geometry turns det B at `v` (a configuration near a
    /// singularity of the new geometry), it keeps the sign of the new det B at `v`, which is
    /// not the old branch's. Use this where the geometry `v` solves is at hand.
    ///
    /// Where `v` already solves `sys` (its Newton correction within 1e-9 of ‖v‖) this is
    /// [`Start::new`]: a configuration given as it stands. Errors as [`Start::new`]'s for `v`
    /// on `along(0.0)`;
    /// [`SolveError::InconsistentStart`] (with ‖F(v, x)‖ for `sys`) where `along` builds no
    /// mechanism for some `s`, or the path cannot be followed to s = 1 — it meets a
    /// singularity, or turns back (no configuration on `v`'s branch at these inputs for the new
    /// geometry).
    ///
    /// ```
    /// use linkage::{Mechanism, Pose, Start};
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
    /// let rps = Rps::new();
    /// let v = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
    /// let x = rps.inverse(&v, &[0.0; 3]).unwrap();
    /// let before = Start::new(&rps, v, x).unwrap();
    /// // Calibration: the platform's first ball joint is 8 mm from where it was declared.
    /// let mut calibrated = rps.clone();
    /// calibrated.set_pivot("platform", "G1", [0.0, 58.0, 0.0]).unwrap();
    /// let (from, to) = (*rps.geometry(), *calibrated.geometry());
    /// let after = Start::follow_geometry(&calibrated, v, x, |s| {
    ///     Rps::from_geometry(core::array::from_fn(|i| from[i] + s * (to[i] - from[i]))).ok()
    /// })
    /// .unwrap();
    /// assert_eq!(after.x(), &x);
    /// assert!(linkage::error_estimate(&calibrated, after.v(), &x) < 1e-9);
    /// assert!(after.det() * before.det() > 0.0, "the same branch");
    /// // The same, generated for every declared mechanism:
    /// assert_eq!(calibrated.follow_from(&rps, v, x).unwrap(), after);
    /// ```
    pub fn follow_geometry<S, G>(
        sys: &S,
        v: [f64; N],
        x: [f64; M],
        mut along: G,
    ) -> Result<Self, SolveError>
    where
        S: Mechanism<N, M>,
        G: FnMut(f64) -> Option<S>,
    {
        let mut f = [0.0; N];
        sys.residual(&v, &x, &mut f);
        let refused = SolveError::InconsistentStart {
            residual_norm: norm(&f),
        };
        // A configuration that solves the new geometry as it stands (its Newton correction
        // there within the path's tolerance, not merely within what `Start::new` refines) is
        // taken as given: a declared home that a calibration left a solution, on whichever
        // side of a singular geometry the calibration went.
        let given = scale_or_one(size(&v));
        if correction(sys, &v, &x).is_ok_and(|c| c.size <= PATH_TOLERANCE * given) {
            return Start::new(sys, v, x);
        }
        let mut current = along(0.0).ok_or(refused)?;
        let first = Start::new(&current, v, x)?;
        let sign = first.det.signum();
        let tolerance = PATH_TOLERANCE * scale_or_one(first.scale);
        let mut w = first.v;
        // B where the path stands, for each step's predictor.
        let mut here = current.new_factor();
        current.factor(&w, &x, &mut here).ok_or(refused)?;
        let mut work = current.new_factor();
        let zero = [0.0; N];
        let (mut s, mut step) = (0.0f64, 1.0f64);
        // The last point the path passed, and where.
        let mut previous: Option<(f64, [f64; N])> = None;
        for _ in 0..MAX_STEPS {
            let next = (s + step).min(1.0);
            let built = if next < 1.0 {
                Some(along(next).ok_or(refused)?)
            } else {
                None
            };
            let ahead = built.as_ref().unwrap_or(sys);
            // The predictor: along the secant through the last two points of the path once
            // there are two; before that the Euler step of dw/ds = −B⁻¹ ∂F/∂s, the chord step
            // to the geometry ahead with B where the path stands (F is within the tolerance of
            // zero there for the geometry behind). The secant needs no B⁻¹, which for a
            // nearly singular B magnifies the terms of F of second order in s that the Euler
            // step leaves out: a spherical 3-UPU wrist with its base 1 mm deeper moved along a
            // nearly straight path, yet the Euler step's error was a third of the step at a
            // thousandth of the change, and the path took 2 056 attempts on Euler steps alone
            // against 21 with the secant.
            let predicted: [f64; N] = match previous {
                Some((s0, w0)) => {
                    let r = (next - s) / (s - s0);
                    core::array::from_fn(|i| w[i] + r * (w[i] - w0[i]))
                }
                None => {
                    let mut d = [0.0; N];
                    ahead.residual(&w, &x, &mut d);
                    current.solve(&here, &mut d);
                    core::array::from_fn(|i| w[i] - d[i])
                }
            };
            let moved: [f64; N] = core::array::from_fn(|i| predicted[i] - w[i]);
            let length = size(&moved);
            let corrected = if length.is_finite() {
                correct(
                    ahead, &x, &zero, predicted, length, sign, tolerance, &mut work,
                )
            } else {
                None
            };
            match corrected {
                Some(c) => {
                    previous = Some((s, w));
                    w = c;
                    s = next;
                    let Some(built) = built else {
                        // Polished and checked as any start (B regular to rounding there).
                        let last = Start::new(sys, w, x).map_err(|e| match e {
                            SolveError::InconsistentStart { .. } => refused,
                            e => e,
                        })?;
                        return if last.det.signum() == sign {
                            Ok(last)
                        } else {
                            Err(refused)
                        };
                    };
                    current = built;
                    match current.factor(&w, &x, &mut here) {
                        Some(info) if info.det.signum() == sign => {}
                        _ => return Err(refused),
                    }
                    step = (2.0 * step).min(1.0);
                }
                None => {
                    // The secant's direction is off the tangent by as much as the path bent
                    // over the step before, however short this one: the same step again on
                    // the Euler step, whose error shrinks with the step, before a shorter one.
                    if previous.take().is_some() {
                        continue;
                    }
                    step *= 0.5;
                    if step < MIN_STEP {
                        return Err(refused);
                    }
                }
            }
        }
        Err(refused)
    }
}
