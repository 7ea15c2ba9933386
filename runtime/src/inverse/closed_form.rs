//! The check a closed-form inverse ends with. The closed forms read one platform point per
//! input (a leg's end, the rod's end on a crank); given pivots that are not one placement of
//! the platform — not a rigid body at this geometry, or a point the closed forms do not read
//! somewhere else — they still give inputs, which place the points they read and not the
//! others. So the inputs are returned only where every equation on the platform's points
//! alone holds with them.

use super::off_in;
use crate::Mechanism;

/// How far, relative to the scale (1 + the largest platform coordinate), the equations on the
/// platform's points may be from holding with the closed forms' inputs: a thousandth. Far
/// looser than the numerical inverse's [`ACCEPT`](super::ACCEPT), which must decide whether
/// its own iterations converged: the closed forms are exact for the points they read, and this
/// check is for a point elsewhere or a platform that is not one rigid body — not for a pose
/// near the motion of a mechanism of fewer freedoms, whose legs a caller asks for and then
/// refines (`Start::new`): a 3-RPS's level pose, with its hinges declared to 1 µm, is
/// 1e-3 to 1.5e-2 mm off its motion (7e-6 to 1e-4 of the scale), and gets the legs the closed
/// forms give, as it always did.
pub const CLOSED_FORM_ACCEPT: f64 = 1e-3;

/// Whether inputs `x` place the platform at `v` (its first `held` coordinates): every
/// equation whose unknowns are all the platform's holds to `CLOSED_FORM_ACCEPT` of the
/// scale, as a length (measured as the numerical inverse measures). Equations that read the
/// links between are left out: a caller may give the platform alone.
pub fn closed_form_places<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    held: usize,
) -> bool {
    // Rows that read a coordinate past the platform's, or none at all.
    let mut skip = [true; N];
    for &(r, _) in S::PATTERN {
        if let Some(s) = skip.get_mut(r) {
            *s = false;
        }
    }
    for &(r, c) in S::PATTERN {
        if c >= held
            && let Some(s) = skip.get_mut(r)
        {
            *s = true;
        }
    }
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    let scale = 1.0 + v.iter().take(held).fold(0.0f64, |m, q| m.max(q.abs()));
    off_in(sys, v, x, &f, &skip) <= CLOSED_FORM_ACCEPT * scale
}
