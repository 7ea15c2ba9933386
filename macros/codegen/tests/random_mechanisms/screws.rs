//! The oracle: first-order kinematics at home by screw theory, from the declaration as the
//! generator made it and the README's pair table, nothing of the model. Each pair's unit twists
//! at home in the base frame, (ω, v) with v the velocity of the point at the base's origin;
//! every chain's twists sum, from the link it starts at to each declared link on it, to that
//! link's twist relative to the link before it (an active input is "the link after relative
//! to the link before, in the chain's direction"); the loop closures, solved by least squares
//! for the declared links' twists and the passive rates, give the platform's twist.

use crate::generator::{add, cross, norm, scale, sub, unit, Joint, Kind, Mech, BASE, PLATFORM, V3};
use nalgebra::{DMatrix, DVector};

/// (ω, v), v in units of [`UNIT`] per unit rate: turns and moments of comparable size, so
/// that singular values compare (a moment in mm would outweigh a turn a hundredfold).
type Twist = [f64; 6];

/// The oracle's unit of length, in the declaration's (mm).
pub const UNIT: f64 = 100.0;

fn revolute(axis: V3, through: V3) -> Twist {
    let v = cross(scale(1.0 / UNIT, through), axis);
    [axis[0], axis[1], axis[2], v[0], v[1], v[2]]
}

fn slide(dir: V3) -> Twist {
    let v = scale(1.0 / UNIT, dir);
    [0.0, 0.0, 0.0, v[0], v[1], v[2]]
}

/// Which rate a twist is scaled by.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum Rate {
    Input(usize),
    Passive(usize),
}

/// Whether U pair `k` of `chain` has its first axis's points on the link after it (the README
/// allows either link), its second axis then fixed in the link before.
pub fn axis_after(m: &Mech, chain: usize, k: usize) -> bool {
    let c = &m.chains[chain];
    let (a, _) = c.joints[k].axis.expect("a U has an axis");
    c.links[k + 1] == Some(m.pivots[a].link) && c.links[k] != Some(m.pivots[a].link)
}

/// The leg's far end from the centre of U pair `k` (the README's U): the centre of the nearest
/// pair on the other link's side that has one (after the U where its first axis is on the link
/// before, before it where the axis is on the link after; an S or U centre, an R's first axis
/// pivot; P, C and H pairs passed over); where there is none, the pivot declared on the other
/// link (the one right after or before the U, not the chain's end: they differ when a P, C or H
/// lies between) farthest from the centre; `None` where that link declares no pivot (the leg,
/// and with it the second axis, is then undefined: the model must refuse it).
fn leg_end(m: &Mech, chain: usize, k: usize, centre: V3) -> Option<V3> {
    let c = &m.chains[chain];
    let after = axis_after(m, chain, k);
    let side: Vec<&Joint> = if after {
        c.joints[..k].iter().rev().collect()
    } else {
        c.joints[k + 1..].iter().collect()
    };
    for j in side {
        match (j.kind, j.centre, j.axis) {
            (Kind::S | Kind::U, Some(p), _) => return Some(m.pivots[p].at),
            (Kind::R, _, Some((a, _))) => return Some(m.pivots[a].at),
            _ => {}
        }
    }
    // The generator leaves a link unnamed only inside a leg, where a centre always follows a
    // U (a rod to the ball).
    let other = c.links[if after { k } else { k + 1 }]
        .expect("the other link of a U with no centre on its side is declared");
    m.pivots
        .iter()
        .filter(|p| p.link == other)
        .map(|p| p.at)
        .max_by(|a, b| norm(sub(*a, centre)).total_cmp(&norm(sub(*b, centre))))
}

/// The centre a leg's slide runs from or to: an S or U centre, an R's first axis point.
fn centre_of(m: &Mech, j: &Joint) -> Option<V3> {
    match (j.kind, j.centre, j.axis) {
        (Kind::S | Kind::U, Some(p), _) => Some(m.pivots[p].at),
        (Kind::R, _, Some((a, _))) => Some(m.pivots[a].at),
        _ => None,
    }
}

