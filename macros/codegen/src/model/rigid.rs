//! Rigid-body equations of the moving platform (Eq. 3, with Eq. 16's coplanar form).
//!
//! Three non-collinear frame points p1, p2, p3 keep their three mutual distances. Every other
//! pivot q is tied to them linearly: in the coplanar form `q = a p1 + b p2 + c p3` (a + b + c = 1,
//! the E_j of Eq. 17); otherwise `q = a p1 + b p2 + c p3 + d (p2 − p1) × (p3 − p1)`, which a
//! mirror image does not satisfy (the cross product flips sign under a reflection) while the
//! degree stays 2. The paper's printed "O.W." case, four distances, is neither rigid nor
//! mirror-free (see ERRATA.md).

use crate::expr::{self, Expr, Vec3};
use crate::model::{Builder, PointRef, Recipe};
use nalgebra::Vector3;

pub fn triangle_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let (a, b, c) = (Vector3::from(a), Vector3::from(b), Vector3::from(c));
    0.5 * (b - a).cross(&(c - a)).norm()
}

/// Whether every platform point lies in the frame's plane at the default geometry.
pub fn is_coplanar(b: &Builder, frame: [usize; 3], k: usize) -> bool {
    let p = |i: usize| Vector3::from(b.default_slot_point(b.points[i].local));
    let (p1, p2, p3) = (p(frame[0]), p(frame[1]), p(frame[2]));
    let n = (p2 - p1).cross(&(p3 - p1));
    let scale = (p2 - p1).norm().max((p3 - p1).norm());
    (0..k).all(|i| (n.dot(&(p(i) - p1)) / n.norm()).abs() <= 1e-9 * scale)
}

pub fn platform_equations(b: &mut Builder, frame: [usize; 3], k: usize, coplanar: bool) {
    let local = |b: &Builder, i: usize| b.points[i].local;
    let frame_slots = [frame[0], frame[1], frame[2]].map(|f| PointRef::Slots(local(b, f)));
    let pts: Vec<Vec3> = (0..k)
        .map(|i| [0, 1, 2].map(|a| Expr::Unknown(a * k + i)))
        .collect();
    let cross = expr::cross(
        &expr::vsub(&pts[frame[1]], &pts[frame[0]]),
        &expr::vsub(&pts[frame[2]], &pts[frame[0]]),
    );
    let mut next = 1;
    for q in (0..k).filter(|q| !frame.contains(q)) {
        let coefficients: Vec<Expr> = (0..if coplanar { 3 } else { 4 })
            .map(|index| {
                let name = format!("E{next}");
                next += 1;
                b.constant(
                    name,
                    Recipe::Rigid {
                        frame: frame_slots,
                        point: PointRef::Slots(local(b, q)),
                        index,
                        coplanar,
                    },
                )
            })
            .collect();
        for axis in 0..3 {
            let mut terms: Vec<Expr> = (0..3)
                .map(|j| Expr::times(coefficients[j].clone(), pts[frame[j]][axis].clone()))
                .collect();
            if !coplanar {
                terms.push(Expr::times(coefficients[3].clone(), cross[axis].clone()));
            }
            terms.push(pts[q][axis].clone().negated());
            b.equations.push(Expr::Sum(terms).simplify());
        }
    }
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let name = format!("E{next}");
        next += 1;
        let d = b.constant(
            name,
            Recipe::Distance {
                a: frame_slots[i],
                b: frame_slots[j],
            },
        );
        let eq = Expr::minus(
            expr::squared_distance(&pts[frame[i]], &pts[frame[j]]),
            d.square(),
        );
        b.equations.push(eq);
    }
}

