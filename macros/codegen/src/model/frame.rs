//! The platform's frame: three of its pivots that locate it.

use crate::front::resolved::Decl;
use crate::model::rigid;
use syn::Error;

/// The platform's three frame pivots (places among its pivots): the declared ones, else the
/// largest triangle; `None` for a platform of one point or of collinear points (its chains fix
/// only its position).
pub fn choose(d: &Decl) -> Result<Option<[usize; 3]>, Error> {
    let pivots = d.platform_pivots();
    let pts: Vec<[f64; 3]> = pivots.iter().map(|&p| d.point(p)).collect();
    let area = |i: usize, j: usize, l: usize| rigid::triangle_area(pts[i], pts[j], pts[l]);
    let scale = pts
        .iter()
        .flat_map(|p| p.iter())
        .fold(1e-300f64, |a, x| a.max(x.abs()));
    let tol = 1e-9 * scale * scale;
    let platform = &d.link(crate::front::ids::LinkId::PLATFORM).name;
    if let Some(frame) = &d.platform.frame {
        // The resolver has checked that the three are the platform's.
        let idx: Vec<usize> = frame
            .iter()
            .filter_map(|f| pivots.iter().position(|&p| p == f.id))
            .collect();
        let [a, b, c] = idx[..] else {
            return Err(Error::new(
                platform.span(),
                "`frame` names three pivots of the platform",
            ));
        };
        if area(a, b, c) <= tol {
            let name = |i: usize| &d.pivot(pivots[i]).name;
            return Err(Error::new(frame[0].span, format!("the `frame` pivots `{}`, `{}`, `{}` are collinear: the platform needs three non-collinear pivots", name(a), name(b), name(c))));
        }
        return Ok(Some([a, b, c]));
    }
    // Largest triangle: the best-conditioned frame.
    let n = pts.len();
    let mut best = None;
    let mut best_area = tol;
    for i in 0..n {
        for j in i + 1..n {
            for l in j + 1..n {
                let a = area(i, j, l);
                if a > best_area * (1.0 + 1e-9) {
                    best_area = a;
                    best = Some([i, j, l]);
                }
            }
        }
    }
    // None if all are collinear: a line platform (a tool axis on a linear pentapod), placed
    // like one of two pivots, by a point and a direction; its spin about the line is no freedom.
    Ok(best)
}
