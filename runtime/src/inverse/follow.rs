//! The last search before the turns: the platform followed from the declared home to the
//! given pose, each step solved by Levenberg–Marquardt from the last.

use super::levenberg_marquardt::Solver;
use crate::mechanism::Mechanism;
use crate::pose::{Pose, pose_from_unknowns, unknowns_from_pose};

/// Levenberg–Marquardt iterations per step along the path (each starts near its answer).
const PATH_ITERATIONS: usize = 100;

/// Levenberg–Marquardt iterations from where the path from home stalled to a singular v, where
/// they converge only linearly: a SCARA with a wrist stretched to q2 = 4.6e-5 (1e-7 mm inside
/// its reach) took more than 500 from q2 = 0.06.
const STALLED_ITERATIONS: usize = 5000;

/// Smallest step, as a fraction of the path from home, before following the platform gives up.
const SMALLEST_STEP: f64 = 1.0 / 4096.0;

/// Steps taken in all along the path from home.
const PATH_STEPS: usize = 400;

/// The platform from home to `v`, each step solved from the last: its pose's Euler angles and
/// translation interpolated (its coordinates, for a platform of one or two points), the last
/// step at `v` itself.
pub(super) fn follow<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize>(
    solver: &Solver<'_, S, N, M, Z>,
    v: &[f64; N],
    home_v: &[f64; N],
    home_x: &[f64; M],
    scale: &dyn Fn(&[f64; N]) -> f64,
) -> Option<[f64; M]> {
    let held = solver.held;
    let poses = pose_from_unknowns(solver.sys, home_v).zip(pose_from_unknowns(solver.sys, v));
    let at = |t: f64| -> [f64; N] {
        if t >= 1.0 {
            return *v;
        }
        match poses {
            Some((a, b)) => {
                let (ea, eb) = (a.euler(), b.euler());
                let angle = |i: usize| ea[i] + t * half_turn(eb[i] - ea[i]);
                let (ta, tb) = (a.translation, b.translation);
                let pose = Pose::from_euler(
                    angle(0),
                    angle(1),
                    angle(2),
                    core::array::from_fn(|i| ta[i] + t * (tb[i] - ta[i])),
                );
                unknowns_from_pose(solver.sys, &pose)
            }
            None => core::array::from_fn(|i| home_v[i] + t * (v[i] - home_v[i])),
        }
    };
    let (mut vv, mut x) = (*home_v, *home_x);
    let (mut t, mut h) = (0.0f64, 1.0 / 16.0);
    for _ in 0..PATH_STEPS {
        let next = (t + h).min(1.0);
        let target = at(next);
        let (mut vt, mut xt) = (vv, x);
        copy_head(&mut vt, &target, held);
        if solver
            .levenberg_marquardt(&mut vt, &mut xt, PATH_ITERATIONS)
            .within(scale(&vt))
        {
            (t, vv, x) = (next, vt, xt);
            if t >= 1.0 {
                return Some(x);
            }
            h = (2.0 * h).min(0.25);
        } else {
            h *= 0.5;
            if h < SMALLEST_STEP {
                break;
            }
        }
    }
    // Stalled short of v: where v is a singular pose (a serial arm stretched to the edge of its
    // reach), each step converges only linearly and ends short of its iterations; from the
    // last pose reached, v itself with [`STALLED_ITERATIONS`].
    if t > 0.0 {
        let (mut vt, mut xt) = (vv, x);
        copy_head(&mut vt, v, held);
        if solver
            .levenberg_marquardt(&mut vt, &mut xt, STALLED_ITERATIONS)
            .within(scale(&vt))
        {
            return Some(xt);
        }
    }
    // A platform of fewer freedoms than its points have (a coupler point, which moves on a
    // curve) leaves the motion on any straight path: then each step's least-squares answer is
    // the next one's start, and only the last must be exact.
    let (mut vv, mut x) = (*home_v, *home_x);
    for k in 1..=16 {
        copy_head(&mut vv, &at(k as f64 / 16.0), held);
        let left = solver.levenberg_marquardt(&mut vv, &mut x, PATH_ITERATIONS);
        if k == 16 && left.within(scale(&vv)) {
            return Some(x);
        }
    }
    None
}

/// `d` brought into (−π, π].
pub(super) fn half_turn(d: f64) -> f64 {
    let turn = 2.0 * core::f64::consts::PI;
    let mut d = d % turn;
    if d > 0.5 * turn {
        d -= turn;
    } else if d <= -0.5 * turn {
        d += turn;
    }
    d
}

/// `dst[..to] = src[..to]` (all of it past N), with no panic path for the no-panic proof.
pub(super) fn copy_head<const N: usize>(dst: &mut [f64; N], src: &[f64; N], to: usize) {
    for (d, s) in dst.iter_mut().zip(src).take(to) {
        *d = *s;
    }
}

/// `dst[from..] = src[from..]` (nothing past N), with no panic path.
pub(super) fn copy_tail<const N: usize>(dst: &mut [f64; N], src: &[f64; N], from: usize) {
    for (d, s) in dst.iter_mut().zip(src).skip(from) {
        *d = *s;
    }
}
