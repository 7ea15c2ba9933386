//! What the small example binaries show: a mechanism's generated system, then one forward-
//! kinematics solve from its home configuration.

use linkage::{arc_length, pose_from_unknowns, Mechanism, Options, SolveError, Start};

/// Prints `listing`, then solves for the home inputs moved by `step` and prints the pose.
/// Returns the process exit code.
pub fn show<S: Mechanism<N, M>, const N: usize, const M: usize>(
    listing: &str,
    sys: &S,
    start: Result<Start<N, M>, SolveError>,
    step: f64,
) -> std::process::ExitCode {
    println!("{listing}");
    let start = match start {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: home configuration: {e}");
            return std::process::ExitCode::FAILURE;
        }
    };
    let target = start.x().map(|q| q + step);
    match arc_length(sys, &start, &target, &Options::TIGHT) {
        Ok(sol) => {
            let pose = pose_from_unknowns(sys, &sol.v);
            println!(
                "inputs {target:.4?} -> {} ({:?})",
                sol.status,
                pose.map(|p| (p.euler(), p.translation))
            );
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
