//! Pseudo-arc-length continuation with a proof: the answer of [`arc_length`] is the start
//! continued along the straight joint-space segment, proven by chained parametric Krawczyk
//! certificates over the segment (as [`crate::certified_steps::CertifiedSteps`] chains a tracker's steps).

use crate::arc_length::arc_length;
use crate::certified_steps::{PATH_DEPTH, PATH_PIECES, StepProof, prove};
use crate::mechanism::Mechanism;
use crate::solution::{Options, Solution, SolveError};
use crate::start::Start;

/// [`arc_length`], and for a converged answer the proof that it lies on the start's branch:
/// the segment from the start's inputs to `target` covered by parametric Krawczyk certificates
/// (halved where one does not pass: up to 4096 pieces, down to 1/2³² of the segment), each box holding exactly one root for
/// every input on its piece and ∂F/∂v nonsingular throughout, chained from a certificate of
/// the start. `None` for an answer that is not ok (nothing to prove). An unproven answer is not
/// a wrong one; it is one this test could not vouch for.
///
/// ```
/// use linkage::{arc_length_certified, Mechanism, Options, StepProof};
/// # linkage::mechanism! {
/// #     pub struct Rps;
/// #     base {
/// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
/// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
/// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
/// #     }
/// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
/// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
/// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
/// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// # }
/// # let rps = Rps::new();
/// # let v0 = linkage::unknowns_from_pose(&rps, &linkage::Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// # let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// # let start = linkage::Start::new(&rps, v0, x0).unwrap();
/// let (sol, proof) = arc_length_certified(&rps, &start, &[170.0, 150.0, 160.0], &Options::TIGHT).unwrap();
/// assert!(sol.is_ok());
/// let Some(StepProof::Proven { error_bound, .. }) = proof else { panic!("{proof:?}") };
/// assert!(error_bound < 1e-9);
/// ```
pub fn arc_length_certified<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: &[f64; M],
    options: &Options,
) -> Result<(Solution<N>, Option<StepProof>), SolveError> {
    let sol = arc_length(sys, start, target, options)?;
    let proof = sol.is_ok().then(|| {
        prove::<S, N, M, PATH_DEPTH>(
            sys,
            None,
            (start.v(), start.x()),
            (&sol.v, target),
            PATH_PIECES,
        )
        .0
    });
    Ok((sol, proof))
}
