//! Rigid-body equations of the moving platform (Eq. 3, with Eq. 16's coplanar form).
//!
//! Three non-collinear frame points p1, p2, p3 keep their three mutual distances. Every other
//! pivot q is tied to them linearly: in the coplanar form `q = a p1 + b p2 + c p3` (a + b + c = 1,
//! the E_j of Eq. 17); otherwise `q = a p1 + b p2 + c p3 + d (p2 − p1) × (p3 − p1)`, which a
//! mirror image does not satisfy (the cross product flips sign under a reflection) while the
//! degree stays 2. The paper's printed "O.W." case, four distances, is neither rigid nor
//! mirror-free (see ERRATA.md).

use crate::expr::{self, Expr, Vec3};
use crate::model::{Builder, Recipe};
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
    let frame_slots = [local(b, frame[0]), local(b, frame[1]), local(b, frame[2])];
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
                        point: local(b, q),
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
