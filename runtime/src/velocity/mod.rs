//! Velocity kinematics at a solution: how fast the pivots and the platform move for given
//! input rates, and the input rates a wanted platform motion takes.
//!
//! Differentiating F(v(t), x(t)) = 0 along a motion gives B v̇ + (∂F/∂x) ẋ = 0 (Eq. 5 without
//! the step), so at a configuration where B is regular — away from direct singularities —
//! v̇ = −B⁻¹ (∂F/∂x) ẋ, with the generated sparse factorisation and ∂F/∂x product. The
//! platform's [`Twist`] (angular velocity and the velocity of its frame's origin) follows from
//! the rates of its frame pivots; [`platform_jacobian`] holds one twist per unit input rate, and
//! [`input_rates`] inverts it (exactly where the platform has as many freedoms as inputs, in
//! the least-squares sense otherwise, with what is left over reported); [`input_efforts`] is
//! its transpose, the statics: what a load on the platform puts on each actuator.
//!
//! ```
//! use linkage::velocity::{input_rates, twist};
//! use linkage::{Mechanism, Pose};
//! # linkage::mechanism! {
//! #     pub struct Rps;
//! #     base {
//! #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
//! #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
//! #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
//! #     }
//! #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
//! #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
//! #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
//! #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
//! # }
//! let rps = Rps::new();
//! let v = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.1, 0.0, [0.0, 0.0, 150.0]));
//! let x = rps.inverse(&v, &[0.0; 3]).unwrap();
//! // All three legs extending at 1 mm/s: the platform rises, and turns as the legs lean.
//! let t = twist(&rps, &v, &x, &[1.0, 1.0, 1.0]).unwrap();
//! assert!(t.linear[2] > 0.5);
//! // The legs' rates back from that twist, which the 3-RPS can make: nothing left over.
//! let back = input_rates(&rps, &v, &x, &t).unwrap();
//! assert!(back.rates.iter().all(|r| (r - 1.0).abs() < 1e-9));
//! assert!(back.left_over.angular.iter().chain(&back.left_over.linear).all(|e| e.abs() < 1e-9));
//! ```

mod frame;
mod least_squares;
mod statics;

pub use statics::{Wrench, input_efforts};

use crate::math::{cross3, scale_or_one, size, sub3};
use crate::mechanism::Mechanism;
use frame::Frame;
use least_squares::least_squares;

/// Why no velocity could be computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VelocityError {
    /// `(v, x)` is not a solution of F(v, x) = 0: its Newton correction `error` exceeds 1e-3 of
    /// ‖v‖ (the loosest tolerance a solver accepts). Pass a solver's answer with the inputs it
    /// was solved for.
    NotASolution {
        /// ‖B⁻¹F(v, x)‖.
        error: f64,
    },
    /// B is singular at the configuration (a direct singularity: the inputs do not determine
    /// the motion there), or, for [`input_rates`], some combination of input rates moves the
    /// platform not at all.
    Singular,
    /// A value given, or one computed from it, is NaN or infinite.
    NonFinite,
    /// The platform's frame pivots are collinear to rounding at `v` (or a line's pivots
    /// coincide there): its angular velocity is not determined by their rates. The pivots'
    /// rates are [`pivot_rates`].
    NoFrame,
}

