//! `stewart modes`: every assembly mode — all real solutions of the forward kinematics — for
//! each row of a leg-length CSV, from all complex roots (`linkage::modes`).

use linkage::modes::{AllModes, EndpointKind, ModesOptions, Roots};
use linkage_examples::cli::geometry;
use linkage_examples::cli::legs_csv;
use linkage_examples::cli::stream::{print, refuse_overwriting};
use linkage_examples::stewart::{platform_is_coplanar, SixSix, Stewart, StewartGeneral};
use std::path::Path;

/// The capacity: 40 roots for a general 6-6 platform, with room to report a geometry that
/// (wrongly) seems to have more.
pub const CAPACITY: usize = 64;

/// `png`: where to draw the real modes of which row (1-based).
pub fn run(
    geometry: Option<&Path>,
    input: &Path,
    json: bool,
    png: Option<(&Path, usize)>,
) -> Result<(), String> {
    if let Some((file, _)) = png {
        let mut inputs = vec![input];
        inputs.extend(geometry);
        refuse_overwriting(Some(file), &inputs)?;
        // The picture is a PNG whatever the name; a name that says otherwise is a mistake
        // (the drawing library would pick its format from the extension, or fail without one).
        let png_named = file
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png"));
        if !png_named {
            return Err(format!(
                "--png {}: the picture is written as PNG; name the file *.png",
                file.display()
            ));
        }
    }
    let rows = legs_csv::read(input)?;
    if let Some((_, row)) = png {
        if row > rows.len() {
            return Err(format!(
                "--row {row}: {} has {} rows",
                input.display(),
                rows.len()
            ));
        }
    }
    match geometry {
        None => run_on(table_iii(&rows)?, &rows, json, png),
        Some(path) => {
            let (base, platform) = geometry::load_joints(path)?;
            // Coplanar platforms use Eq. 19's form; others the general, mirror-free form.
            if platform_is_coplanar(&platform) {
                let sys = Stewart::with_joints(&base, &platform)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                run_on(solver(sys, &rows)?, &rows, json, png)
            } else {
                let sys = StewartGeneral::with_joints(&base, &platform)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                run_on(solver(sys, &rows)?, &rows, json, png)
            }
        }
    }
}

/// The solver for `sys`, its start set found by monodromy and moved near the mean of the
/// valid rows (shorter paths).
pub fn solver<S: SixSix>(
    sys: S,
    rows: &[legs_csv::Row],
) -> Result<Box<AllModes<S, 18, 6, CAPACITY>>, String> {
    let modes = Box::new(
        AllModes::new(sys, &ModesOptions::default())
            .map_err(|e| format!("start solutions: {e}"))?,
    );
    Ok(recentred(modes, rows))
}

/// The Table III platform's solver from its stored start set (no monodromy), moved near the
/// mean of the valid rows.
pub fn table_iii(
    rows: &[legs_csv::Row],
) -> Result<Box<AllModes<Stewart, 18, 6, CAPACITY>>, String> {
    let modes = Box::new(
        linkage_examples::start_sets::table_iii()
            .map_err(|e| format!("stored start solutions: {e}"))?,
    );
    Ok(recentred(modes, rows))
}

/// Row `x` with a leg beyond the bound `stewart solve` puts on legs (`MAX_LEG_OVER_SIZE` times
/// the mechanism's size): `invalid_input`, not a query whose every path fails.
fn absurd<S: SixSix>(sys: &S, x: &[f64; 6]) -> bool {
    let max_leg = crate::solve::MAX_LEG_OVER_SIZE * crate::solve::mechanism_size(sys);
    x.iter().any(|l| *l > max_leg)
}

fn recentred<S: SixSix>(
    mut modes: Box<AllModes<S, 18, 6, CAPACITY>>,
    rows: &[legs_csv::Row],
) -> Box<AllModes<S, 18, 6, CAPACITY>> {
    let valid: Vec<&[f64; 6]> = rows
        .iter()
        .filter_map(|r| r.as_ref().ok())
        .filter(|x| !absurd(modes.mechanism(), x))
        .collect();
    if !valid.is_empty() {
        let mut centre = [0.0; 6];
        for x in &valid {
            for i in 0..6 {
                centre[i] += x[i] / valid.len() as f64;
            }
        }
        // A failure leaves the start set where it was: queries are then longer, not wrong.
        let _ = modes.recenter(&centre, 0.1, 1);
    }
    modes
}

