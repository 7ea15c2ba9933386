//! The platform's frame pivots at a configuration, and the twist their rates make.

use super::{Twist, VelocityError};
use crate::lu::Lu;
use crate::math::{cross3, dot3, norm3, sub3};
use crate::mechanism::Mechanism;
use crate::pose::pose_from_unknowns;
use crate::pose::{PlatformPivots, platform_pivots};

/// The platform's frame pivots where `v` has them, and its frame's origin.
pub(super) struct Frame {
    /// The three frame pivots; for a line, its first pivot and the farthest one (twice); for a
    /// point, the point (three times).
    points: [[f64; 3]; 3],
    index: [usize; 3],
    origin: [f64; 3],
    count: usize,
    turning: Turning,
}

/// How the platform's ω follows from its frame pivots' rates.
enum Turning {
    /// Σ (|rₖ|² I − rₖ rₖᵀ) over the second and third pivots' offsets rₖ from the first,
    /// factored: the normal matrix of ω × rₖ = uₖ, the same for every set of rates.
    Frame(Lu<3>),
    /// ω square to the line (its spin about itself is no freedom).
    Line,
    /// None: no pair fixes any turn of a point, so ω is zero by convention.
    Point,
}

impl Frame {
    pub(super) fn of<S: Mechanism<N, M>, const N: usize, const M: usize>(
        sys: &S,
        v: &[f64; N],
    ) -> Result<Frame, VelocityError> {
        if !v.iter().all(|c| c.is_finite()) {
            return Err(VelocityError::NonFinite);
        }
        let pose = pose_from_unknowns(sys, v).ok_or(VelocityError::NoFrame)?;
        let count = S::POINTS.len();
        // The turning of a frame of three pivots is known once their offsets are (below).
        let (index, turning) = match platform_pivots(sys) {
            PlatformPivots::Frame(f) => (f, None),
            PlatformPivots::Line(far) => ([0, far, far], Some(Turning::Line)),
            PlatformPivots::Point => ([0; 3], Some(Turning::Point)),
        };
        let points = index.map(|p| point(v, count, p));
        let (r1, r2) = (sub3(points[1], points[0]), sub3(points[2], points[0]));
        let frame = |turning| Frame {
            points,
            index,
            origin: pose.translation,
            count,
            turning,
        };
        match turning {
            // A line of no length (its pivots on one point in `v`) has no direction.
            Some(Turning::Line) if !(norm3(r1) > 0.0) => return Err(VelocityError::NoFrame),
            Some(turning) => return Ok(frame(turning)),
            None => {}
        }
        // Collinear to rounding is collinear: the angle at the first pivot must be more than
        // rounding, or ω about the line through them is not determined by their rates.
        if !(norm3(cross3(r1, r2)) > 1e-9 * norm3(r1) * norm3(r2)) {
            return Err(VelocityError::NoFrame);
        }
        let mut a = [[0.0; 3]; 3];
        for r in [r1, r2] {
            let rr = dot3(r, r);
            for i in 0..3 {
                for j in 0..3 {
                    a[i][j] += if i == j { rr } else { 0.0 } - r[i] * r[j];
                }
            }
        }
        Ok(frame(Turning::Frame(
            Lu::new(a).ok_or(VelocityError::NoFrame)?,
        )))
    }

    /// The distance between the first two frame pivots: a length the platform is (zero for a
    /// point).
    pub(super) fn size(&self) -> f64 {
        norm3(sub3(self.points[1], self.points[0]))
    }

    /// ω and the origin's velocity from the frame pivots' rates: ω is the least-squares
    /// solution of ω × rₖ = uₖ (rₖ, uₖ the second and third pivots' offsets from the first and
    /// their relative velocities), Σ (|rₖ|² I − rₖ rₖᵀ) ω = Σ rₖ × uₖ, exact for a rigid motion
    /// and regular for non-collinear pivots.
    pub(super) fn twist<const N: usize>(&self, vdot: &[f64; N]) -> Result<Twist, VelocityError> {
        let rates = self.index.map(|p| point(vdot, self.count, p));
        let mut b = [0.0; 3];
        for k in 1..3 {
            let c = cross3(
                sub3(self.points[k], self.points[0]),
                sub3(rates[k], rates[0]),
            );
            for i in 0..3 {
                b[i] += c[i];
            }
        }
        match &self.turning {
            Turning::Frame(normal) => normal.solve(&mut b),
            // A line r: ω = r × u / |r|², the one square to it (b holds r × u twice, the
            // line's far pivot standing for the second and third frame pivots alike).
            Turning::Line => {
                let r = sub3(self.points[1], self.points[0]);
                let rr = 2.0 * dot3(r, r);
                b = b.map(|c| c / rr);
            }
            Turning::Point => b = [0.0; 3],
        }
        let w = cross3(b, sub3(self.origin, self.points[0]));
        let t = Twist {
            angular: b,
            linear: [0, 1, 2].map(|i| rates[0][i] + w[i]),
        };
        if t.as_array().iter().all(|c| c.is_finite()) {
            Ok(t)
        } else {
            Err(VelocityError::NonFinite)
        }
    }
}

fn point<const N: usize>(v: &[f64; N], count: usize, p: usize) -> [f64; 3] {
    [0, 1, 2].map(|axis| v.get(axis * count + p).copied().unwrap_or(f64::NAN))
}
