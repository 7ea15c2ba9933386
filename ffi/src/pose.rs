//! LinuxCNC's pose words: X Y Z and A B C in degrees, with `R = Rz(C) · Ry(B) · Rx(A)`
//! (posemath's roll–pitch–yaw, as genhexkins uses it), `p_world = R · p_platform + (X, Y, Z)`.

use linkage::Pose;

/// A platform pose as LinuxCNC's `EmcPose` holds it: translation, then A, B, C in degrees.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinkagePose {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub a: f64,
    pub b: f64,
    pub c: f64,
}

impl LinkagePose {
    pub fn is_finite(&self) -> bool {
        [self.x, self.y, self.z, self.a, self.b, self.c]
            .iter()
            .all(|v| v.is_finite())
    }

    /// The rigid motion: roll A about x, then pitch B about y, then yaw C about z.
    pub fn to_pose(&self) -> Pose {
        let r = f64::to_radians;
        Pose::from_euler(r(self.c), r(self.b), r(self.a), [self.x, self.y, self.z])
    }

    /// The angles of `pose` nearest `near`: each rotation has two A B C triples (and every
    /// angle its turns), and LinuxCNC interpolates and limits the words, so the one continuous
    /// with the caller's last pose is the right one to hand back.
    pub fn from_pose(pose: &Pose, near: &LinkagePose) -> LinkagePose {
        let [yaw, pitch, roll] = pose.euler().map(f64::to_degrees);
        let [x, y, z] = pose.translation;
        let first = [roll, pitch, yaw];
        // The same rotation with B mirrored about ±90°.
        let second = [roll + 180.0, 180.0 - pitch, yaw + 180.0];
        let target = [near.a, near.b, near.c];
        let unwrap = |t: [f64; 3]| -> [f64; 3] {
            [0, 1, 2].map(|i| t[i] + 360.0 * ((target[i] - t[i]) / 360.0).round())
        };
        let distance = |t: [f64; 3]| -> f64 { (0..3).map(|i| (t[i] - target[i]).powi(2)).sum() };
        let (a, b) = (unwrap(first), unwrap(second));
        let [a, b, c] = if distance(b) < distance(a) { b } else { a };
        LinkagePose { x, y, z, a, b, c }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(p: &LinkagePose, q: &LinkagePose) -> bool {
        let d = [
            p.x - q.x,
            p.y - q.y,
            p.z - q.z,
            p.a - q.a,
            p.b - q.b,
            p.c - q.c,
        ];
        d.iter().all(|v| v.abs() < 1e-9)
    }

    #[test]
    fn round_trip_keeps_the_words() {
        let p = LinkagePose {
            x: 1.0,
            y: -2.0,
            z: 20.0,
            a: 5.0,
            b: -7.0,
            c: 30.0,
        };
        assert!(close(&LinkagePose::from_pose(&p.to_pose(), &p), &p));
    }

    #[test]
    fn matches_posemath_rpy() {
        // R = Rz(C) Ry(B) Rx(A): a point on the platform's x axis under pure roll stays put,
        // under pure yaw of 90° it goes to +y.
        let yaw = LinkagePose {
            c: 90.0,
            ..Default::default()
        }
        .to_pose();
        let p = yaw.apply([1.0, 0.0, 0.0]);
        assert!(p[0].abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12);
        let roll = LinkagePose {
            a: 90.0,
            ..Default::default()
        }
        .to_pose();
        let p = roll.apply([0.0, 1.0, 0.0]);
        assert!(
            (p[2] - 1.0).abs() < 1e-12,
            "roll about x takes y to z: {p:?}"
        );
    }

    #[test]
    fn angles_follow_the_caller_past_half_a_turn() {
        let p = LinkagePose {
            c: 190.0,
            a: -185.0,
            ..Default::default()
        };
        assert!(close(&LinkagePose::from_pose(&p.to_pose(), &p), &p));
        let near = LinkagePose {
            c: 170.0,
            ..Default::default()
        };
        let q = LinkagePose::from_pose(&p.to_pose(), &near);
        assert!(
            (q.c - 190.0).abs() < 1e-9 && (q.a - 175.0).abs() < 1e-9,
            "{q:?}"
        );
    }

    #[test]
    fn pitch_beyond_a_right_angle_keeps_its_triple() {
        let p = LinkagePose {
            a: 10.0,
            b: 100.0,
            c: -20.0,
            ..Default::default()
        };
        let q = LinkagePose::from_pose(&p.to_pose(), &p);
        assert!(close(&q, &p), "{q:?}");
    }
}
