//! `stewart solve --modes-within MM`: for each `ok` row, whether another real assembly mode
//! lies within MM of the answer — every real root of the row (`linkage::modes`), the answer
//! found among them, and the distance to the nearest other.
//!
//! Two columns are appended to the result CSV: `modes` and `nearest_other_mode` (mm, the
//! Euclidean distance in v, as `stewart modes` reports `nearest_real`). `modes` is
//! - `other_within`: another real root is closer than MM (a small disturbance, or a path that
//!   passes near a singularity, could end on it);
//! - `none_within`: all roots were found and no other real one is that close;
//! - `incomplete`: some path of the all-modes solve did not end at a root, so nothing is
//!   claimed (the nearest real root found is still given);
//! - `unmatched`: no real root found is the answer (to 1e-6 of the scale): a contradiction
//!   between the two solvers, reported rather than hidden;
//! - empty on rows that are not `ok`.

use crate::modes::CAPACITY;
use linkage::modes::{AllModes, Roots};
use linkage_examples::stewart::SixSix;

/// The all-modes solver of the row's mechanism and the distance asked for.
pub struct ModeCheck<S> {
    modes: Box<AllModes<S, 18, 6, CAPACITY>>,
    roots: Box<Roots<18, CAPACITY>>,
    within: f64,
}

impl<S: SixSix> ModeCheck<S> {
    pub fn new(modes: Box<AllModes<S, 18, 6, CAPACITY>>, within: f64) -> Self {
        ModeCheck {
            modes,
            roots: Box::new(Roots::new()),
            within,
        }
    }

    /// The CSV header's two extra columns.
    pub fn header() -> &'static str {
        ",modes,nearest_other_mode"
    }

    /// The two extra fields for a row: `v` the answer at legs `x` (`None`: not an ok row).
    pub fn fields(&mut self, x: &[f64; 6], v: Option<&[f64; 18]>) -> String {
        let Some(v) = v else {
            return ",,".into();
        };
        if self.modes.solve(x, &mut self.roots).is_err() {
            return ",incomplete,".into();
        }
        let distance = |a: &[f64; 18], b: &[f64; 18]| {
            a.iter()
                .zip(b)
                .map(|(p, q)| (p - q) * (p - q))
                .sum::<f64>()
                .sqrt()
        };
        let real = self.roots.real();
        let Some(me) = real
            .iter()
            .min_by(|a, b| distance(&a.v, v).total_cmp(&distance(&b.v, v)))
        else {
            return ",unmatched,".into();
        };
        if !(distance(&me.v, v) <= 1e-6 * self.modes.scale()) {
            return ",unmatched,".into();
        }
        let nearest = me.nearest_real;
        let word = if nearest < self.within {
            "other_within"
        } else if !self.roots.is_complete() {
            "incomplete"
        } else {
            "none_within"
        };
        if nearest.is_finite() {
            format!(",{word},{nearest:.6}")
        } else {
            format!(",{word},")
        }
    }
}
