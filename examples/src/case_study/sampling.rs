//! Test points as Section 5 describes them: poses reached from the initial configuration (legs
//! 170 mm) by a nonsingular path in pose space, with legs from inverse kinematics (Appendix B).
//!
//! Protocol (all numbers are fields of [`Protocol`]):
//! - A pose is `home ⊕ u`: yaw, pitch, roll offsets and x, y, z offsets added to the home pose.
//!   Uniform samples take u in the box ±`rotation` rad, ±`translation` mm (z: ±`heave` mm).
//! - A pose path is the straight segment from home to the pose in these six coordinates. It is
//!   *nonsingular* when det B keeps the start's sign at `checks` evenly spaced points and every
//!   leg stays longer than `min_leg`.
//! - The mean |det B| over `mean_samples` uniform valid poses sets the scale; a point is
//!   *near singular* below `near_fraction` (0.1 %) of it, *normal* otherwise.
//! - Normal points are uniform valid samples. Near-singular points are found along random
//!   rays u: the first sign change of det B along the ray (at up to `reach` times the box), then
//!   bisection back towards home to a point whose |det B| is below the threshold — so the path
//!   from home stays nonsingular by construction.
//! - Every search is capped: it gives up, with a [`SamplingError`], once it has drawn
//!   `max_tries_per_point` random offsets per point found (plus one), that is when fewer
//!   than 1 in `max_tries_per_point` draws succeed. Extreme boxes (say ±1e-9) never meet a
//!   singularity, and the search must end with a message rather than spin forever.
//! - A seeded SplitMix64 generator makes every run with the same seed identical.

use crate::stewart::{home_start, legs_for_pose, Stewart};
use linkage::{det_b, Pose, Start};

#[derive(Clone, Copy, Debug)]
pub struct Protocol {
    pub seed: u64,
    pub normal: usize,
    pub near_singular: usize,
    pub rotation: f64,
    pub translation: f64,
    pub heave: f64,
    pub checks: usize,
    pub min_leg: f64,
    pub mean_samples: usize,
    pub near_fraction: f64,
    pub reach: f64,
    /// Random draws allowed per point found (see the module's protocol).
    pub max_tries_per_point: usize,
}

impl Default for Protocol {
    fn default() -> Self {
        Protocol {
            seed: 2015,
            normal: 100,
            near_singular: 100,
            rotation: 0.35,
            translation: 50.0,
            heave: 40.0,
            checks: 200,
            min_leg: 20.0,
            mean_samples: 5000,
            near_fraction: 1e-3,
            reach: 4.0,
            max_tries_per_point: 200,
        }
    }
}

impl Protocol {
    /// Every size finite and positive, every count positive, angles within ±π.
    pub fn validate(&self) -> Result<(), SamplingError> {
        let sizes = [
            ("rotation", self.rotation),
            ("translation", self.translation),
            ("heave", self.heave),
            ("min_leg", self.min_leg),
            ("near_fraction", self.near_fraction),
            ("reach", self.reach),
        ];
        for (name, x) in sizes {
            if !(x.is_finite() && x > 0.0) {
                return Err(SamplingError::Invalid(format!(
                    "{name} must be a finite positive number, not {x}"
                )));
            }
        }
        if self.rotation > std::f64::consts::PI {
            return Err(SamplingError::Invalid(format!(
                "rotation must be at most π rad (a box of ±{} rad covers some angles twice)",
                self.rotation
            )));
        }
        let counts = [
            ("normal", self.normal),
            ("near_singular", self.near_singular),
            ("checks", self.checks),
            ("mean_samples", self.mean_samples),
            ("max_tries_per_point", self.max_tries_per_point),
        ];
        for (name, n) in counts {
            if n == 0 {
                return Err(SamplingError::Invalid(format!("{name} must be at least 1")));
            }
        }
        Ok(())
    }
}

