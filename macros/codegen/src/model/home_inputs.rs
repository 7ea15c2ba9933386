//! `home = inputs(q1 = .., ...)`: the home configuration given by joint values, solved at
//! compile time. The declared geometry is one assembled configuration (the platform's frame at
//! the base frame, the links' pivots where declared, the inputs there from inverse kinematics
//! or the general model's zeros); the home configuration is where forward kinematics takes it
//! as the inputs move in a straight line to the declared values — Newton's method along the
//! line in steps, on the exact Jacobian, the step halved where Newton does not contract. A
//! path that would cross a singularity (det ∂F/∂v changes sign between two steps, so the
//! branch is no longer the declared configuration's) or ends at one is a compile error, as is
//! a declared geometry that does not assemble.

use crate::expr::Expr;
use crate::model::reference::{assembled, configuration, Reference};
use crate::model::Model;
use nalgebra::{DMatrix, DVector};

/// Newton corrections are accepted below this fraction of the configuration's size.
const TOLERANCE: f64 = 1e-12;

/// A first correction larger than this fraction of the configuration's size is not followed:
/// Newton's method would converge (if at all) far from where it started, possibly on another
/// branch whose det ∂F/∂v has the same sign. The step along the inputs is shortened instead.
/// With every later correction at most half the one before, the point found is within twice
/// the first correction of the one the step started from.
const FIRST_CORRECTION: f64 = 0.05;

struct System<'a> {
    model: &'a Model,
    jacobian: Vec<(usize, usize, Expr)>,
    c: Vec<f64>,
}

impl System<'_> {
    fn residual(&self, v: &[f64], x: &[f64]) -> DVector<f64> {
        DVector::from_iterator(
            self.model.equations.len(),
            self.model.equations.iter().map(|f| f.eval(v, x, &self.c)),
        )
    }

    fn jacobian(&self, v: &[f64], x: &[f64]) -> DMatrix<f64> {
        let n = v.len();
        let mut b = DMatrix::zeros(self.model.equations.len(), n);
        for (r, c, e) in &self.jacobian {
            b[(*r, *c)] = e.eval(v, x, &self.c);
        }
        b
    }

    /// Newton from `v` at inputs `x`: the converged point and det B there, or `None` where it
    /// does not contract (each correction at most half the one before, the first at most
    /// `FIRST_CORRECTION` of the configuration's size).
    fn newton(&self, v: &[f64], x: &[f64]) -> Option<(Vec<f64>, f64)> {
        let scale = v.iter().fold(1.0f64, |m, a| m.max(a.abs()));
        let mut v = v.to_vec();
        let mut last = FIRST_CORRECTION * scale / 0.5;
        for _ in 0..12 {
            let lu = self.jacobian(&v, x).lu();
            let step = lu.solve(&(-self.residual(&v, x)))?;
            let size = step.amax();
            if !(size <= 0.5 * last) {
                return None;
            }
            v.iter_mut().zip(step.iter()).for_each(|(a, d)| *a += d);
            if size <= TOLERANCE * scale {
                let det = self.jacobian(&v, x).determinant();
                return Some((v, det));
            }
            last = size;
        }
        None
    }
}