impl core::fmt::Display for VelocityError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            VelocityError::NotASolution { error } => {
                write!(f, "not a solution: its Newton correction is {error:e}")
            }
            VelocityError::Singular => {
                write!(f, "singular configuration: the rates are not determined")
            }
            VelocityError::NonFinite => write!(f, "a value is not finite"),
            VelocityError::NoFrame => {
                write!(f, "the platform has no frame of three non-collinear pivots")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for VelocityError {}

/// The platform's velocity: its angular velocity and the velocity of its frame's origin (the
/// point [`Pose::translation`](crate::pose::Pose) places), both in base-frame axes; per unit of time
/// of the input rates (rad and mm per second for rates per second). For a line platform (a
/// linear pentapod's tool axis), whose spin about itself no pair fixes, ω is square to the
/// line: its part along the line is no motion of the platform's pivots, and no input makes or
/// feels it ([`input_rates`] leaves it over, [`input_efforts`] gives a moment about the line
/// no effort). For a point platform (a five-bar's output, a tripod's apex), which no pair turns
/// at all, ω is zero and `linear` is the point's velocity; [`input_rates`] leaves any ω over and
/// [`input_efforts`] gives any moment no effort.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Twist {
    /// ω, rad per unit time.
    pub angular: [f64; 3],
    /// The frame origin's velocity, length per unit time.
    pub linear: [f64; 3],
}

impl Twist {
    /// The velocity of a platform point now at `p` (base frame, the origin at `origin`):
    /// linear + ω × (p − origin).
    pub fn at(&self, origin: [f64; 3], p: [f64; 3]) -> [f64; 3] {
        let w = cross3(self.angular, sub3(p, origin));
        [0, 1, 2].map(|i| self.linear[i] + w[i])
    }

    fn as_array(&self) -> [f64; 6] {
        let [a, b, c] = self.angular;
        let [d, e, f] = self.linear;
        [a, b, c, d, e, f]
    }
}

/// Input rates for a wanted twist ([`input_rates`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rates<const M: usize> {
    /// ẋ: the input rates whose twist is nearest the wanted one.
    pub rates: [f64; M],
    /// The twist of `rates` minus the wanted twist: zero, to rounding, where the wanted motion
    /// is one the mechanism can make (always, for six independent inputs moving a platform of
    /// six freedoms); otherwise the part of it the inputs cannot produce.
    pub left_over: Twist,
}

/// v̇ = −B⁻¹ (∂F/∂x) ẋ: the rates of every unknown at the solution `(v, x)` for input rates
/// `xdot`. One factorisation of B and one solve.
pub fn pivot_rates<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    xdot: &[f64; M],
) -> Result<[f64; N], VelocityError> {
    let mut fac = sys.new_factor();
    factor(sys, v, x, &mut fac)?;
    rates_with(sys, v, x, &fac, xdot)
}

/// The platform's [`Twist`] at the solution `(v, x)` for input rates `xdot`.
pub fn twist<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    xdot: &[f64; M],
) -> Result<Twist, VelocityError> {
    let frame = Frame::of(sys, v)?;
    let vdot = pivot_rates(sys, v, x, xdot)?;
    frame.twist(&vdot)
}

/// The platform Jacobian at the solution `(v, x)`: column j is the [`Twist`] of a unit rate of
/// input j, as rows ωx, ωy, ωz, then the frame origin's velocity x, y, z. One factorisation
/// and `M` solves.
pub fn platform_jacobian<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Result<[[f64; M]; 6], VelocityError> {
    jacobian_in(sys, &Frame::of(sys, v)?, v, x)
}

/// [`platform_jacobian`] for the frame at `v`.
fn jacobian_in<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    frame: &Frame,
    v: &[f64; N],
    x: &[f64; M],
) -> Result<[[f64; M]; 6], VelocityError> {
    let mut fac = sys.new_factor();
    factor(sys, v, x, &mut fac)?;
    let mut j = [[0.0; M]; 6];
    for input in 0..M {
        let mut unit = [0.0; M];
        unit[input] = 1.0;
        let column = frame
            .twist(&rates_with(sys, v, x, &fac, &unit)?)?
            .as_array();
        for (row, value) in j.iter_mut().zip(column) {
            row[input] = value;
        }
    }
    Ok(j)
}

