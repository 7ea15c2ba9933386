//! A reference for "the start's branch": the branch followed along the straight joint-space
//! segment in many small Newton steps, counting det B's sign changes on the way. Slow (thousands
//! of factorisations) and with no step control: the ground truth that Table V, the tests and a
//! user checking a solver's answer judge "same branch" by, not a solver.

use crate::correction::dense_b;
use crate::lu::Lu;
use crate::mechanism::Mechanism;
use crate::start::Start;

/// The start's branch at `target` by natural-parameter continuation along the straight segment
/// from the start's inputs, in `steps` equal steps (Newton at each), with the number of sign
/// changes of det B met on the way (a singular B counts as one). Trustworthy when no sign
/// change is met and the steps are small against the path's curvature: judge a solver's answer
/// by it only then.
///
/// ```
/// use linkage::{arc_length, reference::straight_segment, Mechanism, Options, Pose, Start};
///
/// linkage::mechanism! {
///     /// A 3-RPS: three hinged legs of variable length carry a triangular platform.
///     pub struct Rps;
///     base {
///         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
///         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
///         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
///     }
///     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
///     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
///     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
///     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// }
///
/// let rps = Rps::new();
/// let v0 = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// let start = Start::new(&rps, v0, x0).unwrap();
/// let target = [160.0, 155.0, 158.0];
/// let (truth, flips) = straight_segment(&rps, &start, &target, 1000);
/// assert_eq!(flips, 0);
/// let sol = arc_length(&rps, &start, &target, &Options::TIGHT).unwrap();
/// assert!(sol.is_ok());
/// assert!(sol.v.iter().zip(&truth).all(|(a, b)| (a - b).abs() < 1e-8));
/// ```
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
    let steps = steps.max(1);
    let mut v = *v0;
    let mut prev = det;
    let mut flips = 0;
    // B factored where the last step ended, for det B there; where B does not read the inputs
    // it is also B at the next step's first iterate (the same v), which takes it instead of
    // factoring the same matrix again: the same factors, the same answer.
    let mut carried: Option<Lu<N>> = None;
    for k in 1..=steps {
        let l = k as f64 / steps as f64;
        let x: [f64; M] = core::array::from_fn(|j| x0[j] + l * (target[j] - x0[j]));
        for _ in 0..if k == steps { 30 } else { 6 } {
            let mut f = [0.0; N];
            sys.residual(&v, &x, &mut f);
            let Some(lu) = carried.take().or_else(|| dense_b(sys, &v, &x)) else {
                return (v, flips + 1);
            };
            lu.solve(&mut f);
            // The configuration's own size, not floored at 1: a mechanism 1e-9 across would
            // otherwise stop each middle step 1e-3 of its size from the branch.
            let (mut step, mut size) = (0.0f64, 0.0f64);
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
        // det B as `det_b` gives it: 0 where B cannot be factored.
        let lu = dense_b(sys, &v, &x);
        let d = lu.as_ref().map_or(0.0, Lu::det);
        if !S::JACOBIAN_USES_INPUTS {
            carried = lu;
        }
        // `!(> 0)`: a NaN det B counts as a change too.
        if !(d * prev > 0.0) {
            flips += 1;
        }
        prev = d;
    }
    (v, flips)
}
