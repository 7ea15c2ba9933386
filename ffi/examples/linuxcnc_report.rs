//! Checks what LinuxCNC reported while test.sh drove the simulated hexapod, and prints the
//! linkagehexkins and genhexkins runs of each path side by side.
//!
//! ```text
//! linuxcnc_report GEOMETRY.hal PATH_NAME PATH_FILE OURS.csv GENHEX.csv [PATH_NAME PATH_FILE OURS.csv GENHEX.csv]...
//! ```
//!
//! Every sample holds the joint feedback and the Cartesian feedback LinuxCNC's motion
//! controller computed from it with the module's kinematicsForward. The check runs our
//! inverse kinematics (linkage's) on that pose: it must give back the joints. In coordinated
//! moves the pose must also follow the commanded one (to a few servo cycles of lag). The
//! A path with a HAL file of its own beside it (PATH with the extension `.hal`) sets the
//! strut correction there; the check's inverse kinematics then adds it too. One beside it
//! for linkagehexkins alone (`.linkagehexkins.hal`) that switches `certify` on makes every
//! answered sample of that path require the module's certified pin. The
//! linkagehexkins runs must pass every check; the genhexkins runs are measured the same way
//! and reported. Ends with one line starting `linuxcnc:`; exits 1 if a check failed.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::ExitCode;

use linkage_ffi::{Hexapod, LinkageGeometry, LinkagePose, LinkageStrutCorrection};

/// |IK(pose) − joints| above this (inches) is a wrong pose.
const LEG_TOLERANCE: f64 = 1e-6;
/// Feedback further than this from the command in a coordinated move (inches, degrees) is
/// off the path: the lag at these feeds is a few servo cycles, well below it.
const LAG_LINEAR: f64 = 0.05;
const LAG_ANGULAR: f64 = 0.5;
/// A step with fewer samples did not really run.
const MIN_SAMPLES: usize = 20;

struct Sample {
    /// Where it is: the CSV file and line.
    at: String,
    step: usize,
    joints: [f64; 6],
    pose: LinkagePose,
    command: LinkagePose,
    /// The fwd-kins-fail pin was set, or (linkagehexkins) a forward call failed since the
    /// sample before: LinuxCNC then kept the last good Cartesian feedback, which is stale.
    fail: bool,
    /// linkagehexkins' proximity pin (NaN for genhexkins).
    proximity: f64,
    /// linkagehexkins' last-failure pin when a call failed since the sample before.
    failure: Option<i32>,
    /// linkagehexkins' certified pin: the last forward step was proven.
    certified: bool,
}

#[derive(Clone)]
struct Stats {
    samples: usize,
    failed: usize,
    /// linkagehexkins' failed calls seen, by status code.
    failures: BTreeMap<i32, usize>,
    /// Samples whose step was certified (linkagehexkins' certified pin).
    certified: usize,
    /// Samples whose pose and joints came from adjacent servo cycles ([`torn_read`]): not
    /// checked against each other, and not in `max_leg_error`.
    torn: usize,
    /// Samples whose pose is wrong though the pin says success (it does not give back the
    /// joints), or, in coordinated moves, is off the commanded pose; each counted once.
    bad: usize,
    max_leg_error: f64,
    max_lag: f64,
    max_lag_angle: f64,
    /// The smallest proximity pin value seen (NaN if none).
    min_proximity: f64,
}

impl Default for Stats {
    fn default() -> Self {
        Stats {
            samples: 0,
            failed: 0,
            failures: BTreeMap::new(),
            certified: 0,
            torn: 0,
            bad: 0,
            max_leg_error: 0.0,
            max_lag: 0.0,
            max_lag_angle: 0.0,
            min_proximity: f64::NAN,
        }
    }
}

impl Stats {
    fn add(&mut self, o: &Stats) {
        self.samples += o.samples;
        self.failed += o.failed;
        self.certified += o.certified;
        self.torn += o.torn;
        for (code, n) in &o.failures {
            *self.failures.entry(*code).or_default() += n;
        }
        self.bad += o.bad;
        self.max_leg_error = self.max_leg_error.max(o.max_leg_error);
        self.max_lag = self.max_lag.max(o.max_lag);
        self.max_lag_angle = self.max_lag_angle.max(o.max_lag_angle);
        self.min_proximity = self.min_proximity.min(o.min_proximity);
    }
}

