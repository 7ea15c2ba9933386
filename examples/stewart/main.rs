//! The paper's case study on the command line: the Stewart platform of Table III.
//!
//! ```text
//! cargo run --release --example stewart -- equations [--json]
//! cargo run --release --example stewart -- solve [--geometry FILE] [--method ph|nh|nr] [--track] [--certify] [--modes-within MM] --input legs.csv|- [--output out.csv]
//! cargo run --release --example stewart -- modes [--geometry FILE] --input legs.csv|- [--json] [--png FILE [--row N]]
//! cargo run --release --example stewart -- table-v [--seed S] [--json]
//! cargo run --release --example stewart -- map --out DIR
//! cargo run --release --example stewart -- errors --out DIR
//! ```

mod args;
mod bench;
mod equations;
mod errors;
mod map;
mod mode_check;
mod modes;
mod modes_png;
mod plot;
mod solve;
mod table_v;
mod trajectory;

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
    /// Every assembly mode (all real solutions, from all complex roots) per row of leg lengths.
    Modes {
        /// TOML geometry: `base` and `platform` (6 joint centres each); `[start]` may be
        /// omitted. Default: Table III.
        #[arg(long)]
        geometry: Option<PathBuf>,
        /// CSV with a header containing L1…L6 (mm); `-` reads standard input.
        #[arg(long)]
        input: PathBuf,
        /// One JSON object per row: {"row", "status", "paths", "complex", "real": [{"yaw",
        /// "pitch", "roll", "x", "y", "z", "det_sign", "residual", "nearest", ...}], ...}.
        #[arg(long)]
        json: bool,
        /// Also draw every real mode of row --row side by side, as PNG.
        #[arg(long)]
        png: Option<PathBuf>,
        /// The row --png draws (1-based). Only with --png: alone it would be ignored, and
        /// every row printed as if it had not been given.
        #[arg(long, requires = "png", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
        row: u64,
    },
    /// Reproduce Table V: 100 normal and 100 near-singular points solved by PH, NH and NR.
    TableV {
        /// Seed of the test-point generator.
        #[arg(long, default_value_t = 2015)]
        seed: u64,
        /// One JSON object: {"methods": {"PH": {...}, "NH": {...}, "NR": {...}}, ...}.
        #[arg(long)]
        json: bool,
        /// Half-width of the sampled box in yaw, pitch and roll (rad, at most π).
        #[arg(long, default_value_t = 0.35, allow_hyphen_values = true, value_parser = args::angle)]
        rotation: f64,
        /// Half-width of the sampled box in x and y (mm); z uses 0.8 of it.
        #[arg(long, default_value_t = 50.0, allow_hyphen_values = true, value_parser = args::positive)]
        translation: f64,
        /// Also write the test points (legs, true pose and pivots) to this CSV.
        #[arg(long)]
        export: Option<PathBuf>,
    },
    /// Write a smooth manoeuvre around home, sampled at --rate Hz, as a leg-length CSV.
    Trajectory {
        #[arg(long)]
        out: PathBuf,
        #[arg(long, default_value_t = 2.0, allow_hyphen_values = true, value_parser = args::positive)]
        seconds: f64,
        #[arg(long, default_value_t = 1000.0, allow_hyphen_values = true, value_parser = args::positive)]
        rate: f64,
    },
    /// Draw Fig. 6 (det B over L2 × L4 for L6 = 190…250 mm) and a Fig. 5-style view, as PNG.
    Map {
        #[arg(long, default_value = "figures")]
        out: PathBuf,
    },
    /// Time per solve over every row of a leg-length CSV (from the start, or tracking).
    Bench {
        /// `all`: every assembly mode per row (`stewart modes`).
        #[arg(long, value_enum, default_value_t = BenchMethod::Nr)]
        method: BenchMethod,
        /// TOML geometry for `--method all` (`[start]` optional). Default: Table III.
        #[arg(long)]
        geometry: Option<PathBuf>,
        /// Solve each row from the previous row's solution (PH: the trajectory tracker).
        #[arg(long)]
        track: bool,
        /// CSV with a header containing L1…L6 (mm); `-` reads standard input.
        #[arg(long)]
        input: PathBuf,
        /// {"method", "points", "mean_us", "median_us", "p99_us", ...}
        #[arg(long)]
        json: bool,
        /// Use the dense-LU baseline instead of the generated elimination.
        #[arg(long)]
        dense: bool,
        /// Time each solve with its certificate (with `--track`: each step proven).
        #[arg(long)]
        certify: bool,
        /// Least time to spend timing, in seconds (at least 3 passes over the rows whatever it
        /// is; timing stops early, and says so, after 4 194 304 timed solves).
        #[arg(long, default_value_t = 1.0, value_parser = timing_seconds)]
        seconds: f64,
        /// Run the solvers as built for the plain target, not their x86-64-v3 twin (the
        /// answers are the same; the time is that of a CPU without AVX2).
        #[arg(long)]
        as_built: bool,
    },
    /// Draw Fig. 7 (relative error per test point and method) as PNG.
    Errors {
        #[arg(long, default_value = "figures")]
        out: PathBuf,
        #[arg(long, default_value_t = 2015)]
        seed: u64,
    },
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
    /// CSV with a header containing L1…L6 (mm) once each; other columns are ignored. `-` reads
    /// standard input. Rows are solved and written one at a time, as they arrive.
    #[arg(long)]
    input: PathBuf,
    /// Where to write the result CSV (default: standard output).
    #[arg(long)]
    output: Option<PathBuf>,
    /// Convergence tolerance on the Newton correction, mm (above 0, at most 1).
    #[arg(long, default_value_t = linkage::Options::TIGHT.tolerance, allow_hyphen_values = true, value_parser = args::tolerance)]
    tolerance: f64,
    /// Continuation steps allowed per row (accepted plus rejected).
    #[arg(long, default_value_t = linkage::Options::TIGHT.max_steps, allow_hyphen_values = true, value_parser = clap::value_parser!(u32).range(1..))]
    max_steps: u32,
    /// Newton iterations allowed for the final correction (and for NR altogether).
    #[arg(long, default_value_t = linkage::Options::TIGHT.max_iterations, allow_hyphen_values = true, value_parser = clap::value_parser!(u32).range(1..))]
    max_iterations: u32,
    /// Prove each ok answer by the Krawczyk test (columns `certified`, `radius_mm`,
    /// `error_bound_mm`); with `--track`, prove each step from the last row kept its branch,
    /// and refuse a row (`unproven`) whose step is not proven.
    #[arg(long)]
    certify: bool,
    /// For each ok row, whether another real assembly mode lies within this distance (mm, in
    /// v): adds the columns `modes` (other_within, none_within, incomplete, unmatched) and
    /// `nearest_other_mode`.
    #[arg(long, allow_hyphen_values = true, value_parser = args::positive)]
    modes_within: Option<f64>,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum Method {
    Ph,
    Nh,
    Nr,
}

