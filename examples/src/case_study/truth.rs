//! The ground truth Table V and the tests judge "the start's branch" by: the branch followed
//! along the straight joint-space segment in many small Newton steps, counting det B's sign
//! changes on the way.

use linkage::{Mechanism, Start};

/// Ground truth for "the start's branch along the straight joint-space segment": natural-
/// parameter continuation in `steps` small steps (Newton at each), with the number of sign
/// changes of det B met on the way. Trustworthy when no sign change is met and the steps are
/// small against the path's curvature.
pub fn straight_segment<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: &[f64; M],
    steps: usize,
) -> ([f64; N], usize) {
    straight_segment_from(sys, (start.v(), start.x()), start.det(), target, steps)
}

/// [`straight_segment`] from any point `(v, x)` of the branch whose det B has the sign of
/// `det` (such as the corners of a detour, which may lie too near a fold to be a [`Start`]).
pub fn straight_segment_from<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    (v0, x0): (&[f64; N], &[f64; M]),
    det: f64,
    target: &[f64; M],
    steps: usize,
) -> ([f64; N], usize) {
    let mut v = *v0;
    let mut prev = det;
    let mut flips = 0;
    for k in 1..=steps {
        let l = k as f64 / steps as f64;
        let x: [f64; M] = std::array::from_fn(|j| x0[j] + l * (target[j] - x0[j]));
        for _ in 0..if k == steps { 30 } else { 6 } {
            let mut f = [0.0; N];
            sys.residual(&v, &x, &mut f);
            let mut b = [[0.0; N]; N];
            sys.jacobian_dense(&v, &x, &mut b);
            let Some(lu) = linkage::lu::Lu::new(b) else {
                return (v, flips + 1);
            };
            lu.solve(&mut f);
            let (mut step, mut size) = (0.0f64, 1.0f64);
            for i in 0..N {
                v[i] -= f[i];
                // `!(a <= b)` so that a NaN correction is never mistaken for a small one.
                if !(f[i].abs() <= step) {
                    step = f[i].abs();
                }
                size = size.max(v[i].abs());
            }
            // Converged to rounding: at a regular point the next correction is of the order of
            // this one squared, so a middle step stops here instead of running its 6 iterations
            // (the tests' cost was these). The last step keeps its full 30: it is the answer.
            if k < steps && step <= 1e-12 * size {
                break;
            }
        }
        let d = linkage::det_b(sys, &v, &x);
        if d * prev <= 0.0 {
            flips += 1;
        }
        prev = d;
    }
    (v, flips)
}
