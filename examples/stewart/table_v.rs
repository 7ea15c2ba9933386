//! `stewart table-v`: Table V of the paper, measured.

use linkage_examples::case_study::sampling::Protocol;
use linkage_examples::case_study::table_v::{self, summarize, Report};
use linkage_examples::cli::stream::print;
use std::fmt::Write;

pub fn run(
    seed: u64,
    rotation: f64,
    translation: f64,
    json: bool,
    export: Option<&std::path::Path>,
) -> Result<(), String> {
    let protocol = Protocol {
        seed,
        rotation,
        translation,
        heave: 0.8 * translation,
        ..Protocol::default()
    };
    // The export file is created before the minutes of solving, so that a path that cannot
    // be written fails at once, not after them.
    let export = export
        .map(|path| {
            std::fs::File::create(path)
                .map(|file| (path, file))
                .map_err(|e| format!("{}: {e}", path.display()))
        })
        .transpose()?;
    let report = table_v::run(protocol, |stage| eprintln!("table-v: {stage}…"))
        .map_err(|e| format!("test points: {e}"))?;
    if let Some((path, file)) = export {
        write_points(&report, path, file)?;
    }
    if json {
        print(&format!("{}\n", table_v::to_json(&report)))
    } else {
        print(&table(&report))
    }
}

fn table(r: &Report) -> String {
    let mut out = String::new();
    // Writing to a String cannot fail.
    macro_rules! line {
        ($($t:tt)*) => { let _ = writeln!(out, $($t)*); };
    }
    let n = r.normal.len();
    for (label, pick) in [
        ("paper settings (accuracy 0.0005, ≤ 150 iterations)", 0),
        ("tight tolerance (1e-9 mm)", 1),
    ] {
        line!(
            "\nTable V, {label}: {} normal and {} near-singular points, seed {}",
            n,
            r.near.len(),
            r.protocol.seed
        );
        line!("{:<68}{:>14}{:>14}{:>14}", "", "PH", "NH", "NR");
        let s: Vec<table_v::Summary> = r
            .outcomes
            .iter()
            .map(|(_, paper, tight)| {
                let o = if pick == 0 { paper } else { tight };
                summarize(&o[..n], &o[n..])
            })
            .collect();
        let mut row = |name: &str, f: &dyn Fn(&table_v::Summary) -> String| {
            line!("{name:<68}{:>14}{:>14}{:>14}", f(&s[0]), f(&s[1]), f(&s[2]));
        };
        row(
            "near-singular points answered, relative error < 0.1 %",
            &|s| format!("{:.0} %", 100.0 * s.near_singular_ok_ratio),
        );
        row("average relative error, normal points", &|s| {
            format!("{:.2e}", s.normal_mean_rel_error)
        });
        row("average time per point (s)", &|s| {
            format!("{:.2e}", s.mean_time_s)
        });
        row(
            "answered but another branch (PH: ok, wrong; NH, NR: unverified)",
            &|s| s.wrong_branch.to_string(),
        );
        row(
            "answered, off truth, same branch by a nonsingular path (*)",
            &|s| s.path_dependent.to_string(),
        );
        row("ended with a fold (typed outcome)", &|s| {
            s.fold_reported.to_string()
        });
        row("ended otherwise, not answered", &|s| {
            s.other_failures.to_string()
        });
        row("normal points not solved", &|s| {
            s.normal_failures.to_string()
        });
        row("answers certified (Krawczyk): normal", &|s| {
            format!("{}/{}", s.normal_certified, s.normal_ok)
        });
        row("answers certified (Krawczyk): near-singular", &|s| {
            format!("{}/{}", s.near_singular_certified, s.near_singular_ok)
        });
    }
    line!(
        "\nnear-singular points whose straight joint-space segment leaves the valid joint space: {} of {}",
        r.segment_leaves_vjs,
        r.near.len()
    );
    let d = &r.detours;
    line!(
        "PH with detours around folds: {} of {} reached ({} at the true pivots, {} a second solution on the start's branch confirmed by continuation, {} wrong)",
        d.reached, d.folds, d.at_truth, d.path_dependent, d.wrong_branch
    );
    line!("answered: the tolerance met, status ok (PH) or unverified (NH and NR, which cannot establish the branch)");
    match &r.path_dependence {
        Ok(p) => {
            line!(
                "every real mode of the {} near-singular targets ({} solved completely, true pose among the roots in {}; {:.1} real roots each):",
                p.targets,
                p.complete,
                p.truth_found,
                p.real_roots as f64 / p.complete.max(1) as f64
            );
            line!(
                "  {} targets have another real root reached from home without a singularity ({} such roots by the straight pose path, {} by the joint-space segment only; {} other roots had the start's det B sign)",
                p.path_dependent_targets,
                p.by_pose_path,
                p.by_segment_only,
                p.same_sign_others
            );
        }
        Err(e) => {
            line!("every real mode of the near-singular targets: not examined ({e})");
        }
    }
    line!("(*) the straight joint-space segment reaches it with no sign change of det B (checked by fine continuation),");
    line!("    while the pose path reaches the true pose: two solutions on the start's branch (see README, Errata)");
    line!("paper (Table V): PH 100 % / 0.026 % / 3.203 s; NH 61 % / 0.024 % / 2.286 s; NR 10 % / 0.036 % / 0.208 s");
    out
}

/// The test points: kind, legs, true pose (Appendix B) and pivots (Eq. 19's order).
fn write_points(r: &Report, path: &std::path::Path, file: std::fs::File) -> Result<(), String> {
    use std::io::Write;
    let io = |e: std::io::Error| format!("{}: {e}", path.display());
    let mut w = std::io::BufWriter::new(file);
    let v_names: Vec<String> = (1..=18).map(|i| format!("v{i}")).collect();
    writeln!(
        w,
        "kind,L1,L2,L3,L4,L5,L6,yaw,pitch,roll,x,y,z,{}",
        v_names.join(",")
    )
    .map_err(io)?;
    for p in r.normal.iter().chain(&r.near) {
        let e = p.pose.euler();
        let t = p.pose.translation;
        let nums: Vec<String> =
            p.x.iter()
                .chain(&e)
                .chain(&t)
                .chain(&p.v)
                .map(|x| format!("{x:.15e}"))
                .collect();
        writeln!(
            w,
            "{},{}",
            if p.near_singular {
                "near_singular"
            } else {
                "normal"
            },
            nums.join(",")
        )
        .map_err(io)?;
    }
    w.flush().map_err(io)
}