/// The `setp PIN VALUE` lines of a HAL file: each pin name's dot-separated parts after the
/// prefix, and the value.
fn setps(file: &str) -> Result<Vec<(Vec<String>, f64)>, String> {
    let text = std::fs::read_to_string(file).map_err(|e| format!("{file}: {e}"))?;
    let mut out = Vec::new();
    for line in text.lines().filter(|l| l.starts_with("setp ")) {
        let mut words = line.split_whitespace().skip(1);
        let (Some(name), Some(value)) = (words.next(), words.next()) else {
            return Err(format!("{file}: `{line}` is not `setp PIN VALUE`"));
        };
        let value: f64 = value
            .parse()
            .map_err(|_| format!("{file}: bad value in `{line}`"))?;
        out.push((name.split('.').skip(1).map(str::to_string).collect(), value));
    }
    Ok(out)
}

/// Writes `value` into `table[i][axis]` for the parts `[_, i, axis]`.
fn set_vector(table: &mut [[f64; 3]; 6], parts: &[String], value: f64) -> Option<()> {
    let i: usize = parts.get(1)?.parse().ok()?;
    let k = ["x", "y", "z"]
        .iter()
        .position(|a| Some(*a) == parts.get(2).map(|s| s.as_str()))?;
    *table.get_mut(i)?.get_mut(k)? = value;
    Some(())
}

fn geometry(file: &str) -> Result<LinkageGeometry, String> {
    let mut g = LinkageGeometry {
        base: [[f64::NAN; 3]; 6],
        platform: [[f64::NAN; 3]; 6],
    };
    for (parts, value) in setps(file)? {
        let target = match parts.first().map(|s| s.as_str()) {
            Some("base") => &mut g.base,
            Some("platform") => &mut g.platform,
            _ => continue,
        };
        set_vector(target, &parts, value).ok_or(format!("{file}: bad pin {}", parts.join(".")))?;
    }
    if g.base
        .iter()
        .chain(&g.platform)
        .flatten()
        .any(|v| v.is_nan())
    {
        return Err(format!("{file}: not every joint centre is set"));
    }
    Ok(g)
}

/// The strut correction a path's own HAL file sets (every joint axis and the screw lead),
/// or None when the path has no HAL file.
fn strut_correction(path: &str) -> Result<Option<LinkageStrutCorrection>, String> {
    let file = Path::new(path).with_extension("hal");
    if !file.exists() {
        return Ok(None);
    }
    let file = file.to_string_lossy().into_owned();
    let mut c = LinkageStrutCorrection {
        base_n: [[f64::NAN; 3]; 6],
        platform_n: [[f64::NAN; 3]; 6],
        screw_lead: f64::NAN,
    };
    for (parts, value) in setps(&file)? {
        let set = match parts.first().map(|s| s.as_str()) {
            Some("screw-lead") => {
                c.screw_lead = value;
                Some(())
            }
            Some("base-n") => set_vector(&mut c.base_n, &parts, value),
            Some("platform-n") => set_vector(&mut c.platform_n, &parts, value),
            _ => Some(()),
        };
        set.ok_or(format!("{file}: bad pin {}", parts.join(".")))?;
    }
    let all = c.base_n.iter().chain(&c.platform_n).flatten();
    if c.screw_lead.is_nan() || all.clone().any(|v| v.is_nan()) {
        return Err(format!("{file}: the screw lead or a joint axis is not set"));
    }
    Ok(Some(c))
}

fn samples(file: &str) -> Result<Vec<Sample>, String> {
    let text = std::fs::read_to_string(file).map_err(|e| format!("{file}: {e}"))?;
    if let Some(e) = text.lines().find(|l| l.starts_with("# error")) {
        return Err(format!("{file}: the run stopped: {e}"));
    }
    let mut out = Vec::new();
    // Failures before the first sample (the module is called before homing, at zero legs)
    // are not any sample's.
    let mut failures = f64::NAN;
    for (n, line) in text.lines().enumerate().skip(1) {
        let v: Vec<f64> = line
            .split(',')
            .map(|w| w.parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("{file}:{}: not a sample", n + 1))?;
        if v.len() != 25 {
            return Err(format!("{file}:{}: {} fields, not 25", n + 1, v.len()));
        }
        let failed_since = !failures.is_nan() && v[22] != failures;
        failures = v[22];
        let pose = |i: usize| LinkagePose {
            x: v[i],
            y: v[i + 1],
            z: v[i + 2],
            a: v[i + 3],
            b: v[i + 4],
            c: v[i + 5],
        };
        out.push(Sample {
            at: format!("{file}:{}", n + 1),
            step: v[0] as usize,
            joints: std::array::from_fn(|j| v[2 + j]),
            pose: pose(8),
            command: pose(14),
            fail: v[20] != 0.0 || failed_since,
            proximity: v[21],
            failure: failed_since.then_some(v[23] as i32),
            certified: v[24] != 0.0,
        });
    }
    Ok(out)
}

