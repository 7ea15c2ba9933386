//! `stewart modes --png FILE [--row N]`: every real assembly mode of one row drawn side by
//! side — base (grey), platform (blue where det B > 0, red where det B < 0) and legs — in one
//! oblique view and one scale, so that the modes compare at a glance.

use crate::plot::{draw_err, init_fonts};
use linkage::modes::RealRoot;
use linkage::Pose;
use linkage_examples::stewart::SixSix;
use plotters::prelude::*;
use std::path::Path;

/// View direction: azimuth and elevation (rad) of the oblique projection.
const AZIMUTH: f64 = 0.5;
const ELEVATION: f64 = 0.35;

fn project(p: [f64; 3]) -> (f64, f64) {
    let (sa, ca) = AZIMUTH.sin_cos();
    let (se, ce) = ELEVATION.sin_cos();
    let x = p[0] * ca - p[1] * sa;
    let depth = p[0] * sa + p[1] * ca;
    (x, p[2] * ce + depth * se)
}

/// One mode's drawing: base joints, platform pivots in the base frame.
struct Figure {
    base: [[f64; 3]; 6],
    platform: [[f64; 3]; 6],
    det: f64,
    pose: Pose,
}

/// Draws the real modes of the row with legs `x` to `file`. Each mode's leg lengths are checked
/// against `x` first: a drawing of anything else would be a wrong picture.
pub fn draw<S: SixSix, const N: usize>(
    sys: &S,
    x: &[f64; 6],
    real: &[RealRoot<N>],
    row: usize,
    file: &Path,
) -> Result<(), String> {
    let base = sys.base_joints();
    let mut figures = Vec::new();
    for r in real {
        let Some(pose) = r.pose else { continue };
        let platform: [[f64; 3]; 6] = std::array::from_fn(|k| pose.apply(sys.point_local(k)));
        for k in 0..6 {
            let l = (0..3)
                .map(|i| (platform[k][i] - base[k][i]).powi(2))
                .sum::<f64>()
                .sqrt();
            if !((l - x[k]).abs() <= 1e-6 * x[k].max(1.0)) {
                return Err(format!(
                    "mode drawing: leg {} is {l} mm, the row says {}",
                    k + 1,
                    x[k]
                ));
            }
        }
        figures.push(Figure {
            base,
            platform,
            det: r.det,
            pose,
        });
    }
    if figures.is_empty() {
        return Err(format!("row {row}: no real assembly mode to draw"));
    }
    init_fonts()?;
    let (mut lo, mut hi) = (
        (f64::INFINITY, f64::INFINITY),
        (f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for f in &figures {
        for p in f.base.iter().chain(&f.platform) {
            let (a, b) = project(*p);
            lo = (lo.0.min(a), lo.1.min(b));
            hi = (hi.0.max(a), hi.1.max(b));
        }
    }
    // One scale for all panels, square, with a margin.
    let span = (hi.0 - lo.0).max(hi.1 - lo.1) * 1.08;
    let centre = ((lo.0 + hi.0) / 2.0, (lo.1 + hi.1) / 2.0);
    let (xr, yr) = (
        centre.0 - span / 2.0..centre.0 + span / 2.0,
        centre.1 - span / 2.0..centre.1 + span / 2.0,
    );
    let cols = figures.len().min(4);
    let rows = figures.len().div_ceil(cols);
    let panel = 300u32;
    let root = BitMapBackend::new(file, (panel * cols as u32, panel * rows as u32 + 30))
        .into_drawing_area();
    root.fill(&WHITE).map_err(draw_err)?;
    let (head, body) = root.split_vertically(30);
    head.draw(&Text::new(
        format!(
            "row {row}: {} real assembly modes (legs {}) — grey base, platform blue det B > 0, red det B < 0",
            figures.len(),
            x.map(|l| format!("{l:.1}")).join(", ")
        ),
        (8, 8),
        ("sans-serif", 13),
    ))
    .map_err(draw_err)?;
    for (n, (area, f)) in body
        .split_evenly((rows, cols))
        .iter()
        .zip(&figures)
        .enumerate()
    {
        let [yaw, pitch, roll] = f.pose.euler();
        let t = f.pose.translation;
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!(
                    "mode {}: z {:.1} mm, ypr {:.2} {:.2} {:.2}",
                    n + 1,
                    t[2],
                    yaw,
                    pitch,
                    roll
                ),
                ("sans-serif", 12),
            )
            .margin(6)
            .build_cartesian_2d(xr.clone(), yr.clone())
            .map_err(draw_err)?;
        let ring = |points: &[[f64; 3]; 6]| {
            let mut v: Vec<(f64, f64)> = points.iter().map(|p| project(*p)).collect();
            v.push(v[0]);
            v
        };
        let colour = if f.det > 0.0 {
            RGBColor(40, 90, 200)
        } else {
            RGBColor(210, 40, 40)
        };
        chart
            .draw_series(std::iter::once(PathElement::new(
                ring(&f.base),
                RGBColor(150, 150, 150).stroke_width(2),
            )))
            .map_err(draw_err)?;
        chart
            .draw_series((0..6).map(|k| {
                PathElement::new(
                    vec![project(f.base[k]), project(f.platform[k])],
                    BLACK.stroke_width(1),
                )
            }))
            .map_err(draw_err)?;
        chart
            .draw_series(std::iter::once(Polygon::new(
                ring(&f.platform),
                colour.mix(0.35).filled(),
            )))
            .map_err(draw_err)?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                ring(&f.platform),
                colour.stroke_width(2),
            )))
            .map_err(draw_err)?;
    }
    root.present().map_err(draw_err)?;
    Ok(())
}