/// The input rates that move the platform with `wanted` at the solution `(v, x)`: the
/// least-squares solution of J ẋ = wanted over the [`platform_jacobian`] J (by Householder
/// reflections; the angular rows weighted by the distance between the first two frame pivots,
/// so that both halves are lengths per unit time, and so left out for a point platform), with
/// what the inputs cannot produce in
/// [`Rates::left_over`]. A mechanism with fewer inputs than six can make only some twists (a
/// 3-RPS cannot slide sideways): check the left-over part, given unweighted, in the wanted
/// twist's units. [`VelocityError::Singular`] where two combinations of input rates give the
/// same twist to rounding (an inverse singularity, or more than six inputs).
pub fn input_rates<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    wanted: &Twist,
) -> Result<Rates<M>, VelocityError> {
    let t = wanted.as_array();
    if !t.iter().all(|c| c.is_finite()) {
        return Err(VelocityError::NonFinite);
    }
    let frame = Frame::of(sys, v)?;
    let j = jacobian_in(sys, &frame, v, x)?;
    // The angular rows weighted by the platform's size, so that both halves of the residual
    // are lengths per unit time: otherwise "nearest" would depend on the unit of length.
    let size = frame.size();
    let mut weighted = j;
    let mut rhs = t;
    for r in 0..3 {
        for c in weighted[r].iter_mut() {
            *c *= size;
        }
        rhs[r] *= size;
    }
    let rates = least_squares(weighted, rhs).ok_or(VelocityError::Singular)?;
    let made = (0..6).map(|r| (0..M).map(|c| j[r][c] * rates[c]).sum::<f64>() - t[r]);
    let mut left = [0.0; 6];
    for (l, m) in left.iter_mut().zip(made) {
        *l = m;
    }
    if !rates.iter().chain(&left).all(|c| c.is_finite()) {
        return Err(VelocityError::NonFinite);
    }
    Ok(Rates {
        rates,
        left_over: Twist {
            angular: [left[0], left[1], left[2]],
            linear: [left[3], left[4], left[5]],
        },
    })
}

/// How far from a solution `(v, x)` may be, relative to ‖v‖: the loosest tolerance the
/// solvers accept (`Options::check_for`), so that any answer they return passes.
const SOLUTION: f64 = 1e-3;

/// B factored at `(v, x)`, after checking that `(v, x)` is a solution (its Newton correction
/// within [`SOLUTION`] of ‖v‖): rates anywhere else would be rates of nothing.
fn factor<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    fac: &mut S::Factor,
) -> Result<(), VelocityError> {
    if !(v.iter().chain(x).all(|c| c.is_finite())) {
        return Err(VelocityError::NonFinite);
    }
    sys.factor(v, x, fac).ok_or(VelocityError::Singular)?;
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    sys.solve(fac, &mut f);
    let error = size(&f);
    if error <= SOLUTION * scale_or_one(size(v)) {
        Ok(())
    } else if error.is_finite() {
        Err(VelocityError::NotASolution { error })
    } else {
        Err(VelocityError::NonFinite)
    }
}

fn rates_with<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    fac: &S::Factor,
    xdot: &[f64; M],
) -> Result<[f64; N], VelocityError> {
    if !xdot.iter().all(|c| c.is_finite()) {
        return Err(VelocityError::NonFinite);
    }
    let solved = |xdot: &[f64; M]| {
        let mut out = [0.0; N];
        sys.input_derivative(v, x, xdot, &mut out);
        sys.solve(fac, &mut out);
        for o in out.iter_mut() {
            *o = -*o;
        }
        out
    };
    let out = solved(xdot);
    if out.iter().all(|c| c.is_finite()) {
        return Ok(out);
    }
    // Finite rates and a factorisation that passed: either the rates are so large that the
    // pivots' overflow (1e308 of each), or B is singular to rounding. The rates scaled to a
    // largest of 1 tell which (a B that passed gave `Singular` for both).
    let largest = xdot.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    let unit = xdot.map(|r| r / largest);
    if largest > 1.0 && solved(&unit).iter().all(|c| c.is_finite()) {
        Err(VelocityError::NonFinite)
    } else {
        Err(VelocityError::Singular)
    }
}
