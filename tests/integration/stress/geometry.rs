//! Random Stewart platforms and their start configurations: Table III, Table III with its joints
//! moved, and random 6-6 platforms, each with a home pose above the base whose legs come from
//! inverse kinematics, so that the start is exact.

use linkage::{Mechanism, Pose, Start};
use linkage_examples::stewart::{legs_for_pose, platform_is_coplanar, SixSix, Stewart, HOME_POSE};
use linkage_tests::Rng;

/// A 6-6 geometry (base joints in the base frame, platform joints in the platform's frame) and
/// the home pose (yaw, pitch, roll, x, y, z) its start is built at.
#[derive(Clone, Debug)]
pub struct Geometry {
    pub family: &'static str,
    pub base: [[f64; 3]; 6],
    pub platform: [[f64; 3]; 6],
    pub home: [f64; 6],
}

impl Geometry {
    /// The paper's platform at its home pose.
    pub fn table_iii() -> Geometry {
        let s = Stewart::new();
        Geometry {
            family: "table_iii",
            base: s.base_joints(),
            platform: std::array::from_fn(|p| s.point_local(p)),
            home: HOME_POSE,
        }
    }

    /// The largest joint coordinate: the mechanism's size.
    pub fn size(&self) -> f64 {
        self.base
            .iter()
            .chain(&self.platform)
            .flatten()
            .fold(1.0f64, |m, c| m.max(c.abs()))
    }

    /// The same geometry scaled by `k` (a power of two keeps every number exact).
    pub fn scaled(&self, k: f64) -> Geometry {
        let mut home = self.home;
        home[3..].iter_mut().for_each(|c| *c *= k);
        Geometry {
            family: self.family,
            base: self.base.map(|p| p.map(|c| c * k)),
            platform: self.platform.map(|p| p.map(|c| c * k)),
            home,
        }
    }

    pub fn coplanar(&self) -> bool {
        platform_is_coplanar(&self.platform)
    }
}

/// `home ⊕ t u`: offsets added to the yaw, pitch, roll, x, y, z of `home`.
pub fn pose_at(home: &[f64; 6], u: &[f64; 6], t: f64) -> Pose {
    Pose::from_euler(
        home[0] + t * u[0],
        home[1] + t * u[1],
        home[2] + t * u[2],
        [home[3] + t * u[3], home[4] + t * u[4], home[5] + t * u[5]],
    )
}

/// One of five families: Table III; its joints moved in the plane; moved in space (then the
/// general form); a random 6-6 with a planar platform; a random 6-6 in space.
pub fn random_geometry(rng: &mut Rng) -> Geometry {
    let family = rng.next_u64() % 5;
    if family <= 2 {
        let mut g = Geometry::table_iii();
        if family == 0 {
            return g;
        }
        let lift = if family == 2 { 20.0 } else { 0.0 };
        for p in g.base.iter_mut().chain(g.platform.iter_mut()) {
            p[0] += 10.0 * rng.symmetric();
            p[1] += 10.0 * rng.symmetric();
            p[2] += lift * rng.symmetric();
        }
        g.home[0] += 0.05 * rng.symmetric();
        g.home[3] += 5.0 * rng.symmetric();
        g.home[4] += 5.0 * rng.symmetric();
        g.home[5] += 10.0 * rng.symmetric();
        g.family = if family == 1 {
            "table_iii_moved"
        } else {
            "table_iii_moved_3d"
        };
        return g;
    }
    let general = family == 4;
    let rb = rng.uniform(80.0, 200.0);
    let rp = rb * rng.uniform(0.4, 1.0);
    let turn = rng.uniform(0.0, std::f64::consts::TAU);
    let (sb, sp) = (rng.uniform(0.08, 0.8), rng.uniform(0.08, 0.8));
    let mut ring = |r: f64, centre: f64, half: f64, lift: f64| -> [[f64; 3]; 6] {
        std::array::from_fn(|i| {
            let pair = (i / 2) as f64;
            let side = if i % 2 == 0 { -1.0 } else { 1.0 };
            let a = turn + centre + pair * std::f64::consts::TAU / 3.0 + side * half;
            [
                r * a.cos() + 0.1 * r * rng.symmetric(),
                r * a.sin() + 0.1 * r * rng.symmetric(),
                lift * r * rng.symmetric(),
            ]
        })
    };
    let base = ring(rb, 0.0, sb, if general { 0.1 } else { 0.05 });
    let platform = ring(
        rp,
        std::f64::consts::PI / 3.0,
        sp,
        if general { 0.15 } else { 0.0 },
    );
    let centre = base.iter().fold([0.0; 3], |a, p| {
        [a[0] + p[0] / 6.0, a[1] + p[1] / 6.0, a[2] + p[2] / 6.0]
    });
    Geometry {
        family: if general {
            "random_6_6_3d"
        } else {
            "random_6_6"
        },
        base,
        platform,
        home: [
            0.3 * rng.symmetric(),
            0.1 * rng.symmetric(),
            0.1 * rng.symmetric(),
            centre[0] + 0.1 * rb * rng.symmetric(),
            centre[1] + 0.1 * rb * rng.symmetric(),
            centre[2] + rb * rng.uniform(0.5, 1.3),
        ],
    }
}