/// Most servo cycles between two readings of the status that the torn-read rule considers.
const MAX_CYCLES: usize = 8;

/// The nearest readings before and after sample `n`, in its step, whose joints differ from
/// its own (the status is sampled more often than the servo cycle updates it: neighbours
/// may repeat the same copy).
fn neighbours(samples: &[Sample], n: usize) -> Option<(&[f64; 6], &[f64; 6])> {
    let s = &samples[n];
    let same_step = |t: &&Sample| t.step == s.step;
    let other = |t: &&Sample| t.joints != s.joints;
    let before = samples[..n]
        .iter()
        .rev()
        .take_while(same_step)
        .find(other)?;
    let after = samples[n + 1..].iter().take_while(same_step).find(other)?;
    Some((&before.joints, &after.joints))
}

/// Whether sample `n`'s disagreement with its pose is a copy of the motion status torn across
/// a servo cycle, not a wrong pose. `legs` is the inverse kinematics of the pose. Seen: the
/// whole pose a cycle ahead of the joints (no forward kinematics can give that, since it only
/// ever sees the joints of its own cycle), and one strut's joint a cycle behind the other
/// five while the pose agreed with those five to 1e-10. So each leg must either equal its
/// joint (to the wrong-pose tolerance) or differ from it by exactly one cycle's motion of that
/// joint, forward or back, with the same numbers of cycles `m1` from the reading before to
/// this one and `m2` from this one to the reading after for every joint.
///
/// One cycle's motion is bounded by the motion around it: the cycle after this reading (a pose
/// ahead) and the one before it (a pose behind) each moved the joint by between its mean
/// motion per cycle before the reading and after it, as long as the joint does not change
/// from speeding up to slowing down within those few cycles; 2 % of the larger is allowed
/// beyond that (the 40 torn reads of 13 recorded runs of `test.sh` needed 0.2 % at most). A
/// single mean over both sides, as this rule used first, missed a pose a cycle ahead where
/// one strut was slowing down (its motion per cycle 1.53e-4 in before the reading and
/// 1.34e-4 after it, the pose's legs 1.38e-4 ahead of its joint: 4.8e-6 in off the mean of
/// both sides, against an allowance of 3.9e-6; every moving strut's difference lay between its
/// two sides; CI, 2026-11-30). A pose off by anything else is wrong, not torn.
fn torn_read(legs: &[f64; 6], samples: &[Sample], n: usize) -> bool {
    let Some((a, b)) = neighbours(samples, n) else {
        return false;
    };
    let joints = &samples[n].joints;
    let one_cycle = |i: usize, m1: usize, m2: usize| {
        let before = (joints[i] - a[i]) / m1 as f64;
        let after = (b[i] - joints[i]) / m2 as f64;
        let slack = LEG_TOLERANCE + 0.02 * before.abs().max(after.abs());
        let (low, high) = (before.min(after) - slack, before.max(after) + slack);
        let r = legs[i] - joints[i];
        r.abs() <= LEG_TOLERANCE || (low..=high).contains(&r) || (low..=high).contains(&-r)
    };
    (1..=MAX_CYCLES).any(|m1| (1..=MAX_CYCLES).any(|m2| (0..6).all(|i| one_cycle(i, m1, m2))))
}

/// Each step's statistics; `show` prints the first wrong samples (for linkagehexkins, whose
/// runs must have none).
fn measure(
    hex: &Hexapod,
    samples: &[Sample],
    coordinated: &dyn Fn(usize) -> bool,
    show: bool,
) -> Vec<Stats> {
    let steps = samples.iter().map(|s| s.step).max().unwrap_or(0) + 1;
    let mut stats = vec![Stats::default(); steps];
    for (n, s) in samples.iter().enumerate() {
        let st = &mut stats[s.step];
        st.samples += 1;
        st.min_proximity = st.min_proximity.min(s.proximity);
        if s.fail {
            st.failed += 1;
        }
        if let Some(code) = s.failure {
            *st.failures.entry(code).or_default() += 1;
        }
        st.certified += usize::from(s.certified);
        let legs = hex.inverse(&s.pose).ok();
        let error = legs.map_or(f64::INFINITY, |legs| {
            (0..6)
                .map(|i| (legs[i] - s.joints[i]).abs())
                .fold(0.0, f64::max)
        });
        let torn =
            !(error <= LEG_TOLERANCE) && legs.is_some_and(|legs| torn_read(&legs, samples, n));
        if torn {
            st.torn += 1;
        } else {
            st.max_leg_error = st.max_leg_error.max(error);
        }
        let mut bad = !s.fail && !torn && !(error <= LEG_TOLERANCE);
        if coordinated(s.step) {
            let (p, q) = (&s.pose, &s.command);
            let lag = [p.x - q.x, p.y - q.y, p.z - q.z]
                .iter()
                .fold(0.0f64, |m, d| m.max(d.abs()));
            let turn = [p.a - q.a, p.b - q.b, p.c - q.c]
                .iter()
                .fold(0.0f64, |m, d| m.max(d.abs()));
            st.max_lag = st.max_lag.max(lag);
            st.max_lag_angle = st.max_lag_angle.max(turn);
            bad |= !(lag <= LAG_LINEAR && turn <= LAG_ANGULAR);
        }
        st.bad += usize::from(bad);
        // The first few, for whoever has to find out why.
        if show && bad && st.bad <= 3 {
            println!(
                "wrong or off-path: {} |IK(pose) - joints| {error:.1e}, pose {:?}, command {:?}",
                s.at, s.pose, s.command
            );
        }
    }
    stats
}

