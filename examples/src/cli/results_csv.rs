//! The result CSV of `stewart solve`: one line per input row.

use std::fmt::Write;

/// How a row's solution was reached.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Via {
    /// Along the straight joint-space segment from the start (or from the previous row).
    Direct,
    /// Around a fold, through a waypoint (`arc_length_detour`).
    Detour,
    /// The tracker's fast step failed and full continuation from the last sample took over.
    Fallback,
}

impl Via {
    pub fn word(self) -> &'static str {
        match self {
            Via::Direct => "direct",
            Via::Detour => "detour",
            Via::Fallback => "fallback",
        }
    }
}

/// One output row. Empty fields are what the solve did not produce.
#[derive(Clone, Debug, PartialEq)]
pub struct Record<'a> {
    /// 1-based input row number (the header not counted).
    pub row: u64,
    /// `ok` or a word saying why not.
    pub status: &'a str,
    /// The pose (yaw, pitch, roll, x, y, z) and v, for `ok` rows only.
    pub solution: Option<([f64; 6], [f64; 18])>,
    pub error_estimate: Option<f64>,
    pub steps: Option<u32>,
    /// The smallest |det B| / |det B at the start| met on the way.
    pub min_det_ratio: Option<f64>,
    pub via: Option<Via>,
    /// With `--certify`, for a proven answer: the radius (mm) within which it is the only
    /// root (for a tracked step: the smallest along the step) and the proven bound on its
    /// error (mm, largest coordinate).
    pub certified: Option<(f64, f64)>,
}

impl<'a> Record<'a> {
    /// A row with nothing but its status (nothing was solved).
    pub fn status_only(row: u64, status: &'a str) -> Self {
        Record {
            row,
            status,
            solution: None,
            error_estimate: None,
            steps: None,
            min_det_ratio: None,
            via: None,
            certified: None,
        }
    }

    /// Appends the `--certify` columns: `,true,radius_mm,error_bound_mm` for a proven
    /// answer, `,false,,` otherwise.
    pub fn write_certificate(&self, line: &mut String) {
        match self.certified {
            Some((radius, bound)) => {
                let _ = write!(line, ",true,{radius:.3e},{bound:.3e}");
            }
            None => line.push_str(",false,,"),
        }
    }

    /// Appends the row as CSV (no newline). No field needs quoting: numbers and words.
    pub fn write_to(&self, line: &mut String) {
        let _ = write!(line, "{},{}", self.row, self.status);
        match &self.solution {
            Some((pose, v)) => {
                for x in pose.iter().chain(v) {
                    let _ = write!(line, ",{x:.12}");
                }
            }
            None => (0..24).for_each(|_| line.push(',')),
        }
        line.push(',');
        if let Some(e) = self.error_estimate {
            let _ = write!(line, "{e:.3e}");
        }
        line.push(',');
        if let Some(s) = self.steps {
            let _ = write!(line, "{s}");
        }
        line.push(',');
        if let Some(r) = self.min_det_ratio {
            let _ = write!(line, "{r:.3e}");
        }
        line.push(',');
        if let Some(via) = self.via {
            line.push_str(via.word());
        }
    }
}

/// The header: row, status, the pose (Appendix B), v in the paper's order, and the solve's
/// account.
pub fn header() -> String {
    let mut h: Vec<String> = ["row", "status", "yaw", "pitch", "roll", "x", "y", "z"]
        .map(String::from)
        .to_vec();
    h.extend((1..=18).map(|i| format!("v{i}")));
    h.extend(["error_estimate", "steps", "min_det_ratio", "via"].map(String::from));
    h.join(",")
}

/// The header with the `--certify` columns.
pub fn header_certified() -> String {
    header() + ",certified,radius_mm,error_bound_mm"
}
