//! genhexkins' strut length correction, for struts driven by a screw whose joints turn the nut.
//!
//! A strut's screw turns with the relative rotation of its two end joints about the strut, so
//! the length a strut's encoder reports is the geometric length plus `lead · φ / 2π`, where
//! φ = asin(n₃ · n₂) is the angle between the two joints' axes seen across the strut:
//! n₃ = u × (n_b × u) (the base joint's axis n_b made normal to the strut direction u) and
//! n₂ = (R n_p) × u (the platform joint's axis n_p, turned with the platform). This is the
//! model LinuxCNC's genhexkins applies when its `screw-lead` pin is not zero; the same pins
//! (`base-n`, `platform-n`, `screw-lead`) drive it here.

use linkage::Pose;

use crate::geometry::LinkageGeometry;
use crate::status;

/// The joints' axes (base ones in the base frame, platform ones in the platform frame) and
/// the screw lead (length per turn; 0 turns the correction off).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkageStrutCorrection {
    pub base_n: [[f64; 3]; 6],
    pub platform_n: [[f64; 3]; 6],
    pub screw_lead: f64,
}

impl LinkageStrutCorrection {
    /// No correction.
    pub const NONE: LinkageStrutCorrection = LinkageStrutCorrection {
        base_n: [[0.0; 3]; 6],
        platform_n: [[0.0; 3]; 6],
        screw_lead: 0.0,
    };

    pub fn is_on(&self) -> bool {
        self.screw_lead != 0.0
    }

    /// Finite values and, when on, axes of non-zero length.
    pub fn check(&self) -> Result<(), i32> {
        let axes = self.base_n.iter().chain(&self.platform_n);
        if !self.screw_lead.is_finite() || !axes.clone().flatten().all(|v| v.is_finite()) {
            return Err(status::NON_FINITE);
        }
        if self.is_on() && axes.clone().any(|n| direction(*n).is_none()) {
            return Err(status::INVALID_GEOMETRY);
        }
        Ok(())
    }

    /// Each strut's correction at `pose` (0 when off). Fails where a strut runs along its base
    /// joint's axis or its platform joint's axis, where the angle is undefined.
    pub fn at(&self, g: &LinkageGeometry, pose: &Pose) -> Result<[f64; 6], i32> {
        let mut out = [0.0; 6];
        if !self.is_on() {
            return Ok(out);
        }
        for (i, c) in out.iter_mut().enumerate() {
            let w = pose.apply(g.platform[i]);
            let u = unit(sub(w, g.base[i])).ok_or(status::FAILED)?;
            // The axes as directions: their length is the caller's unit, not the strut's (axes
            // 1e300 long overflowed the cross products, and every call failed).
            let (nb, np) = (direction(self.base_n[i]), direction(self.platform_n[i]));
            let (nb, np) = (nb.ok_or(status::FAILED)?, np.ok_or(status::FAILED)?);
            let n3 = unit(cross(u, cross(nb, u))).ok_or(status::FAILED)?;
            let turned = sub(pose.apply(np), pose.translation);
            let n2 = unit(cross(turned, u)).ok_or(status::FAILED)?;
            // Rounding may put the dot product of two unit vectors just outside [-1, 1].
            let dot = (n3[0] * n2[0] + n3[1] * n2[1] + n3[2] * n2[2]).clamp(-1.0, 1.0);
            *c = self.screw_lead * dot.asin() / core::f64::consts::TAU;
        }
        Ok(out)
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// An axis of any length a double holds, scaled by a power of two so that its largest
/// component is in [1, 2): exact, so the corrections are bit for bit those of the axis as
/// given wherever that one neither overflows nor underflows (genhexkins' formula near
/// asin(±1) is ill-conditioned enough that dividing by the norm instead moved a correction by
/// 1.2e-12), and neither 1e300 nor 1e-300 over- or underflows. None for a zero or non-finite
/// axis.
fn direction(a: [f64; 3]) -> Option<[f64; 3]> {
    let m = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    // m's binary exponent (a subnormal m brought up by 2^64 first).
    let (m, pre) = if m < f64::MIN_POSITIVE {
        (m * pow2(64), 64)
    } else {
        (m, 0)
    };
    let e = ((m.to_bits() >> 52) & 0x7ff) as i32 - 1023 - pre;
    // 2^-e in two factors, each a normal number.
    let half = -e / 2;
    Some(a.map(|v| v * pow2(half) * pow2(-e - half)))
}

/// 2^k for k in [-1022, 1023].
fn pow2(k: i32) -> f64 {
    f64::from_bits(((1023 + k) as u64) << 52)
}

/// `a / |a|`, or None when `a` is (relative to rounding) zero.
fn unit(a: [f64; 3]) -> Option<[f64; 3]> {
    let n = norm(a);
    (n > 1e-12 && n.is_finite()).then(|| a.map(|v| v / n))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An axis is a direction: scaled by 1e300 or 1e-300 it gives the corrections of the unit
    /// axis (1e300 overflowed the cross products, and every forward call failed), and a zero
    /// axis is refused when the correction is set.
    #[test]
    fn axes_of_any_length_give_the_corrections_of_their_directions() {
        let g = LinkageGeometry {
            base: core::array::from_fn(|i| {
                let a = i as f64 * core::f64::consts::TAU / 6.0;
                [200.0 * a.cos(), 200.0 * a.sin(), 0.0]
            }),
            platform: core::array::from_fn(|i| {
                let a = (i as f64 + 0.5) * core::f64::consts::TAU / 6.0;
                [100.0 * a.cos(), 100.0 * a.sin(), 0.0]
            }),
        };
        let pose = Pose::from_euler(0.1, -0.05, 0.2, [3.0, -4.0, 250.0]);
        let with = |scale: f64| LinkageStrutCorrection {
            base_n: core::array::from_fn(|i| [0.3 * scale, -0.2 * scale, (1.0 + i as f64) * scale]),
            platform_n: core::array::from_fn(|i| {
                [-0.1 * scale, 0.4 * scale, (2.0 - 0.1 * i as f64) * scale]
            }),
            screw_lead: 5.0,
        };
        let unit = with(1.0).at(&g, &pose).unwrap();
        assert!(unit.iter().any(|c| c.abs() > 1e-3), "{unit:?}");
        for scale in [1e300, 1e-300, 3.7] {
            let c = with(scale);
            assert_eq!(c.check(), Ok(()));
            let got = c.at(&g, &pose).unwrap();
            for (a, b) in got.iter().zip(&unit) {
                assert!((a - b).abs() < 1e-12, "scale {scale}: {got:?} vs {unit:?}");
            }
        }
        let mut zero = with(1.0);
        zero.platform_n[3] = [0.0; 3];
        assert_eq!(zero.check(), Err(status::INVALID_GEOMETRY));
    }
}