fn cell(s: &Stats) -> String {
    format!(
        "{:>6} {:>6} {:>6} {:>9.1e} {:>7.3}",
        s.samples,
        s.failed,
        s.bad,
        s.max_leg_error,
        s.max_lag.max(s.max_lag_angle)
    )
}

fn run() -> Result<bool, String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 5 || args.len() % 4 != 1 {
        return Err(
            "usage: linuxcnc_report GEOMETRY.hal (NAME PATH OURS.csv GENHEX.csv)...".into(),
        );
    }
    let hex = Hexapod::new(&geometry(&args[0])?).map_err(|c| format!("geometry: status {c}"))?;
    let (mut ours_all, mut theirs_all) = (Stats::default(), Stats::default());
    let mut ok = true;
    let mut problems = Vec::new();
    println!("columns per module: samples, fwd-kins-fail samples, wrong or off-path samples,");
    println!(
        "max |IK(pose) - joints| (in), max |pose - command| in coordinated moves (in or deg),"
    );
    println!(
        "and for linkagehexkins the smallest value of its proximity pin, |det B| / |det B at home|"
    );
    for chunk in args[1..].chunks_exact(4) {
        let [name, path, ours, theirs] = chunk else {
            continue;
        };
        let commands: Vec<String> = std::fs::read_to_string(path)
            .map_err(|e| format!("{path}: {e}"))?
            .lines()
            .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
            .map(str::to_string)
            .collect();
        let coordinated =
            |step: usize| step > 0 && commands.get(step - 1).is_some_and(|c| c.starts_with("mdi"));
        let mut hex = hex.clone();
        let correction = strut_correction(path)?;
        if let Some(c) = &correction {
            hex.set_strut_correction(c)
                .map_err(|code| format!("{path}: strut correction: status {code}"))?;
        }
        let a = measure(&hex, &samples(ours)?, &coordinated, true);
        let b = measure(&hex, &samples(theirs)?, &coordinated, false);
        println!("\npath {name} ({path})");
        if let Some(c) = correction {
            println!("with screw-driven struts (lead {} per turn)", c.screw_lead);
        }
        // linkagehexkins proves every step on a path whose own pins for it switch `certify` on.
        let certify = std::fs::read_to_string(Path::new(path).with_extension("linkagehexkins.hal"))
            .is_ok_and(|t| t.lines().any(|l| l.starts_with("setp PREFIX.certify 1")));
        if certify {
            println!("linkagehexkins proving every step (certify)");
        }
        let mut ours_path = Stats::default();
        let width = commands.iter().map(String::len).max().unwrap_or(0).max(34);
        println!(
            "{:<width$} | {:^47} | {:^38}",
            "step", "linkagehexkins", "genhexkins"
        );
        for step in 0..=commands.len() {
            let label = if step == 0 {
                "home".to_string()
            } else {
                commands[step - 1].clone()
            };
            let (sa, sb) = (
                a.get(step).cloned().unwrap_or_default(),
                b.get(step).cloned().unwrap_or_default(),
            );
            println!(
                "{:<width$} | {} {:>8.1e} | {}",
                label,
                cell(&sa),
                sa.min_proximity,
                cell(&sb)
            );
            if step > 0 && sa.samples < MIN_SAMPLES {
                problems.push(format!("{name} step {step}: only {} samples", sa.samples));
            }
            ours_path.add(&sa);
            theirs_all.add(&sb);
        }
        let answered = ours_path.samples - ours_path.failed;
        if certify {
            println!(
                "linkagehexkins: {} of {answered} answered samples certified",
                ours_path.certified
            );
            if ours_path.certified != answered {
                problems.push(format!(
                    "{name}: {} answered samples not certified",
                    answered - ours_path.certified
                ));
            }
        } else if ours_path.certified > 0 {
            problems.push(format!("{name}: certified samples without certify"));
        }
        ours_all.add(&ours_path);
    }
    if !(ours_all.min_proximity > 0.0) {
        problems.push("the proximity pin was not read or not positive".to_string());
    }
    if ours_all.failed > 0 {
        let codes: Vec<String> = ours_all
            .failures
            .iter()
            .map(|(code, n)| format!("status {code} after {n} samples"))
            .collect();
        problems.push(format!(
            "{} samples with fwd-kins-fail or after a failed call ({})",
            ours_all.failed,
            codes.join(", ")
        ));
    }
    if ours_all.bad > 0 || !(ours_all.max_leg_error <= LEG_TOLERANCE) {
        problems.push(format!(
            "{} wrong or off-path samples (max |IK(pose) - joints| {:.1e})",
            ours_all.bad, ours_all.max_leg_error
        ));
    }
    if !problems.is_empty() {
        ok = false;
        println!("\nlinkagehexkins failed: {}", problems.join("; "));
    }
    println!(
        "\nlinuxcnc: {} — linkagehexkins: {} samples, {} failed, {} wrong or off-path, {} torn reads, {} certified, max |IK(pose) - joints| {:.1e} in, proximity down to {:.1e}; \
         genhexkins: {} samples, {} failed, {} wrong or off-path, {} torn reads, feedback up to {:.3} off the command",
        if ok { "ok" } else { "FAILED" },
        ours_all.samples, ours_all.failed, ours_all.bad, ours_all.torn, ours_all.certified, ours_all.max_leg_error, ours_all.min_proximity,
        theirs_all.samples, theirs_all.failed, theirs_all.bad, theirs_all.torn,
        theirs_all.max_lag.max(theirs_all.max_lag_angle),
    );
    Ok(ok)
}

