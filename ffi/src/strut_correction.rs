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
        if self.is_on() && axes.clone().any(|n| norm(*n) == 0.0) {
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
            let n3 = unit(cross(u, cross(self.base_n[i], u))).ok_or(status::FAILED)?;
            let turned = sub(pose.apply(self.platform_n[i]), pose.translation);
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

/// `a / |a|`, or None when `a` is (relative to rounding) zero.
fn unit(a: [f64; 3]) -> Option<[f64; 3]> {
    let n = norm(a);
    (n > 1e-12 && n.is_finite()).then(|| a.map(|v| v / n))
}
