//! The paper's case study on the command line: the Stewart platform of Table III.
//!
//! ```text
//! cargo run --release --example stewart -- equations [--json]
//! cargo run --release --example stewart -- solve [--geometry FILE] [--method ph|nh|nr] [--track] --input legs.csv [--output out.csv]
//! ```

#[path = "stewart_cli/equations.rs"]
mod equations;
#[path = "stewart_cli/solve.rs"]
mod solve;

use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "stewart",
    about = "Forward kinematics of the Stewart platform of Gao & Wu (2015), Table III"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print the generated system F(v, x) = 0 (Eq. 19) and its Jacobian (Table A1).
    Equations {
        /// One JSON object: unknowns, inputs, equations, jacobian (1-based rows and columns).
        #[arg(long)]
        json: bool,
    },
    /// Solve forward kinematics for every row of a CSV of leg lengths (columns L1…L6).
    Solve(SolveArgs),
}

#[derive(clap::Args)]
pub struct SolveArgs {
    /// TOML geometry: `base`, `platform` (6 joint centres each) and `[start]` with `legs` and
    /// an optional `pose = [yaw, pitch, roll, x, y, z]`. Default: Table III, legs 170 mm.
    #[arg(long)]
    geometry: Option<PathBuf>,
    /// Solver: pseudo-arc-length continuation, Newton homotopy or Newton–Raphson.
    #[arg(long, value_enum, default_value_t = Method::Ph)]
    method: Method,
    /// Solve each row from the previous row's solution instead of from the start.
    #[arg(long)]
    track: bool,
    /// CSV with a header containing L1…L6 (mm); other columns are ignored.
    #[arg(long)]
    input: PathBuf,
    /// Where to write the result CSV (default: standard output).
    #[arg(long)]
    output: Option<PathBuf>,
    /// Convergence tolerance on the Newton correction, mm.
    #[arg(long, default_value_t = 1e-10)]
    tolerance: f64,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum Method {
    Ph,
    Nh,
    Nr,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Equations { json } => equations::run(json),
        Command::Solve(args) => solve::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
