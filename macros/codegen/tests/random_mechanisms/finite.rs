//! The oracle a finite step from home: the mechanism's own joint-space loop closure, written
//! from the declaration and the README's pair table. Every chain's links are placed by the
//! product of exponentials of its pairs' home twists (a pair's motion at its joint values,
//! about its axes as they were at home, in the chain's direction); the passive joint values
//! are solved (Gauss–Newton by least squares, along home's branch: `crate::path`) so that
//! every chain puts the platform in one place, the actives held at their targets.

use crate::generator::{add, dot, scale, sub, unit, Kind, Mech, BASE, PLATFORM, V3};
use crate::screws::{joint_axis, leg_ends};
use nalgebra::{DMatrix, DVector};

type M3 = [[f64; 3]; 3];

/// A rigid motion x ↦ r x + p.
#[derive(Clone, Copy)]
struct Motion {
    r: M3,
    p: V3,
}

const IDENTITY: Motion = Motion {
    r: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    p: [0.0; 3],
};

fn apply(r: &M3, x: V3) -> V3 {
    [dot(r[0], x), dot(r[1], x), dot(r[2], x)]
}

impl Motion {
    /// `self ∘ then`: `then` first, `self` after.
    fn after(&self, then: &Motion) -> Motion {
        let r =
            [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| self.r[i][k] * then.r[k][j]).sum()));
        Motion {
            r,
            p: add(apply(&self.r, then.p), self.p),
        }
    }

    fn point(&self, x: V3) -> V3 {
        add(apply(&self.r, x), self.p)
    }
}

/// A turn by `angle` about the axis `u` through `a`, then a slide `s` along `u`.
fn screw(u: V3, a: V3, angle: f64, s: f64) -> Motion {
    let (c, sn) = (angle.cos(), angle.sin());
    let k = [[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]];
    let r = [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let id = if i == j { 1.0 } else { 0.0 };
            id * c + sn * k[i][j] + (1.0 - c) * u[i] * u[j]
        })
    });
    let p = add(sub(a, apply(&r, a)), scale(s, u));
    Motion { r, p }
}

/// The motion of joint `k` of `chain` at its joint values `q` (one per freedom, in the order
/// of [`crate::screws::joint_twists`]).
fn joint_motion(m: &Mech, chain: usize, k: usize, q: &[f64]) -> Motion {
    let j = &m.chains[chain].joints[k];
    let axis = joint_axis(m, chain, k);
    match j.kind {
        Kind::R => {
            let (a, u) = axis.unwrap();
            screw(u, a, q[0], 0.0)
        }
        Kind::P => {
            let u = match axis {
                Some((_, u)) => u,
                None => {
                    let [from, to] = leg_ends(m, chain, k);
                    unit(sub(to, from))
                }
            };
            screw(u, [0.0; 3], 0.0, q[0])
        }
        Kind::C => {
            let (a, u) = axis.unwrap();
            screw(u, a, q[0], q[1])
        }
        Kind::H => {
            let (a, u) = axis.unwrap();
            screw(u, a, q[0], j.lead.unwrap() * q[0] / std::f64::consts::TAU)
        }
        // Rz(yaw)·Ry(pitch)·Rx(roll) about the centre, in the base frame's axes.
        Kind::S => {
            let c = m.pivots[j.centre.unwrap()].at;
            let z = screw([0.0, 0.0, 1.0], c, q[0], 0.0);
            let y = screw([0.0, 1.0, 0.0], c, q[1], 0.0);
            let x = screw([1.0, 0.0, 0.0], c, q[2], 0.0);
            z.after(&y).after(&x)
        }
        // About the axis the link before holds, then about the other as the link after holds
        // it: the first axis first where it is on the link before, else the second.
        Kind::U => {
            let c = m.pivots[j.centre.unwrap()].at;
            let t = crate::screws::joint_twists(m, chain, k);
            let (u1, u2) = ([t[0][0], t[0][1], t[0][2]], [t[1][0], t[1][1], t[1][2]]);
            let (first, second) = (screw(u1, c, q[0], 0.0), screw(u2, c, q[1], 0.0));
            if crate::screws::axis_after(m, chain, k) {
                second.after(&first)
            } else {
                first.after(&second)
            }
        }
    }
}

/// Per chain, per joint, per freedom: an input's index (`Ok`) or a passive unknown's (`Err`).
type Variables = Vec<Vec<Vec<Result<usize, usize>>>>;

/// Where each joint variable lives, and how many passive unknowns there are.
fn variables(m: &Mech) -> (Variables, usize) {
    let mut passive = 0;
    let table = m
        .chains
        .iter()
        .map(|c| {
            c.joints
                .iter()
                .map(|j| {
                    (0..j.kind.freedoms())
                        .map(|f| match j.inputs.get(f) {
                            Some(name) => Ok(m.inputs.iter().position(|i| i == name).unwrap()),
                            None => {
                                passive += 1;
                                Err(passive - 1)
                            }
                        })
                        .collect()
                })
                .collect()
        })
        .collect();
    (table, passive)
}
/// A joint's values: an input's from `x`, a passive freedom's from `y`.
fn joint_values(vars: &[Result<usize, usize>], x: &[f64], y: &[f64]) -> Vec<f64> {
    vars.iter()
        .map(|v| match v {
            Ok(i) => x[*i],
            Err(p) => y[*p],
        })
        .collect()
}

