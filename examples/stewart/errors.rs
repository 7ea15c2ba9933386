//! `stewart errors`: Fig. 7, the relative error of every test point for each method.

use crate::plot::{draw_err, init_fonts};
use linkage_examples::case_study::sampling::Protocol;
use linkage_examples::case_study::table_v;
use plotters::prelude::*;
use std::path::Path;

pub fn run(out: &Path, seed: u64) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    init_fonts()?;
    let report = table_v::run(
        Protocol {
            seed,
            ..Protocol::default()
        },
        |stage| eprintln!("errors: {stage}…"),
    )
    .map_err(|e| format!("test points: {e}"))?;
    let file = out.join("fig7_relative_errors.png");
    let root = BitMapBackend::new(&file, (720, 800)).into_drawing_area();
    let (plots, legend) = root.split_vertically(780);
    root.fill(&WHITE).map_err(draw_err)?;
    let panels = plots.split_evenly((3, 1));
    let n = report.normal.len();
    let total = n + report.near.len();
    for ((name, paper, _), area) in report.outcomes.iter().zip(panels.iter()) {
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("{name}: relative error per test point (paper settings)"),
                ("sans-serif", 15),
            )
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(50)
            .build_cartesian_2d(0f64..(total as f64 + 1.0), -17f64..1f64)
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc(format!(
                "test point (1–{n} normal, {}–{total} near singular)",
                n + 1
            ))
            .y_desc("log10 relative error")
            .disable_mesh()
            .draw()
            .map_err(draw_err)?;
        chart
            .draw_series(LineSeries::new(
                [(0.0, -3.0), (total as f64 + 1.0, -3.0)],
                RED.mix(0.5),
            ))
            .map_err(draw_err)?;
        let y = |e: f64| e.max(1e-17).log10();
        let ok = paper
            .iter()
            .enumerate()
            .filter(|(_, o)| o.status.meets_tolerance());
        chart
            .draw_series(
                ok.map(|(i, o)| {
                    Circle::new((i as f64 + 1.0, y(o.relative_error)), 2, BLUE.filled())
                }),
            )
            .map_err(draw_err)?;
        let refused = paper
            .iter()
            .enumerate()
            .filter(|(_, o)| !o.status.meets_tolerance());
        chart
            .draw_series(refused.map(|(i, o)| {
                Cross::new(
                    (i as f64 + 1.0, y(o.relative_error)),
                    4,
                    RGBColor(230, 120, 0),
                )
            }))
            .map_err(draw_err)?;
    }
    legend
        .draw(&Text::new("blue: returned ok;  orange ×: typed outcome (fold, not converged…), error of the last point;  red line: 0.1 %", (10, 4), ("sans-serif", 11)))
        .map_err(draw_err)?;
    root.present().map_err(draw_err)?;
    eprintln!("errors: wrote {}", file.display());
    Ok(())
}