/// Eq. 3 for a moving link of the general model, on its points (`name`, its expression in the
/// unknowns, where it is at home). A link with two points keeps their distance (its declared
/// `length`, if any); with more, three frame points keep their distances and every other point
/// is a combination of them: on the line (collinear form), in their plane (coplanar form), or
/// off it (with the cross product, mirror-free). Equations in no unknown are left out.
pub fn link_equations(
    b: &mut Builder,
    link: &str,
    members: &[(String, Vec3, PointRef)],
    length: Option<Expr>,
) {
    let n = members.len();
    if n < 2 {
        return;
    }
    let home: Vec<Vector3<f64>> = members
        .iter()
        .map(|(_, _, at)| Vector3::from(b.home(*at)))
        .collect();
    let e = |k: usize| members[k].1.clone();
    let push = |b: &mut Builder, eq: Expr| {
        if eq.degree() > 0 {
            b.equations.push(eq);
        }
    };
    let f1 = linkage_geometry::farthest_from_first(n, |k| home[k].into()).max(1);
    let scale = (home[f1] - home[0]).norm().max(1e-300);
    let area = |k: usize| (home[f1] - home[0]).cross(&(home[k] - home[0])).norm();
    let f2 = (1..n)
        .filter(|&k| k != f1)
        .max_by(|&i, &j| area(i).total_cmp(&area(j)))
        .filter(|&k| area(k) > 1e-9 * scale * scale);
    let distance = |b: &mut Builder, i: usize, j: usize| -> Expr {
        let d = if n == 2 { length.clone() } else { None };
        let d = d.unwrap_or_else(|| {
            b.constant(
                format!("d_{}_{}", members[i].0, members[j].0),
                Recipe::Distance {
                    a: members[i].2,
                    b: members[j].2,
                },
            )
        });
        Expr::minus(expr::squared_distance(&e(i), &e(j)), d.square())
    };
    let Some(f2) = f2 else {
        // Collinear: one distance, the others on the line.
        let eq = distance(b, 0, f1);
        push(b, eq);
        for q in (1..n).filter(|&q| q != f1) {
            let coefficients: Vec<Expr> = (0..2)
                .map(|index| {
                    b.constant(
                        format!("k{index}_{}_{link}", members[q].0),
                        Recipe::Collinear {
                            line: [members[0].2, members[f1].2],
                            point: members[q].2,
                            index,
                        },
                    )
                })
                .collect();
            for axis in 0..3 {
                let eq = Expr::Sum(vec![
                    Expr::times(coefficients[0].clone(), e(0)[axis].clone()),
                    Expr::times(coefficients[1].clone(), e(f1)[axis].clone()),
                    e(q)[axis].clone().negated(),
                ])
                .simplify();
                push(b, eq);
            }
        }
        return;
    };
    let frame = [0, f1, f2];
    let normal = (home[f1] - home[0]).cross(&(home[f2] - home[0]));
    let cross = expr::cross(&expr::vsub(&e(f1), &e(0)), &expr::vsub(&e(f2), &e(0)));
    for q in (1..n).filter(|q| !frame.contains(q)) {
        let off = normal.dot(&(home[q] - home[0])).abs() / normal.norm();
        let coplanar = off <= 1e-9 * scale.max((home[q] - home[0]).norm());
        let coefficients: Vec<Expr> = (0..if coplanar { 3 } else { 4 })
            .map(|index| {
                b.constant(
                    format!("k{index}_{}_{link}", members[q].0),
                    Recipe::Rigid {
                        frame: frame.map(|f| members[f].2),
                        point: members[q].2,
                        index,
                        coplanar,
                    },
                )
            })
            .collect();
        for axis in 0..3 {
            let mut terms: Vec<Expr> = (0..3)
                .map(|j| Expr::times(coefficients[j].clone(), e(frame[j])[axis].clone()))
                .collect();
            if !coplanar {
                terms.push(Expr::times(coefficients[3].clone(), cross[axis].clone()));
            }
            terms.push(e(q)[axis].clone().negated());
            push(b, Expr::Sum(terms).simplify());
        }
    }
    for (i, j) in [(0, f1), (f1, f2), (f2, 0)] {
        let eq = distance(b, i, j);
        push(b, eq);
    }
}

/// Three non-collinear points among `points` (home positions): the first, the farthest from it,
/// and the one spanning the largest triangle with them. `None` if all are collinear.
pub fn frame_of(points: &[[f64; 3]]) -> Option<[usize; 3]> {
    let p: Vec<Vector3<f64>> = points.iter().map(|q| Vector3::from(*q)).collect();
    let f1 = (1..p.len()).max_by(|&i, &j| (p[i] - p[0]).norm().total_cmp(&(p[j] - p[0]).norm()))?;
    let scale = (p[f1] - p[0]).norm();
    let area = |k: usize| (p[f1] - p[0]).cross(&(p[k] - p[0])).norm();
    let f2 = (1..p.len())
        .filter(|&k| k != f1)
        .max_by(|&i, &j| area(i).total_cmp(&area(j)))
        .filter(|&k| area(k) > 1e-9 * scale * scale)?;
    Some([0, f1, f2])
}
