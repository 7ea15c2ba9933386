//! `stewart trajectory`: a smooth manoeuvre sampled at a fixed rate, legs from inverse
//! kinematics, for tracking tests and benchmarks.

use linkage::Pose;
use linkage_examples::stewart::{legs_for_pose, Stewart, HOME_POSE};
use std::io::Write;
use std::path::Path;

/// Heave, sway and a wobble at 0.5 Hz around the home pose, clear of singularities.
pub fn pose_at(t: f64) -> Pose {
    let w = 2.0 * std::f64::consts::PI * 0.5 * t;
    let [_, _, _, x, y, z] = HOME_POSE;
    Pose::from_euler(
        0.15 * w.sin(),
        0.1 * (2.0 * w).sin(),
        -0.08 * w.sin(),
        [
            x + 15.0 * w.sin(),
            y + 10.0 * (1.0 - w.cos()),
            z + 20.0 * w.sin(),
        ],
    )
}

pub fn run(out: &Path, seconds: f64, rate: f64) -> Result<(), String> {
    if !(seconds > 0.0 && rate > 0.0 && seconds * rate <= 1e7) {
        return Err("--seconds and --rate must be positive (at most 10 million samples)".into());
    }
    // Samples at t = 0, 1/rate, …, seconds (rounded to whole samples). A duration that rounds
    // to no step (`--seconds 1e-9` at 1 kHz) would write the home sample alone: no trajectory
    // to track, and not what was asked for. Refused before the file is created.
    let n = (seconds * rate).round();
    if n < 1.0 {
        return Err(format!(
            "--seconds {seconds} at --rate {rate} Hz is less than half a sample period: a trajectory needs at least two samples"
        ));
    }
    let n = n as usize;
    let sys = Stewart::new();
    let mut w = std::io::BufWriter::new(
        std::fs::File::create(out).map_err(|e| format!("cannot write {}: {e}", out.display()))?,
    );
    let io = |e: std::io::Error| e.to_string();
    writeln!(w, "t_s,L1,L2,L3,L4,L5,L6,yaw,pitch,roll,x,y,z").map_err(io)?;
    for k in 0..=n {
        let t = k as f64 / rate;
        let pose = pose_at(t);
        let (x, _) = legs_for_pose(&sys, &pose).ok_or("inverse kinematics failed")?;
        let [yaw, pitch, roll] = pose.euler();
        let p = pose.translation;
        writeln!(
            w,
            "{t:.6},{},{},{},{},{},{},{yaw:.12},{pitch:.12},{roll:.12},{:.9},{:.9},{:.9}",
            x[0], x[1], x[2], x[3], x[4], x[5], p[0], p[1], p[2]
        )
        .map_err(io)?;
    }
    w.flush().map_err(io)
}