fn run_on<S: SixSix>(
    modes: Box<AllModes<S, 18, 6, CAPACITY>>,
    rows: &[legs_csv::Row],
    json: bool,
    png: Option<(&Path, usize)>,
) -> Result<(), String> {
    let mut roots = Box::new(Roots::<18, CAPACITY>::new());
    for (i, row) in rows.iter().enumerate() {
        let n = i + 1;
        let result = match row {
            Ok(x) if absurd(modes.mechanism(), x) => Err("invalid_input"),
            Ok(x) => modes.solve(x, &mut roots).map_err(|e| match e {
                linkage::modes::ModesError::InvalidInput { .. } => "invalid_input",
                _ => "non_finite",
            }),
            Err(word) => Err(*word),
        };
        if let Some((file, _)) = png.filter(|(_, r)| *r == n) {
            let Ok(x) = row else {
                return Err(format!("--row {n}: the row is not valid legs"));
            };
            if result.is_err() {
                return Err(format!("--row {n}: the row could not be solved"));
            }
            crate::modes_png::draw(modes.mechanism(), x, roots.real(), n, file)?;
            eprintln!("modes: wrote {}", file.display());
        }
        match result {
            Err(word) => {
                if json {
                    let out = serde_json::json!({
                        "row": n, "status": word, "complex": null, "real": [],
                    });
                    print(&format!("{out}\n"))?;
                } else {
                    print(&format!("row {n}: {word}\n"))?;
                }
            }
            Ok(()) if json => print(&format!("{}\n", row_json(n, &modes, &roots)))?,
            Ok(()) => print_row(n, &modes, &roots)?,
        }
    }
    Ok(())
}

fn row_json<S: SixSix>(
    n: usize,
    modes: &AllModes<S, 18, 6, CAPACITY>,
    roots: &Roots<18, CAPACITY>,
) -> serde_json::Value {
    let real: Vec<serde_json::Value> = roots
        .real()
        .iter()
        .filter_map(|r| {
            let p = r.pose?;
            let [yaw, pitch, roll] = p.euler();
            let t = p.translation;
            Some(serde_json::json!({
                "yaw": yaw, "pitch": pitch, "roll": roll, "x": t[0], "y": t[1], "z": t[2],
                "det_sign": r.det_sign(), "residual": r.residual, "nearest": r.nearest,
                "nearest_real": finite(r.nearest_real),
            }))
        })
        .collect();
    serde_json::json!({
        "row": n,
        "status": if roots.is_complete() { "ok" } else { "incomplete" },
        "paths": modes.start_count(),
        "complex": roots.roots(),
        "singular": roots.count(EndpointKind::Singular),
        "diverging": roots.count(EndpointKind::Diverging),
        "failed": roots.count(EndpointKind::Failed) + roots.count(EndpointKind::Duplicate),
        "real": real,
    })
}

/// JSON has no infinity: no other real root is `null`.
fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

fn print_row<S: SixSix>(
    n: usize,
    modes: &AllModes<S, 18, 6, CAPACITY>,
    roots: &Roots<18, CAPACITY>,
) -> Result<(), String> {
    let mut text = format!(
        "row {n}: {} of {} paths end at roots, {} real{}\n",
        roots.roots(),
        modes.start_count(),
        roots.real().len(),
        if roots.is_complete() {
            String::new()
        } else {
            format!(
                " ({} singular, {} diverging, {} failed)",
                roots.count(EndpointKind::Singular),
                roots.count(EndpointKind::Diverging),
                roots.count(EndpointKind::Failed) + roots.count(EndpointKind::Duplicate)
            )
        }
    );
    text.push_str("  yaw        pitch      roll       x          y          z          det  residual  nearest\n");
    for r in roots.real() {
        let Some(p) = r.pose else { continue };
        let [yaw, pitch, roll] = p.euler();
        let t = p.translation;
        text.push_str(&format!(
            "  {yaw:<10.6} {pitch:<10.6} {roll:<10.6} {:<10.4} {:<10.4} {:<10.4} {:>3}  {:.1e}   {:.3}\n",
            t[0],
            t[1],
            t[2],
            if r.det < 0.0 { "-" } else { "+" },
            r.residual,
            r.nearest
        ));
    }
    print(&text)
}