/// Why the protocol could not produce its test points.
#[derive(Clone, Debug, PartialEq)]
pub enum SamplingError {
    /// A protocol value is out of range.
    Invalid(String),
    /// Random draws came up empty too often: `found` of `wanted` after `tries` draws.
    GaveUp {
        what: &'static str,
        found: usize,
        wanted: usize,
        tries: usize,
        /// What the points need, for the message.
        hint: &'static str,
    },
}

impl std::fmt::Display for SamplingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SamplingError::Invalid(why) => write!(f, "invalid protocol: {why}"),
            SamplingError::GaveUp {
                what,
                found,
                wanted,
                tries,
                hint,
            } => write!(
                f,
                "gave up after {tries} random draws with {found} of {wanted} {what} found: \
                 the sampled box (rotation, translation) cannot produce them ({hint})"
            ),
        }
    }
}

impl std::error::Error for SamplingError {}

/// A capped rejection-sampling loop: `wanted` successes, at most `max_tries_per_point` draws
/// per success so far (plus one).
struct Search {
    what: &'static str,
    hint: &'static str,
    wanted: usize,
    per_point: usize,
    count: usize,
    tries: usize,
}

impl Search {
    fn new(what: &'static str, hint: &'static str, wanted: usize, protocol: &Protocol) -> Self {
        Search {
            what,
            hint,
            wanted,
            per_point: protocol.max_tries_per_point,
            count: 0,
            tries: 0,
        }
    }

    /// Whether to draw again: `Ok(false)` when done, an error when the draws keep failing.
    fn more(&mut self) -> Result<bool, SamplingError> {
        if self.count >= self.wanted {
            return Ok(false);
        }
        if self.tries >= self.per_point.saturating_mul(self.count + 1) {
            return Err(SamplingError::GaveUp {
                what: self.what,
                found: self.count,
                wanted: self.wanted,
                tries: self.tries,
                hint: self.hint,
            });
        }
        self.tries += 1;
        Ok(true)
    }

    fn found(&mut self) {
        self.count += 1;
    }
}

/// A test point: the true pose, pivots and legs, and |det B| there.
#[derive(Clone, Copy, Debug)]
pub struct TestPoint {
    pub pose: Pose,
    pub v: [f64; 18],
    pub x: [f64; 6],
    pub det: f64,
    pub near_singular: bool,
}

/// SplitMix64: seeded and reproducible (the protocol needs repeatability, not quality).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }

    /// Uniform in [-1, 1).
    pub fn symmetric(&mut self) -> f64 {
        self.uniform(-1.0, 1.0)
    }
}

pub struct Sampler {
    pub sys: Stewart,
    pub start: Start<18, 6>,
    home: [f64; 6],
    pub protocol: Protocol,
}

impl Sampler {
    pub fn new(protocol: Protocol) -> Self {
        let sys = Stewart::new();
        let start = home_start(&sys).expect("Table III's home configuration is valid");
        let p = linkage::pose_from_unknowns(&sys, start.v()).expect("home pose");
        let e = p.euler();
        let t = p.translation;
        Sampler {
            sys,
            start,
            home: [e[0], e[1], e[2], t[0], t[1], t[2]],
            protocol,
        }
    }

    pub fn pose(&self, u: &[f64; 6], t: f64) -> Pose {
        let h = &self.home;
        Pose::from_euler(
            h[0] + t * u[0],
            h[1] + t * u[1],
            h[2] + t * u[2],
            [h[3] + t * u[3], h[4] + t * u[4], h[5] + t * u[5]],
        )
    }

    /// det B at the pose `home ⊕ t·u` (0 if its legs are too short).
    pub fn det_at(&self, u: &[f64; 6], t: f64) -> f64 {
        match legs_for_pose(&self.sys, &self.pose(u, t)) {
            Some((x, v)) if x.iter().all(|l| *l > self.protocol.min_leg) => {
                det_b(&self.sys, &v, &x)
            }
            _ => 0.0,
        }
    }

    /// Whether det B keeps the start's sign on the path to `t·u`.
    pub fn nonsingular(&self, u: &[f64; 6], t: f64) -> bool {
        let n = self.protocol.checks;
        (1..=n).all(|k| self.det_at(u, t * k as f64 / n as f64) * self.start.det() > 0.0)
    }