/// Every chain's platform motion at inputs `x` (declared order, each from its home zero) and
/// passive values `y`.
fn platform_motions(m: &Mech, x: &[f64], y: &[f64]) -> Vec<Motion> {
    let (table, _) = variables(m);
    let mut placed: Vec<Option<Motion>> = vec![None; m.links.len()];
    placed[BASE] = Some(IDENTITY);
    let mut out = Vec::new();
    // Chains start at the base or at a link of an earlier chain: one pass in order.
    for (ci, c) in m.chains.iter().enumerate() {
        let mut t = placed[c.links[0].unwrap()].expect("a chain starts at a link placed before");
        for (k, _) in c.joints.iter().enumerate() {
            let q = joint_values(&table[ci][k], x, y);
            t = t.after(&joint_motion(m, ci, k, &q));
            if let Some(l) = c.links[k + 1] {
                if l == PLATFORM {
                    out.push(t);
                } else if placed[l].is_none() {
                    placed[l] = Some(t);
                }
            }
        }
    }
    out
}

/// The loop closure's residual: every chain's platform against the first chain's, and every
/// chain's pass through a declared link against that link's first placement. Rotations' entries
/// and translations in units of 100 mm.
fn residual(m: &Mech, x: &[f64], y: &[f64]) -> DVector<f64> {
    let (table, _) = variables(m);
    let mut placed: Vec<Option<Motion>> = vec![None; m.links.len()];
    placed[BASE] = Some(IDENTITY);
    let mut r = Vec::new();
    let compare = |a: &Motion, b: &Motion, r: &mut Vec<f64>| {
        for i in 0..3 {
            for j in 0..3 {
                r.push(a.r[i][j] - b.r[i][j]);
            }
            r.push((a.p[i] - b.p[i]) / 100.0);
        }
    };
    for (ci, c) in m.chains.iter().enumerate() {
        let mut t = placed[c.links[0].unwrap()].unwrap();
        for (k, _) in c.joints.iter().enumerate() {
            let q = joint_values(&table[ci][k], x, y);
            t = t.after(&joint_motion(m, ci, k, &q));
            if let Some(l) = c.links[k + 1] {
                match placed[l] {
                    Some(first) => compare(&t, &first, &mut r),
                    None => placed[l] = Some(t),
                }
            }
        }
    }
    DVector::from_vec(r)
}

/// The platform's pivots (base frame) at inputs `x`, each a step from its home zero, by the
/// oracle's loop closure solved from home along the way, following home's branch
/// (`crate::path::follow`); `Err` if it does not close.
pub fn platform_points(m: &Mech, x: &[f64]) -> Result<Vec<(String, V3)>, crate::path::Stop> {
    let (_, n) = variables(m);
    let at = |t: f64| -> Vec<f64> { x.iter().map(|xi| xi * t).collect() };
    // dy/dt = −J⁺ ∂r/∂t, for the prediction.
    let tangent = |t: f64, y: &[f64]| -> Result<Vec<f64>, String> {
        let e = 1e-6;
        let rt = (residual(m, &at(t + e), y) - residual(m, &at(t - e), y)) / (2.0 * e);
        Ok(least_squares(jacobian(m, &at(t), y), &rt)?
            .iter()
            .copied()
            .collect())
    };
    let y = crate::path::follow(vec![0.0; n], tangent, |t, mut y| {
        close(m, &at(t), &mut y).map(|()| y)
    })?;
    let t = platform_motions(m, x, &y)[0];
    Ok(m.pivots
        .iter()
        .filter(|p| p.link == PLATFORM)
        .map(|p| (p.name.clone(), t.point(p.at)))
        .collect())
}

/// The residual's Jacobian in the passive values, by central differences.
fn jacobian(m: &Mech, x: &[f64], y: &[f64]) -> DMatrix<f64> {
    let h = 1e-7;
    let mut jac = DMatrix::zeros(residual(m, x, y).len(), y.len());
    for c in 0..y.len() {
        let mut yp = y.to_vec();
        yp[c] += h;
        let mut ym = y.to_vec();
        ym[c] -= h;
        jac.set_column(
            c,
            &((residual(m, x, &yp) - residual(m, x, &ym)) / (2.0 * h)),
        );
    }
    jac
}

/// −J⁺ f, the least-squares step, with singular values below 1e-9 of the largest (idle
/// freedoms: a rod's spin) left out of the pseudo-inverse, so that those freedoms stay put.
/// Not damped: near a fold J's smallest singular value (2.7e-6 of its largest, seed
/// 1548616513) squared is below any damping that holds the idle ones, which shortened the
/// steps (and the tangent) just where they matter.
fn least_squares(jac: DMatrix<f64>, f: &DVector<f64>) -> Result<DVector<f64>, String> {
    if jac.ncols() == 0 {
        return Ok(DVector::zeros(0));
    }
    let svd = jac.svd(true, true);
    let floor = 1e-9 * svd.singular_values.max();
    Ok(svd.solve(&(-f), floor)?)
}

/// Closes the loops at inputs `x` from passive values `y`.
fn close(m: &Mech, x: &[f64], y: &mut [f64]) -> Result<(), String> {
    let mut f = residual(m, x, y);
    for _ in 0..60 {
        if f.norm() < 1e-13 {
            break;
        }
        let step = least_squares(jacobian(m, x, y), &f)?;
        for (yi, si) in y.iter_mut().zip(step.iter()) {
            *yi += si;
        }
        f = residual(m, x, y);
    }
    if !(f.norm() < 1e-10) {
        return Err(format!("residual {:.1e} after 60 iterations", f.norm()));
    }
    Ok(())
}