/// The centres a leg's slide (joint `k` of `chain`, a P without an axis) runs between.
pub fn leg_ends(m: &Mech, chain: usize, k: usize) -> [V3; 2] {
    let joints = &m.chains[chain].joints;
    let from = joints[..k].iter().rev().find_map(|j| centre_of(m, j));
    let to = joints[k + 1..].iter().find_map(|j| centre_of(m, j));
    [from.unwrap(), to.unwrap()]
}

/// Joint `k` of chain `chain`'s declared axis, if it has one: a point on it and its unit
/// direction, at home.
pub fn joint_axis(m: &Mech, chain: usize, k: usize) -> Option<(V3, V3)> {
    m.chains[chain].joints[k].axis.map(|(a, b)| {
        let (a, b) = (m.pivots[a].at, m.pivots[b].at);
        (a, unit(sub(b, a)))
    })
}

/// The unit twists of joint `k` of chain `chain`, one per freedom, in the order of its
/// joint variables when it is active.
pub fn joint_twists(m: &Mech, chain: usize, k: usize) -> Vec<Twist> {
    let j = &m.chains[chain].joints[k];
    let axis = joint_axis(m, chain, k);
    match j.kind {
        Kind::R => {
            let (a, u) = axis.unwrap();
            vec![revolute(u, a)]
        }
        Kind::P => match axis {
            Some((_, u)) => vec![slide(u)],
            // A leg between two joint centres: its length grows along the line from the
            // centre before to the centre after.
            None => {
                let [from, to] = leg_ends(m, chain, k);
                vec![slide(unit(sub(to, from)))]
            }
        },
        // `active θ z`: θ as R, z as P.
        Kind::C => {
            let (a, u) = axis.unwrap();
            vec![revolute(u, a), slide(u)]
        }
        // θ as R, and the slide pθ/2π along A→B.
        Kind::H => {
            let (a, u) = axis.unwrap();
            let p = j.lead.unwrap() / std::f64::consts::TAU / UNIT;
            let t = revolute(u, a);
            vec![[
                t[0],
                t[1],
                t[2],
                t[3] + p * u[0],
                t[4] + p * u[1],
                t[5] + p * u[2],
            ]]
        }
        // Rz(yaw)·Ry(pitch)·Rx(roll) in the base frame's axes: at zero, d/dyaw turns about z,
        // d/dpitch about y, d/droll about x.
        Kind::S => {
            let c = m.pivots[j.centre.unwrap()].at;
            [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]
                .into_iter()
                .map(|e| revolute(e, c))
                .collect()
        }
        // a about P→Q, b about the second axis, along (Q − P) × (leg).
        Kind::U => {
            let c = m.pivots[j.centre.unwrap()].at;
            let (_, u1) = axis.unwrap();
            let leg = leg_end(m, chain, k, c).map_or([0.0; 3], |end| sub(end, c));
            // Where the leg is along the first axis (or has no length) the README leaves the
            // second axis undefined ([`undefined_u`]): any square to the first stands in, so
            // that the closure stays finite.
            let n = cross(u1, leg);
            let u2 = if norm(n) > 1e-9 * norm(leg) {
                unit(n)
            } else {
                let e = if u1[0].abs() < 0.6 {
                    [1.0, 0.0, 0.0]
                } else {
                    [0.0, 1.0, 0.0]
                };
                unit(cross(u1, e))
            };
            vec![revolute(u1, c), revolute(u2, c)]
        }
    }
}

/// The loop-closure velocity equations: `A_passive · [link twists; passive rates] + A_input ·
/// ẋ = 0`, with the index of the platform's twist among the unknowns.
pub struct Closure {
    pub passive: DMatrix<f64>,
    pub input: DMatrix<f64>,
    pub platform: usize,
    /// The links whose twists are the unknowns, in order (the platform first).
    pub links: Vec<usize>,
}

/// A chain's stretch between two declared links: the links and its pairs' twists.
type Segment = (usize, usize, Vec<(Twist, Rate)>);

