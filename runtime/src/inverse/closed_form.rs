//! The check a closed-form inverse ends with. The closed forms read one platform point per
//! input (a leg's end, the rod's end on a crank); given pivots that are not one placement of
//! the platform — not a rigid body at this geometry, or a point the closed forms do not read
//! somewhere else — they still give inputs, which place the points they read and not the
//! others. So the inputs are returned only where every equation on the platform's points
//! alone holds with them.
//!
//! The same measure, far looser, is the numerical inverse's first step: a platform whose
//! equations on its points alone that read no input fail by far more than the search could
//! accept is refused before the search (`platform_in_shape`), and so is one whose points are
//! not as far apart as declared (`platform_keeps_its_distances`, for every model, whether or
//! not it has such equations).

use crate::mechanism::Mechanism;
use linkage_geometry::distance;

/// How far, relative to the scale (1 + the largest platform coordinate), the equations on the
/// platform's points may be from holding with the closed forms' inputs: a thousandth. Far
/// looser than the numerical inverse's [`ACCEPT`](super::levenberg_marquardt::ACCEPT), which must decide whether
/// its own iterations converged: the closed forms are exact for the points they read, and this
/// check is for a point elsewhere or a platform that is not one rigid body — not for a pose
/// near the motion of a mechanism of fewer freedoms, whose legs a caller asks for and then
/// refines (`Start::new`): a 3-RPS's level pose, with its hinges declared to 1 µm, is
/// 1e-3 to 1.5e-2 mm off its motion (7e-6 to 1e-4 of the scale), and gets the legs the closed
/// forms give, as it always did.
pub const CLOSED_FORM_ACCEPT: f64 = 1e-3;

/// How far (a length, relative to the scale) an equation on the platform's coordinates alone
/// that reads no input (a rigid platform's distances, say) may be off at the given v before
/// the pose is unreachable without a search ([`platform_in_shape`], which the generated
/// `inverse` calls with the generator's list of such equations before this module's search):
/// no inputs or links' points move it, and an answer needs it within [`ACCEPT`](super::levenberg_marquardt::ACCEPT) at v, or at a
/// configuration whose platform is within [`ACCEPT`](super::levenberg_marquardt::ACCEPT) of v — which moves it by at most the
/// row's nonzeros times that, to first order. A thousand times [`ACCEPT`](super::levenberg_marquardt::ACCEPT) leaves room for both
/// and for the second-order term; a pose between the two is searched as any other. Without it
/// a platform given out of shape cost the whole search (every start, the path from home) to
/// be refused: about 50 ms for the 6-PCS of 60 unknowns in the tests' build.
///
/// The same bound holds the platform's distances ([`platform_keeps_its_distances`]), which
/// every model has, equations on the platform alone or not (the 3-PRP's model places its
/// platform's points through links, a delta's tool through its carriage: 25–75 ms a refusal
/// before). A configuration that satisfies F exactly moves the platform rigidly; one an answer
/// accepts satisfies it within [`ACCEPT`](super::levenberg_marquardt::ACCEPT) as lengths, which moves the platform's points off its
/// shape by that times the platform's own equations' coefficients, to first order — a thousand
/// leaves room for coefficients up to hundreds (a frame of three points nearly on a line).
const FAR: f64 = 1e3 * super::levenberg_marquardt::ACCEPT;

/// Whether the closed forms' inputs place the platform at `v` (its first `held`
/// coordinates): F at them is `f`, ∂F/∂v's values `b`, and `rows` the equations whose
/// unknowns are all the platform's, each with the indices of its values (the generator's
/// list). Each must hold to `CLOSED_FORM_ACCEPT` of the scale, as a length: its residual
/// over its largest derivative, as the numerical inverse measures. Equations that read the
/// links between are left out: a caller may give the platform alone.
pub fn closed_form_places<const N: usize>(
    v: &[f64; N],
    held: usize,
    f: &[f64; N],
    b: &[f64],
    rows: &[(usize, &[usize])],
) -> bool {
    rows_hold(f, b, rows, CLOSED_FORM_ACCEPT * scale(v, held), 0.0)
}

/// Whether the platform at `v` is in shape: every equation of `rows` — on the platform's
/// points alone and reading no input (the generator's list), so that no inputs or links'
/// points can make it hold — within `FAR` (a thousand times the numerical inverse's
/// acceptance) of the scale at v (F there `f`, ∂F/∂v's values `b`, as for
/// [`closed_form_places`]), or within the second-order term's allowance in F's own units (it
/// matters only where a row's slope is itself near zero: points of the platform nearly
/// coincident). The generated numerical `inverse` calls it before the search, which a
/// platform out of shape would otherwise run through every start to be refused.
pub fn platform_in_shape<const N: usize>(
    v: &[f64; N],
    held: usize,
    f: &[f64; N],
    b: &[f64],
    rows: &[(usize, &[usize])],
) -> bool {
    let bound = FAR * scale(v, held);
    rows_hold(f, b, rows, bound, 16.0 * bound * bound)
}

/// Whether the platform at `v` keeps its declared distances: every two of its points as far
/// apart as the geometry puts them in the platform's own frame ([`Mechanism::point_local`],
/// calibrated values included), within `FAR` of the scale. A rigid platform keeps them in every
/// configuration, so no inputs or links' points can place one that does not; unlike
/// [`platform_in_shape`], this needs no equation on the platform's points alone, and holds
/// where the model places the platform through links (a delta's tool on its carriage, the
/// 3-PRP's platform through its guides). The generated numerical `inverse` calls it before the
/// search, as it does [`platform_in_shape`].
pub fn platform_keeps_its_distances<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
) -> bool {
    let k = S::POINTS.len();
    let bound = FAR * scale(v, 3 * k);
    // Unknowns are by axis: point p's coordinate a is v[a k + p].
    let at = |p: usize| [0, 1, 2].map(|a| v.get(a * k + p).copied().unwrap_or(f64::NAN));
    // NaN anywhere fails the comparison.
    (0..k).all(|p| {
        (p + 1..k).all(|q| {
            let given = distance(at(p), at(q));
            let declared = distance(sys.point_local(p), sys.point_local(q));
            (given - declared).abs() <= bound
        })
    })
}

/// 1 + the largest of the platform's coordinates (the first `held`): the scale every
/// tolerance of the inverse is relative to.
pub(super) fn scale<const N: usize>(v: &[f64; N], held: usize) -> f64 {
    1.0 + v.iter().take(held).fold(0.0f64, |m, q| m.max(q.abs()))
}

/// Whether each equation of `rows` holds to `bound` as a length (its residual over its largest
/// derivative among its values in `b`), or to `allowance` in F's own units.
fn rows_hold<const N: usize>(
    f: &[f64; N],
    b: &[f64],
    rows: &[(usize, &[usize])],
    bound: f64,
    allowance: f64,
) -> bool {
    rows.iter().all(|&(r, entries)| {
        let slope = entries
            .iter()
            .filter_map(|&k| b.get(k))
            .fold(0.0f64, |m, q| m.max(q.abs()));
        let fr = f.get(r).copied().unwrap_or(f64::NAN);
        // NaN anywhere fails; an equation no coordinate moves must hold exactly.
        if fr.abs() <= allowance {
            true
        } else if slope > 0.0 {
            fr.abs() <= bound * slope
        } else {
            fr == 0.0
        }
    })
}