    fn random_offset(&self, rng: &mut Rng) -> [f64; 6] {
        let p = &self.protocol;
        let s = [
            p.rotation,
            p.rotation,
            p.rotation,
            p.translation,
            p.translation,
            p.heave,
        ];
        std::array::from_fn(|i| s[i] * rng.symmetric())
    }

    fn point(&self, u: &[f64; 6], t: f64, near_singular: bool) -> Option<TestPoint> {
        let pose = self.pose(u, t);
        let (x, v) = legs_for_pose(&self.sys, &pose)?;
        Some(TestPoint {
            pose,
            v,
            x,
            det: det_b(&self.sys, &v, &x).abs(),
            near_singular,
        })
    }

    /// Mean |det B| over uniform samples whose pose path is nonsingular.
    pub fn mean_det(&self, rng: &mut Rng) -> Result<f64, SamplingError> {
        let mut sum = 0.0;
        let mut search = Search::new(
            "poses with a nonsingular path from home",
            "a pose counts when det B keeps its sign along the way and every leg stays above `min_leg`",
            self.protocol.mean_samples,
            &self.protocol,
        );
        while search.more()? {
            let u = self.random_offset(rng);
            if self.nonsingular(&u, 1.0) {
                sum += self.det_at(&u, 1.0).abs();
                search.found();
            }
        }
        Ok(sum / search.count as f64)
    }

    /// `(mean |det B|, normal points, near-singular points)`, or why the protocol cannot
    /// produce them.
    pub fn sample(&self) -> Result<(f64, Vec<TestPoint>, Vec<TestPoint>), SamplingError> {
        self.protocol.validate()?;
        let mut rng = Rng::new(self.protocol.seed);
        let mean = self.mean_det(&mut rng)?;
        let threshold = self.protocol.near_fraction * mean;
        let mut normal = Vec::new();
        let mut search = Search::new(
            "normal points",
            "a normal point has |det B| of at least `near_fraction` of the mean",
            self.protocol.normal,
            &self.protocol,
        );
        while search.more()? {
            let u = self.random_offset(&mut rng);
            if self.nonsingular(&u, 1.0) && self.det_at(&u, 1.0).abs() >= threshold {
                if let Some(p) = self.point(&u, 1.0, false) {
                    normal.push(p);
                    search.found();
                }
            }
        }
        let mut near = Vec::new();
        let mut search = Search::new(
            "near-singular points",
            "a near-singular point needs a singularity within `reach` times the box",
            self.protocol.near_singular,
            &self.protocol,
        );
        while search.more()? {
            let u = self.random_offset(&mut rng);
            if let Some(p) = self
                .near_singular_along(&u, threshold)
                .and_then(|t| self.point(&u, t, true))
            {
                near.push(p);
                search.found();
            }
        }
        Ok((mean, normal, near))
    }

    /// The largest t before the first singularity along `u` with |det B| below `threshold`.
    fn near_singular_along(&self, u: &[f64; 6], threshold: f64) -> Option<f64> {
        let steps = self.protocol.checks * self.protocol.reach as usize;
        let dt = self.protocol.reach / steps as f64;
        let mut before = 0.0;
        let mut after = None;
        for k in 1..=steps {
            let t = k as f64 * dt;
            if self.det_at(u, t) * self.start.det() > 0.0 {
                before = t;
            } else {
                after = Some(t);
                break;
            }
        }
        let mut hi = after?;
        // Bisect the crossing, keeping `lo` on the start's side.
        let mut lo = before;
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if self.det_at(u, mid) * self.start.det() > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
            if self.det_at(u, lo).abs() < threshold {
                break;
            }
        }
        let d = self.det_at(u, lo).abs();
        // A crossing at a leg-length limit (det forced to 0) is not a singularity.
        let legs_ok = legs_for_pose(&self.sys, &self.pose(u, lo))
            .is_some_and(|(x, _)| x.iter().all(|l| *l > self.protocol.min_leg));
        (d > 0.0 && d < threshold && legs_ok).then_some(lo)
    }
}
