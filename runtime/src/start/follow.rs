//! A start carried to a geometry that has changed since its configuration was found
//! ([`Start::follow`]): continuation along the residual homotopy F(w, x) = (1 − t)·F(v, x).

use super::Start;
use super::path::{MAX_STEPS, MIN_STEP, PATH_TOLERANCE, correct};
use crate::math::{norm, scale_or_one, size};
use crate::mechanism::Mechanism;
use crate::solution::SolveError;

impl<const N: usize, const M: usize> Start<N, M> {
    /// [`Start::new`] for a configuration `v` that solved the mechanism before its geometry
    /// changed, where only the new mechanism is at hand: `v` is carried to a solution for the
    /// current geometry at the same inputs `x` by following the path
    /// F(w(t), x) = (1 − t)·F(v, x) from t = 0 (w = v) to t = 1, with the corrector trusted
    /// only where it contracts (the rule continuation and the tracker apply) and det B of one
    /// sign all along: the start found is on the branch of det B's sign at `v` for the new
    /// geometry, never one reached across a singularity of that path.
    ///
    /// That is `v`'s own branch only as long as the change leaves det B at `v` its sign: near
    /// a singularity of the new geometry, or after a large change, it may not (a spherical
    /// 3-UPU wrist with its base pivots 0.3 mm deeper landed in another operation mode). Where
    /// the geometry `v` solves is at hand, [`Start::follow_geometry`] (the generated
    /// `follow_from`, as `home_start` uses it) follows the change of geometry itself instead.
    ///
    /// Where `v` already solves F (to what [`Start::new`] refines) this is `Start::new`.
    /// Errors as [`Start::new`]'s; [`SolveError::InconsistentStart`] (with ‖F(v, x)‖) also
    /// where the path cannot be followed to t = 1 — it meets a singularity, or turns back
    /// (no configuration on `v`'s branch for these inputs and this geometry).
    ///
    /// ```
    /// use linkage::{Mechanism, Pose, SolveError, Start};
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
    /// let mut rps = Rps::new();
    /// let v = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
    /// let x = rps.inverse(&v, &[0.0; 3]).unwrap();
    /// let before = Start::new(&rps, v, x).unwrap();
    /// // Calibration: the platform's first ball joint is 8 mm from where it was declared.
    /// rps.set_pivot("platform", "G1", [0.0, 58.0, 0.0]).unwrap();
    /// assert!(matches!(Start::new(&rps, v, x), Err(SolveError::InconsistentStart { .. })));
    /// let after = Start::follow(&rps, v, x).unwrap();
    /// assert_eq!(after.x(), &x);
    /// assert!(linkage::error_estimate(&rps, after.v(), &x) < 1e-9);
    /// assert!(after.det() * before.det() > 0.0, "the same branch");
    /// ```
    pub fn follow<S: Mechanism<N, M>>(
        sys: &S,
        v: [f64; N],
        x: [f64; M],
    ) -> Result<Self, SolveError> {
        let residual_norm = match Start::new(sys, v, x) {
            Err(SolveError::InconsistentStart { residual_norm }) => residual_norm,
            done => return done,
        };
        // `Start::new` has checked what it could at `v`: finite, valid inputs, F finite, B
        // regular to rounding.
        let mut f0 = [0.0; N];
        sys.residual(&v, &x, &mut f0);
        let scale = scale_or_one(norm(&v));
        let mut path = Path {
            sys,
            x: &x,
            f0,
            tolerance: PATH_TOLERANCE * scale,
            fac: sys.new_factor(),
            det: 0.0,
        };
        let refused = SolveError::InconsistentStart { residual_norm };
        let mut w = v;
        // Where the path starts: B factored at v, det B's sign the branch's.
        let mut velocity = path.velocity(&w).ok_or(refused)?;
        let sign = path.det.signum();
        let (mut t, mut step) = (0.0f64, 1.0f64);
        for _ in 0..MAX_STEPS {
            let next = (t + step).min(1.0);
            let h = next - t;
            let predicted: [f64; N] = core::array::from_fn(|i| w[i] + h * velocity[i]);
            let length = h * size(&velocity);
            match path.correct(predicted, next, length, sign) {
                Some(corrected) => {
                    w = corrected;
                    t = next;
                    if t >= 1.0 {
                        // Polished and checked as any start (B regular to rounding there).
                        return Start::new(sys, w, x).map_err(|e| match e {
                            SolveError::InconsistentStart { .. } => refused,
                            e => e,
                        });
                    }
                    velocity = match path.velocity(&w) {
                        Some(d) if path.det.signum() == sign => d,
                        _ => return Err(refused),
                    };
                    step = (2.0 * step).min(1.0);
                }
                None => {
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

/// The residual homotopy H(w, t) = F(w, x) − (1 − t)·F(v, x) and the factorisation storage of
/// its steps.
struct Path<'a, S: Mechanism<N, M>, const N: usize, const M: usize> {
    sys: &'a S,
    x: &'a [f64; M],
    /// F(v, x) at the configuration the path starts from.
    f0: [f64; N],
    tolerance: f64,
    fac: S::Factor,
    /// det B at the last point factored.
    det: f64,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Path<'_, S, N, M> {
    /// B factored at `w` (kept for the corrector's first iteration), and the path's tangent
    /// dw/dt = −B⁻¹F(v, x) there; `None` where B is singular or the values are not finite.
    fn velocity(&mut self, w: &[f64; N]) -> Option<[f64; N]> {
        let info = self.sys.factor(w, self.x, &mut self.fac)?;
        self.det = info.det;
        let mut d = self.f0;
        self.sys.solve(&self.fac, &mut d);
        let d = d.map(|e| -e);
        (size(&d).is_finite() && info.det.is_finite()).then_some(d)
    }

    /// The corrector at `t`: Newton's method on H(·, t) from the predicted point.
    fn correct(&mut self, predicted: [f64; N], t: f64, length: f64, sign: f64) -> Option<[f64; N]> {
        let shift = self.f0.map(|f| (1.0 - t) * f);
        correct(
            self.sys,
            self.x,
            &shift,
            predicted,
            length,
            sign,
            self.tolerance,
            &mut self.fac,
        )
    }
}
