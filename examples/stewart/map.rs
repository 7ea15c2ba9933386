//! `stewart map`: Fig. 6 (det B over L2 × L4 for four L6) and a Fig. 5-style view of the
//! (L2, L4, L6) joint space, every point on the initial configuration's branch.

use crate::plot::{draw_err, init_fonts, scale};
use indicatif::{ProgressBar, ProgressStyle};
use linkage_examples::case_study::joint_map::{explore, linspace, JointMap};
use linkage_examples::stewart::{home_start, Stewart};
use plotters::prelude::*;
use std::path::Path;
use std::time::Instant;

pub const SLICES: [f64; 4] = [190.0, 210.0, 230.0, 250.0];

pub fn run(out: &Path) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    init_fonts()?;
    let sys = Stewart::new();
    let start = home_start(&sys).map_err(|e| e.to_string())?;
    let l2 = linspace(100.0, 300.0, 81);
    let l4 = linspace(100.0, 300.0, 81);
    let l6 = linspace(170.0, 250.0, 33);
    eprintln!(
        "map: continuation over {} grid points (L1 = L3 = L5 = 190 mm)…",
        l2.len() * l4.len() * l6.len()
    );
    // A progress bar on a terminal; nothing on a pipe or a log.
    let bar = ProgressBar::new(1000).with_style(
        ProgressStyle::with_template("map: {bar:40} {percent:>3} % {elapsed} (eta {eta})")
            .map_err(|e| e.to_string())?,
    );
    let clock = Instant::now();
    let map = explore(&sys, &start, 190.0, l2, l4, l6, |f| {
        bar.set_position((1000.0 * f) as u64)
    });
    bar.finish_and_clear();
    eprintln!(
        "map: {} of {} grid points on the start's branch, {} fold points located, in {:.1} s on {} threads",
        map.reached(),
        map.ratio.len(),
        map.folds.len(),
        clock.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );
    for (n, l6) in SLICES.iter().enumerate() {
        let k = map
            .l6
            .iter()
            .position(|v| (v - l6).abs() < 1e-9)
            .ok_or("slice not on the grid")?;
        let file = out.join(format!(
            "fig6{}_l6_{}.png",
            ['a', 'b', 'c', 'd'][n],
            *l6 as i64
        ));
        slice(&map, k, &file)?;
        eprintln!("map: wrote {}", file.display());
    }
    let file = out.join("fig5_joint_space.png");
    space(&map, &file)?;
    eprintln!("map: wrote {}", file.display());
    Ok(())
}

/// log10 |det B / det B₀| mapped to [0, 1] over [-2, 0.5].
fn shade(r: f64) -> f64 {
    (r.abs().max(1e-12).log10() + 2.0) / 2.5
}

fn slice(map: &JointMap, k: usize, file: &Path) -> Result<(), String> {
    let root = BitMapBackend::new(file, (560, 575)).into_drawing_area();
    root.fill(&WHITE).map_err(draw_err)?;
    let (lo2, hi2) = (map.l2[0], *map.l2.last().expect("grid"));
    let (lo4, hi4) = (map.l4[0], *map.l4.last().expect("grid"));
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("L1 = L3 = L5 = {} mm, L6 = {} mm", map.fixed, map.l6[k]),
            ("sans-serif", 18),
        )
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(lo2..hi2, lo4..hi4)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .x_desc("L2 (mm)")
        .y_desc("L4 (mm)")
        .disable_mesh()
        .draw()
        .map_err(draw_err)?;
    let (d2, d4) = (map.l2[1] - map.l2[0], map.l4[1] - map.l4[0]);
    let near = 1e-3 * map.mean_ratio();
    let cells = (0..map.l4.len()).flat_map(|j| (0..map.l2.len()).map(move |i| (i, j)));
    chart
        .draw_series(cells.map(|(i, j)| {
            let (x, y) = (map.l2[i], map.l4[j]);
            let colour = match map.ratio[map.index(i, j, k)] {
                None => RGBColor(200, 200, 200),
                Some(r) if r.abs() < near => RGBColor(220, 30, 30),
                Some(r) => scale(shade(r)),
            };
            Rectangle::new(
                [(x - d2 / 2.0, y - d4 / 2.0), (x + d2 / 2.0, y + d4 / 2.0)],
                colour.filled(),
            )
        }))
        .map_err(draw_err)?;
    // Fold points located on grid edges in this slice.
    let l6 = map.l6[k];
    let folds = map.folds.iter().filter(|f| (f[2] - l6).abs() < 1e-9);
    chart
        .draw_series(folds.map(|f| Circle::new((f[0], f[1]), 2, BLACK.filled())))
        .map_err(draw_err)?;
    root.draw(&Text::new(
        "colour: log10 |det B / det B0| (-2 dark … 0.5 yellow);  red: |det B| < 0.1 % of mean;",
        (14, 545),
        ("sans-serif", 11),
    ))
    .map_err(draw_err)?;
    root.draw(&Text::new("black: singular points (folds) met by continuation;  grey: not reachable on the start's branch", (14, 559), ("sans-serif", 11)))
        .map_err(draw_err)?;
    root.present().map_err(draw_err)
}

fn space(map: &JointMap, file: &Path) -> Result<(), String> {
    let root = BitMapBackend::new(file, (640, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(draw_err)?;
    let r = |v: &Vec<f64>| v[0]..*v.last().expect("grid");
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!(
                "Singular surface around the valid joint space, L1 = L3 = L5 = {} mm",
                map.fixed
            ),
            ("sans-serif", 16),
        )
        .margin(10)
        .build_cartesian_3d(r(&map.l2), r(&map.l6), r(&map.l4))
        .map_err(draw_err)?;
    chart.with_projection(|mut p| {
        p.yaw = 0.6;
        p.pitch = 0.35;
        p.scale = 0.8;
        p.into_matrix()
    });
    chart
        .configure_axes()
        .x_labels(5)
        .y_labels(5)
        .z_labels(5)
        .light_grid_style(WHITE.mix(0.0))
        .draw()
        .map_err(draw_err)?;
    // The singular surface bounding the valid joint space: fold points met by continuation,
    // coloured by L6.
    let (lo6, hi6) = (map.l6[0], *map.l6.last().expect("grid"));
    chart
        .draw_series(map.folds.iter().map(|f| {
            Circle::new(
                (f[0], f[2], f[1]),
                1,
                scale((f[2] - lo6) / (hi6 - lo6)).filled(),
            )
        }))
        .map_err(draw_err)?;
    root.draw(&Text::new("axes: L2, L6 (vertical), L4 (mm); points: singular points (folds) bounding the start's branch, coloured by L6", (10, 580), ("sans-serif", 11)))
        .map_err(draw_err)?;
    root.present().map_err(draw_err)
}