pub fn closure(m: &Mech) -> Closure {
    // Every declared moving link on a chain has a twist (6 unknowns); the platform first.
    let mut links = vec![PLATFORM];
    for c in &m.chains {
        for l in c.links.iter().flatten() {
            if *l != BASE && !links.contains(l) {
                links.push(*l);
            }
        }
    }
    // One segment per stretch of a chain between declared links: (from, to, its twists).
    let mut rows: Vec<Segment> = Vec::new();
    let mut passive = 0;
    for (ci, c) in m.chains.iter().enumerate() {
        let mut from = c.links[0].unwrap();
        let mut acc: Vec<(Twist, Rate)> = Vec::new();
        for (k, j) in c.joints.iter().enumerate() {
            for (f, t) in joint_twists(m, ci, k).into_iter().enumerate() {
                let rate = match j.inputs.get(f) {
                    Some(name) => Rate::Input(m.inputs.iter().position(|i| i == name).unwrap()),
                    None => {
                        passive += 1;
                        Rate::Passive(passive - 1)
                    }
                };
                acc.push((t, rate));
            }
            if let Some(to) = c.links[k + 1] {
                rows.push((from, to, std::mem::take(&mut acc)));
                from = to;
            }
        }
    }
    let n_links = links.len();
    let unknowns = 6 * n_links + passive;
    let mut a_pass = DMatrix::zeros(6 * rows.len(), unknowns);
    let mut a_in = DMatrix::zeros(6 * rows.len(), m.inputs.len());
    let slot = |l: usize| links.iter().position(|&x| x == l);
    for (r, (from, to, twists)) in rows.iter().enumerate() {
        // T_to − T_from − Σ ξ q̇ = 0.
        for i in 0..6 {
            if let Some(s) = slot(*to) {
                a_pass[(6 * r + i, 6 * s + i)] += 1.0;
            }
            if let Some(s) = slot(*from) {
                a_pass[(6 * r + i, 6 * s + i)] -= 1.0;
            }
            for (t, rate) in twists {
                match rate {
                    Rate::Input(x) => a_in[(6 * r + i, *x)] -= t[i],
                    Rate::Passive(p) => a_pass[(6 * r + i, 6 * n_links + p)] -= t[i],
                }
            }
        }
    }
    Closure {
        passive: a_pass,
        input: a_in,
        platform: 0,
        links,
    }
}

/// Whether some U's first axis lies along its leg at home, or it has no leg (no pair with a
/// centre on the other link's side, and no pivot declared on that link), where the README
/// leaves its second axis undefined (the model must refuse it).
pub fn undefined_u(m: &Mech) -> bool {
    m.chains.iter().enumerate().any(|(ci, c)| {
        c.joints.iter().enumerate().any(|(k, j)| {
            if j.kind != Kind::U {
                return false;
            }
            let centre = m.pivots[j.centre.unwrap()].at;
            let (_, u1) = joint_axis(m, ci, k).unwrap();
            let Some(end) = leg_end(m, ci, k, centre) else {
                return true;
            };
            let leg = sub(end, centre);
            !(norm(cross(u1, leg)) >= 1e-7 * norm(leg) && norm(leg) > 1e-9)
        })
    })
}

/// The largest velocity (over [`UNIT`]) of a declared pivot of a moving link in any motion the
/// inputs held allow: 0 when the inputs determine every pivot. An idle motion that moves none
/// (a rod's spin about the line through its two balls) leaves nothing of the model's free; one
/// that moves a pivot (a chain of seven freedoms with its ends held) leaves the model's
/// unknowns undetermined.
pub fn loose_pivots(m: &Mech, cl: &Closure) -> f64 {
    let (_, _, basis) = kernel_dim(&cl.passive);
    let mut loose: f64 = 0.0;
    for c in 0..basis.ncols() {
        for p in &m.pivots {
            let Some(slot) = cl.links.iter().position(|&l| l == p.link) else {
                continue;
            };
            let t: Twist = [0, 1, 2, 3, 4, 5].map(|i| basis[(6 * slot + i, c)]);
            loose = loose.max(norm(point_velocity(&t, p.at)) / UNIT);
        }
    }
    loose
}

/// What the oracle says at home.
pub struct Verdict {
    /// Kernel of the closure with the inputs free, less the idle freedoms (those that move no
    /// input): the mechanism's mobility.
    pub mobility: usize,
    /// Idle freedoms (a rod's spin between two S).
    pub idle: usize,
    /// The largest share of a platform twist in any idle motion: 0 when the inputs determine
    /// the platform.
    pub platform_free: f64,
    /// The smallest singular value above the kernel, over the largest: how well the
    /// platform's twist is determined.
    pub condition: f64,
}

