linkage::mechanism! {
    /// A delta robot: cranks of 100 mm on tangent axes at radius 100 mm, parallelograms
    /// 60 mm wide of rods `rod`, a platform of radius 40 mm.
    pub struct Delta;
    params {
        rb = 100.0, ra = 100.0, rp = 40.0, hw = 30.0, h = 200.0,
        rod = sqrt((rb + ra - rp) * (rb + ra - rp) + h * h),
        c2 = cos(2.0 * pi / 3.0), s2 = sin(2.0 * pi / 3.0),
    }
    base {
        A1 = [rb, 0.0, 0.0], B1 = [rb, 1.0, 0.0],
        A2 = [rb * c2, rb * s2, 0.0], B2 = [rb * c2 - s2, rb * s2 + c2, 0.0],
        A3 = [rb * c2, -rb * s2, 0.0], B3 = [rb * c2 + s2, -rb * s2 + c2, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -200.0]) {
        F11 = [rp, hw, 0.0], F12 = [rp, -hw, 0.0],
        F21 = [rp * c2 - hw * s2, rp * s2 + hw * c2, 0.0], F22 = [rp * c2 + hw * s2, rp * s2 - hw * c2, 0.0],
        F31 = [rp * c2 + hw * s2, -rp * s2 + hw * c2, 0.0], F32 = [rp * c2 - hw * s2, -rp * s2 - hw * c2, 0.0],
    }
    link arm1 { E11 = [rb + ra, hw, 0.0], E12 = [rb + ra, -hw, 0.0] }
    link arm2 {
        E21 = [(rb + ra) * c2 - hw * s2, (rb + ra) * s2 + hw * c2, 0.0],
        E22 = [(rb + ra) * c2 + hw * s2, (rb + ra) * s2 - hw * c2, 0.0],
    }
    link arm3 {
        E31 = [(rb + ra) * c2 + hw * s2, -(rb + ra) * s2 + hw * c2, 0.0],
        E32 = [(rb + ra) * c2 - hw * s2, -(rb + ra) * s2 - hw * c2, 0.0],
    }
    link rod11 { length = rod } link rod12 { length = rod }
    link rod21 { length = rod } link rod22 { length = rod }
    link rod31 { length = -368.8 } link rod32 { length = rod }
    chain arm1a = base - R(active q1, axis = A1 -> B1) - arm1 - S(E11) - rod11 - S(F11) - platform;
    chain arm1b = arm1 - S(E12) - rod12 - S(F12) - platform;
    chain arm2a = base - R(active q2, axis = A2 -> B2) - arm2 - S(E21) - rod21 - S(F21) - platform;
    chain arm2b = arm2 - S(E22) - rod22 - S(F22) - platform;
    chain arm3a = base - R(active q3, axis = A3 -> B3) - arm3 - S(E31) - rod31 - S(F31) - platform;
    chain arm3b = arm3 - S(E32) - rod32 - S(F32) - platform;
}

fn main() {}