/// The platform's pose `[yaw, pitch, roll, x, y, z]` at `v`: from its three frame points (a
/// located platform), the least rotation of its line (a line), its one point (a point).
fn platform_pose(model: &Model, v: &[f64]) -> [f64; 6] {
    let g = model.default_slots();
    let k = model.points.len();
    let at = |p: usize| nalgebra::Vector3::new(v[p], v[k + p], v[2 * k + p]);
    let local = |p: usize| nalgebra::Vector3::from(model.points[p].local.map(|s| g[s]));
    let r = if model.located {
        let [a, b, c] = model.frame;
        let frame = |p: [nalgebra::Vector3<f64>; 3]| {
            let e1 = (p[1] - p[0]).normalize();
            let e3 = e1.cross(&(p[2] - p[0])).normalize();
            nalgebra::Matrix3::from_columns(&[e1, e3.cross(&e1), e3])
        };
        frame([at(a), at(b), at(c)]) * frame([local(a), local(b), local(c)]).transpose()
    } else {
        // A line: the least rotation that turns it from its direction in the platform's frame
        // to its direction at `v`, as `linkage::pose_from_unknowns` turns it at run time (any
        // two of its pivots give the same rotation; the one farthest from the first is the best
        // conditioned). Every pivot of the line was once left unturned where more than two
        // were declared (a linear pentapod): `home_start` then put the tool on another line,
        // at inputs other than the declared ones.
        match linkage_geometry::farthest_from_first(k, |p| local(p).into()) {
            // A point: no direction to turn.
            0 => nalgebra::Matrix3::identity(),
            f => {
                let (d0, d1) = (local(f) - local(0), at(f) - at(0));
                let r = linkage_geometry::least_rotation(d0.into(), d1.into());
                nalgebra::Matrix3::from_fn(|i, j| r[i][j])
            }
        }
    };
    let t = at(0) - r * local(0);
    let pitch = (-r[(2, 0)]).clamp(-1.0, 1.0).asin();
    let (yaw, roll) = if r[(2, 0)].abs() < 1.0 - 1e-12 {
        (r[(1, 0)].atan2(r[(0, 0)]), r[(2, 1)].atan2(r[(2, 2)]))
    } else {
        ((-r[(0, 1)]).atan2(r[(1, 1)]), 0.0)
    };
    [yaw, pitch, roll, t[0], t[1], t[2]]
}

/// The home configuration for the joint values `target` (in the model's input order).
pub fn solve(model: &Model, target: &[f64]) -> Result<Reference, String> {
    let hint = "the declared geometry must be one configuration the mechanism assembles in (the platform's frame at the base frame), from which forward kinematics reaches the given inputs";
    let (v0, x0, c) = configuration(model, model.home_pose).map_err(|e| format!("{e} ({hint})"))?;
    assembled(model, &v0, &x0, &c).map_err(|e| {
        format!(
            "{} ({hint})",
            e.replace("home configuration", "declared configuration")
        )
    })?;
    let system = System {
        model,
        jacobian: model.jacobian(),
        c,
    };
    let det0 = system.jacobian(&v0, &x0).determinant();
    if !(det0.abs() > 0.0) || !det0.is_finite() {
        return Err(format!("the declared configuration is singular (det ∂F/∂v = {det0:e}): forward kinematics cannot start there ({hint})"));
    }
    let along = |t: f64| -> Vec<f64> {
        x0.iter()
            .zip(target)
            .map(|(a, b)| a + t * (b - a))
            .collect()
    };
    let (mut v, mut t, mut dt, mut det) = (v0, 0.0f64, 1.0 / 32.0, det0);
    while t < 1.0 {
        let next = (t + dt).min(1.0);
        match system.newton(&v, &along(next)) {
            Some((w, d)) if d.signum() == det.signum() && d != 0.0 => {
                v = w;
                det = d;
                t = next;
                dt = (dt * 1.5).min(1.0 / 8.0);
            }
            Some(_) => {
                // Either a fold between t and next (the branch turns back) or a jump to another
                // branch: shorter steps tell which; at the shortest, it is a singularity.
                if dt < 1e-6 {
                    return Err(format!("forward kinematics from the declared configuration meets a singularity (det ∂F/∂v changes sign) at {:.4} of the way to the given inputs: the inputs are not reached on the declared configuration's branch", t));
                }
                dt *= 0.5;
            }
            None => {
                if dt < 1e-6 {
                    return Err(format!("forward kinematics from the declared configuration stops at {:.4} of the way to the given inputs (Newton's method does not converge there: a singularity, or inputs the mechanism cannot reach)", t));
                }
                dt *= 0.5;
            }
        }
    }
    let x = target.to_vec();
    let sv = system.jacobian(&v, &x).singular_values();
    if !(sv.min() > 1e-10 * sv.max()) {
        return Err(format!(
            "the configuration at the given inputs is singular (smallest/largest singular value of ∂F/∂v = {:.1e})",
            sv.min() / sv.max()
        ));
    }
    Ok(Reference {
        pose: platform_pose(model, &v),
        v,
        x,
    })
}
