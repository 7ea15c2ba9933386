//! Statics: what a load on the platform puts on each actuator, the transpose of the platform
//! Jacobian.

use super::{Twist, VelocityError, platform_jacobian};
use crate::mechanism::Mechanism;

/// A load on the platform: a force through its frame's origin and a moment, both in base-frame
/// axes (length times force for the moment, in the same length unit as the mechanism).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Wrench {
    /// The moment about the frame's origin.
    pub moment: [f64; 3],
    /// The force.
    pub force: [f64; 3],
}

/// The actuator efforts a load on the platform puts on the inputs at the solution `(v, x)`:
/// τ = Jᵀ w over the [`platform_jacobian`] J (virtual work: τ · ẋ = moment · ω + force · v_o
/// for every input rate ẋ), forces for prismatic inputs and torques for revolute ones. To
/// hold the platform against the load, the actuators exert −τ; the passive joints take the
/// rest (a 3-RPS's hinges carry what its legs cannot).
///
/// ```
/// use linkage::velocity::{input_efforts, Wrench};
/// use linkage::{Mechanism, Pose};
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
/// let rps = Rps::new();
/// let v = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// let x = rps.inverse(&v, &[0.0; 3]).unwrap();
/// // 30 N of weight on the level platform's centre: each leg leans inwards (50 mm in over
/// // 150 mm up) and takes 10 N of it upright, 10 N / cos 18.4° along itself, pushing it shorter.
/// let weight = Wrench { moment: [0.0; 3], force: [0.0, 0.0, -30.0] };
/// let tau = input_efforts(&rps, &v, &x, &weight).unwrap();
/// let along = 10.0 * (50.0f64.powi(2) + 150.0f64.powi(2)).sqrt() / 150.0;
/// assert!(tau.iter().all(|t| (t + along).abs() < 1e-3), "{tau:?}");
/// ```
pub fn input_efforts<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    load: &Wrench,
) -> Result<[f64; M], VelocityError> {
    let w = Twist {
        angular: load.moment,
        linear: load.force,
    }
    .as_array();
    if !w.iter().all(|c| c.is_finite()) {
        return Err(VelocityError::NonFinite);
    }
    let j = platform_jacobian(sys, v, x)?;
    let mut tau = [0.0; M];
    for (input, t) in tau.iter_mut().enumerate() {
        *t = (0..6).map(|r| j[r][input] * w[r]).sum();
    }
    if tau.iter().all(|c| c.is_finite()) {
        Ok(tau)
    } else {
        Err(VelocityError::NonFinite)
    }
}