impl Command {
    /// Whether the command's results go to standard output.
    fn prints_results(&self) -> bool {
        match self {
            Command::Equations { .. }
            | Command::TableV { .. }
            | Command::Bench { .. }
            | Command::Modes { .. } => true,
            Command::Solve(args) => args.output.is_none(),
            Command::Trajectory { .. } | Command::Map { .. } | Command::Errors { .. } => false,
        }
    }
}

/// `--seconds`: a finite number from 0 to an hour.
fn timing_seconds(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(t) if (0.0..=3600.0).contains(&t) => Ok(t),
        _ => Err(format!("`{s}` is not a number of seconds from 0 to 3600")),
    }
}

/// The solvers `stewart bench` can time: one of [`Method`], or all modes.
#[derive(Clone, Copy, ValueEnum)]
pub enum BenchMethod {
    Ph,
    Nh,
    Nr,
    All,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if cli.command.prints_results() && linkage_examples::cli::stream::stdout_was_closed() {
        eprintln!("error: standard output is closed: the results would be lost (redirect it to a file, or to /dev/null on purpose)");
        return ExitCode::from(2);
    }
    let result = match cli.command {
        Command::Equations { json } => equations::run(json),
        Command::Solve(args) => solve::run(&args),
        Command::TableV {
            seed,
            json,
            rotation,
            translation,
            export,
        } => table_v::run(seed, rotation, translation, json, export.as_deref()),
        Command::Trajectory { out, seconds, rate } => trajectory::run(&out, seconds, rate),
        Command::Map { out } => map::run(&out),
        Command::Modes {
            geometry,
            input,
            json,
            png,
            row,
        } => modes::run(
            geometry.as_deref(),
            &input,
            json,
            png.as_deref().map(|p| (p, row as usize)),
        ),
        Command::Bench {
            method,
            geometry,
            track,
            input,
            json,
            dense,
            certify,
            seconds,
            as_built,
        } => {
            if as_built {
                linkage::__private::prefer_x86_64_v3(false);
            }
            match method {
                BenchMethod::All if certify => {
                    Err("--certify is not available with --method all".into())
                }
                BenchMethod::All => bench::run_all(geometry.as_deref(), &input, json, seconds),
                BenchMethod::Ph => {
                    bench::run(Method::Ph, track, &input, json, dense, certify, seconds)
                }
                BenchMethod::Nh => {
                    bench::run(Method::Nh, track, &input, json, dense, certify, seconds)
                }
                BenchMethod::Nr => {
                    bench::run(Method::Nr, track, &input, json, dense, certify, seconds)
                }
            }
        }
        Command::Errors { out, seed } => errors::run(&out, seed),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