fn kernel_dim(a: &DMatrix<f64>) -> (usize, f64, DMatrix<f64>) {
    let cols = a.ncols();
    // Zero rows square it up: nalgebra's SVD of a wide matrix has fewer right singular
    // vectors than columns.
    let rows = a.nrows().max(cols);
    let padded = DMatrix::from_fn(
        rows,
        cols,
        |r, c| if r < a.nrows() { a[(r, c)] } else { 0.0 },
    );
    // Bounded: nalgebra's `svd` iterates without limit, and loops for good on a matrix with a
    // NaN; the sweep reports the seed of a panic.
    let svd = padded
        .try_svd(false, true, f64::EPSILON, 10_000)
        .expect("the oracle's SVD does not converge");
    let s = &svd.singular_values;
    let vt = svd.v_t.unwrap();
    let max = s.max().max(1e-300);
    let tol = 1e-9 * max;
    let kernel: Vec<usize> = (0..cols).filter(|&i| s[i] < tol).collect();
    let above = (0..cols)
        .map(|i| s[i])
        .filter(|&x| x >= tol)
        .fold(max, f64::min);
    let mut basis = DMatrix::zeros(cols, kernel.len());
    for (c, &i) in kernel.iter().enumerate() {
        for r in 0..cols {
            basis[(r, c)] = vt[(i, r)];
        }
    }
    (kernel.len(), above / max, basis)
}

pub fn verdict(cl: &Closure) -> Verdict {
    let (idle, condition, basis) = kernel_dim(&cl.passive);
    let mut platform_free: f64 = 0.0;
    for c in 0..basis.ncols() {
        let t: f64 = (0..6)
            .map(|i| basis[(6 * cl.platform + i, c)].powi(2))
            .sum::<f64>()
            .sqrt();
        platform_free = platform_free.max(t);
    }
    let full = DMatrix::from_fn(
        cl.passive.nrows(),
        cl.passive.ncols() + cl.input.ncols(),
        |r, c| {
            if c < cl.passive.ncols() {
                cl.passive[(r, c)]
            } else {
                cl.input[(r, c - cl.passive.ncols())]
            }
        },
    );
    let (all, _, _) = kernel_dim(&full);
    Verdict {
        mobility: all - idle,
        idle,
        platform_free,
        condition,
    }
}

/// The platform's twist for input rates `xdot`, and the closure's relative residual there: least
/// squares by QR, with the idle freedoms held at zero (rows of the kernel's basis appended), so
/// that the system has full column rank. (nalgebra's SVD solve was off by 7e-5 on a regular
/// 72×72 closure.)
pub fn platform_twist(cl: &Closure, xdot: &[f64]) -> Result<(Twist, f64), String> {
    let rhs = -(&cl.input * DVector::from_column_slice(xdot));
    let (idle, _, basis) = kernel_dim(&cl.passive);
    let (rows, cols) = cl.passive.shape();
    let a = DMatrix::from_fn(rows + idle, cols, |r, c| {
        if r < rows {
            cl.passive[(r, c)]
        } else {
            basis[(c, r - rows)]
        }
    });
    let b = DVector::from_fn(rows + idle, |r, _| if r < rows { rhs[r] } else { 0.0 });
    let qr = a.qr();
    let y = qr
        .r()
        .solve_upper_triangular(&(qr.q().transpose() * &b))
        .ok_or("the closure's R factor is singular")?;
    let residual = (&cl.passive * &y - &rhs).norm() / rhs.norm().max(1e-300);
    let p = 6 * cl.platform;
    Ok(([0, 1, 2, 3, 4, 5].map(|i| y[p + i]), residual))
}

/// The velocity of a point of a link at `at` (its position at home) under the link's twist `t`.
pub fn point_velocity(t: &Twist, at: V3) -> V3 {
    add(
        scale(UNIT, [t[3], t[4], t[5]]),
        cross([t[0], t[1], t[2]], at),
    )
}