/// A mechanism with its start, and the start's parts kept by the test: the refined pivots,
/// the inputs and det B there (its sign marks the branch).
pub struct Machine<S: SixSix> {
    pub sys: S,
    pub start: Start<18, 6>,
    pub v0: [f64; 18],
    pub x0: [f64; 6],
    pub det0: f64,
    pub size: f64,
    pub home: [f64; 6],
}

/// A [`Start`]'s refined pivots, inputs and det B.
pub fn start_parts(start: &Start<18, 6>) -> ([f64; 18], [f64; 6], f64) {
    (*start.v(), *start.x(), start.det())
}

impl<S: SixSix> Machine<S> {
    /// The mechanism of `g` started at its home pose, or why not.
    pub fn new(g: &Geometry) -> Result<Self, String> {
        let sys = S::with_joints(&g.base, &g.platform).map_err(|e| format!("{e:?}"))?;
        let (x, v) = legs_for_pose(&sys, &pose_at(&g.home, &[0.0; 6], 0.0))
            .ok_or("no inverse kinematics at home")?;
        let size = g.size();
        if x.iter().any(|l| !(*l > 0.1 * size)) {
            return Err(format!("home legs {x:?} too short"));
        }
        let start = Start::new(&sys, v, x).map_err(|e| format!("start: {e:?}"))?;
        let (v0, x0, det0) = start_parts(&start);
        Ok(Machine {
            sys,
            start,
            v0,
            x0,
            det0,
            size,
            home: g.home,
        })
    }

    /// [`Self::new`] for a case of a sweep: `None`, counted as skipped, for a geometry
    /// without a valid start.
    pub fn for_case(g: &Geometry, tally: &mut super::run::Tally) -> Option<Self> {
        let m = Self::new(g).ok();
        if m.is_none() {
            tally.count("geometry without a valid start (skipped)");
        }
        m
    }

    /// Legs, pivots and det B / det0 at the pose `home ⊕ t u`; `None` where a leg is shorter
    /// than a tenth of the size (not a physical configuration of this machine).
    pub fn at(&self, u: &[f64; 6], t: f64) -> Option<([f64; 6], [f64; 18], f64)> {
        let (x, v) = legs_for_pose(&self.sys, &pose_at(&self.home, u, t))?;
        if x.iter().any(|l| !(*l > 0.1 * self.size)) {
            return None;
        }
        Some((x, v, super::oracle::det(&self.sys, &v, &x) / self.det0))
    }

    /// The smallest det B / det0 at `checks` + 1 evenly spaced points of the pose path from
    /// t0 to t1 (negative or zero where it meets a singularity or an invalid pose).
    pub fn path_ratio(&self, u: &[f64; 6], (t0, t1): (f64, f64), checks: usize) -> f64 {
        (0..=checks)
            .map(|k| {
                let t = t0 + (t1 - t0) * k as f64 / checks as f64;
                self.at(u, t).map_or(-1.0, |(_, _, r)| r)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The first singularity along the ray `home ⊕ t u`, t ∈ (0, reach], bracketed to rounding:
    /// `(t_in, t_out)` with the path nonsingular up to t_in (at `checks` points) and det B of
    /// the other sign (or no valid pose) at t_out.
    pub fn crossing(&self, u: &[f64; 6], reach: f64, checks: usize) -> Option<(f64, f64)> {
        let k = (1..=checks).find(|&k| {
            let t = reach * k as f64 / checks as f64;
            self.at(u, t).is_none_or(|(_, _, r)| r <= 0.0)
        })?;
        let (mut lo, mut hi) = (
            reach * (k - 1) as f64 / checks as f64,
            reach * k as f64 / checks as f64,
        );
        while hi - lo > 4.0 * f64::EPSILON * hi {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.at(u, mid).is_some_and(|(_, _, r)| r > 0.0) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some((lo, hi))
    }
}

/// A random offset u in the box ±rot rad, ±trans mm.
pub fn random_offset(rng: &mut Rng, rot: f64, trans: f64) -> [f64; 6] {
    std::array::from_fn(|i| {
        if i < 3 {
            rot * rng.symmetric()
        } else {
            trans * rng.symmetric()
        }
    })
}