fn main() -> ExitCode {
    match run() {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("linuxcnc_report: {e}");
            println!("linuxcnc: FAILED — {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reading(joints: [f64; 6]) -> Sample {
        Sample {
            at: String::new(),
            step: 5,
            joints,
            pose: LinkagePose::default(),
            command: LinkagePose::default(),
            fail: false,
            proximity: 1.0,
            failure: None,
            certified: true,
        }
    }

    const BEFORE: [f64; 6] = [
        30.5215620195,
        29.1480816421,
        30.146714726,
        29.5463634248,
        30.3167358874,
        29.0953812795,
    ];
    const STALE: [f64; 6] = [
        30.5229497925,
        29.1477759265,
        30.146714726,
        29.5463634248,
        30.3182456295,
        29.0919625224,
    ];
    const AFTER: [f64; 6] = [
        30.5242978558,
        29.1475088584,
        30.146714726,
        29.5463634248,
        30.3197156383,
        29.088583648,
    ];
    /// The inverse kinematics of the third reading's pose.
    const LEGS: [f64; 6] = [
        30.52362878733301,
        29.147637572915936,
        30.14671472599484,
        29.546363424814306,
        30.31898560010857,
        29.09026809994192,
    ];

    /// Four readings of CI's workspace run on 2026-11-30 (`workspace-linkagehexkins.csv`,
    /// lines 6041–6044, t = 7.8343 … 7.8379 s): the third repeats the second's joints (a stale
    /// copy) while its pose, the command's to 1e-11, is a cycle ahead; strut 1 is slowing down.
    fn window() -> Vec<Sample> {
        [BEFORE, STALE, STALE, AFTER].map(reading).into()
    }

    #[test]
    fn a_pose_a_cycle_ahead_of_a_slowing_strut_is_a_torn_read() {
        assert!(torn_read(&LEGS, &window(), 2));
    }

    #[test]
    fn a_pose_off_by_other_than_a_cycle_is_not_a_torn_read() {
        // Strut 1 three cycles' motion ahead, the rest as recorded: no cycle counts on either
        // side make that one cycle's motion.
        let mut legs = LEGS;
        legs[1] = STALE[1] - 4.2e-4;
        assert!(!torn_read(&legs, &window(), 2));
        // Another assembly mode's legs are nowhere near.
        assert!(!torn_read(&LEGS.map(|l| l + 0.1), &window(), 2));
        // Without a moving reading on both sides there is nothing to compare with.
        let still: Vec<Sample> = [STALE, STALE, AFTER].map(reading).into();
        assert!(!torn_read(&LEGS, &still, 1));
    }
}
