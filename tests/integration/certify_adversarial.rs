//! The Krawczyk certificates against independent methods, where a wrong one would hide: roots
//! refined in double-double arithmetic (about 32 digits) near folds, where two roots meet, and
//! between mirror images close together; inputs just past a fold, where no real root is near;
//! and every real assembly mode the all-modes solver finds at the Table V points. A certified
//! box must never hold two roots, and must hold the root it encloses.

use linkage::lu::Lu;
use linkage::modes::{AllModes, ModesOptions, Roots};
use linkage::{
    arc_length, certify, certify_step, CertifiedSteps, Interval, Mechanism, Options, Pose, Status,
};
use linkage_examples::stewart::{home_start, Stewart, HOME_LEGS};
use linkage_tests::max_diff;

/// Double-double numbers: an unevaluated sum hi + lo with |lo| ≤ ulp(hi)/2, about 106 bits.
/// Dekker's and Knuth's error-free transformations (the product's error by a fused
/// multiply-add).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Dd {
    hi: f64,
    lo: f64,
}

impl Dd {
    fn from(x: f64) -> Self {
        Dd { hi: x, lo: 0.0 }
    }
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

fn quick_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

impl std::ops::Add for Dd {
    type Output = Dd;
    fn add(self, o: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let r = quick_two_sum(s, e + t);
        quick_two_sum(r.hi, r.lo + f)
    }
}

impl std::ops::Neg for Dd {
    type Output = Dd;
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl std::ops::Sub for Dd {
    type Output = Dd;
    fn sub(self, o: Dd) -> Dd {
        self + (-o)
    }
}

impl std::ops::Mul for Dd {
    type Output = Dd;
    fn mul(self, o: Dd) -> Dd {
        let p = self.hi * o.hi;
        let e = self.hi.mul_add(o.hi, -p);
        quick_two_sum(p, e + (self.hi * o.lo + self.lo * o.hi))
    }
}

impl linkage::Scalar for Dd {
    fn from_f64(x: f64) -> Self {
        Dd::from(x)
    }
    fn sq(self) -> Self {
        self * self
    }
    // The Stewart platform's equations have no sin or cos; first order is enough here.
    fn sin(self) -> Self {
        quick_two_sum(self.hi.sin(), self.lo * self.hi.cos())
    }
    fn cos(self) -> Self {
        quick_two_sum(self.hi.cos(), -self.lo * self.hi.sin())
    }
}

/// Whether the double-double `d` lies in the interval (exactly: `d.hi − bound` is exact when
/// the two are close, and its sign decides otherwise).
fn dd_in(d: Dd, i: &Interval) -> bool {
    (d.hi - i.lo) + d.lo >= 0.0 && (i.hi - d.hi) - d.lo >= 0.0
}

fn dd_in_box(v: &[Dd; 18], b: &[Interval; 18]) -> bool {
    (0..18).all(|i| dd_in(v[i], &b[i]))
}

/// max |a − b| over the coordinates, in double-double.
fn dd_dist(a: &[Dd; 18], b: &[Dd; 18]) -> f64 {
    (0..18)
        .map(|i| {
            let d = a[i] - b[i];
            (d.hi + d.lo).abs()
        })
        .fold(0.0, f64::max)
}

fn hi(v: &[Dd; 18]) -> [f64; 18] {
    v.map(|d| d.hi)
}

/// The root of F(·, x) near `guess` in double-double arithmetic: F evaluated by the generated
/// `residual_in` over [`Dd`], the corrections solved with B in f64 (iterative refinement), until
/// they fall below 1e-20 mm. `None` if they do not.
fn root_dd(s: &Stewart, guess: &[f64; 18], x: &[f64; 6]) -> Option<[Dd; 18]> {
    let xd = x.map(Dd::from);
    let mut v = guess.map(Dd::from);
    for _ in 0..200 {
        let mut f = [Dd::from(0.0); 18];
        s.residual_in(&v, &xd, &mut f);
        let mut b = [[0.0; 18]; 18];
        s.jacobian_dense(&hi(&v), x, &mut b);
        let mut d = f.map(|f| f.hi);
        Lu::new(b)?.solve(&mut d);
        let size = d.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        if !(size < 50.0) {
            return None;
        }
        for i in 0..18 {
            v[i] = v[i] - Dd::from(d[i]);
        }
        if size < 1e-20 {
            return Some(v);
        }
    }
    None
}

/// What the checks of close pairs saw, per decade of the distance between the two roots.
#[derive(Default)]
struct Tally {
    /// [decade (1e-k ≤ distance < 1e-k+1, k = 1..=9)] → (pairs, roots certified)
    decades: [(usize, usize); 10],
}

impl Tally {
    fn add(&mut self, distance: f64, certified: usize) {
        let k = (-distance.log10()).ceil().clamp(0.0, 9.0) as usize;
        self.decades[k].0 += 1;
        self.decades[k].1 += certified;
    }

    fn print(&self, what: &str) {
        for (k, (pairs, certified)) in self.decades.iter().enumerate() {
            if *pairs > 0 {
                println!(
                    "{what}: roots 1e-{k}..1e-{} mm apart: {pairs} pairs, {certified} of {} roots certified",
                    k.saturating_sub(1),
                    2 * pairs
                );
            }
        }
    }

    /// Pairs and certified roots with the roots closer than 10^-k mm.
    fn closer_than(&self, k: usize) -> (usize, usize) {
        self.decades[k + 1..]
            .iter()
            .fold((0, 0), |(p, c), (a, b)| (p + a, c + b))
    }
}

/// Two distinct roots `a`, `b` of F(·, x): each one's certificate must enclose it and must not
/// hold the other, and no step from one to the other may be certified. Returns how many of the
/// two were certified.
fn check_pair(s: &Stewart, x: &[f64; 6], a: &[Dd; 18], b: &[Dd; 18]) -> usize {
    let mut certified = 0;
    for (root, rival) in [(a, b), (b, a)] {
        // Whether or not the root itself is certified, no step may lead from it to the other.
        let (fa, fb) = (hi(root), hi(rival));
        assert!(certify_step(s, (&fa, x), (&fb, x)).is_err());
        assert!(!CertifiedSteps::new()
            .prove(s, (&fa, x), (&fb, x))
            .is_proven());
        let Ok(c) = certify(s, &fa, x) else {
            continue;
        };
        certified += 1;
        assert!(
            !dd_in_box(rival, &c.unique_in),
            "two roots {:.2e} mm apart in one certified box of radius {:.2e}",
            dd_dist(root, rival),
            c.radius
        );
        assert!(
            dd_in_box(root, &c.enclosure),
            "the enclosure (error bound {:.2e}) misses the root",
            c.error_bound
        );
    }
    certified
}

/// A root pair at segment parameter λ: `(λ, x, a, b)`.
type Pair = (f64, [f64; 6], [Dd; 18], [Dd; 18]);

/// Pairs of roots closing in on a fold of the straight joint segment from home along one leg,
/// each refined in double-double, and a λ past the fold (where the bisection found no pair).
fn fold_pairs(s: &Stewart, leg: usize) -> (Vec<Pair>, f64) {
    let start = home_start(s).unwrap();
    let mut target = *start.x();
    target[leg] += 200.0;
    let sol = arc_length(s, &start, &target, &Options::TIGHT).unwrap();
    let Status::Fold { .. } = sol.status else {
        return (Vec::new(), 1.0);
    };
    let x_at = |l: f64| -> [f64; 6] {
        std::array::from_fn(|j| start.x()[j] + l * (target[j] - start.x()[j]))
    };
    let l0 = sol.lambda - 1e-3;
    let x0 = x_at(l0);
    let first = arc_length(s, &start, &x0, &Options::TIGHT).unwrap();
    let Some(a) = root_dd(s, &first.v, &x0) else {
        return (Vec::new(), 1.0);
    };
    let guess: [f64; 18] = std::array::from_fn(|i| 2.0 * sol.v[i] - a[i].hi);
    let Some(b) = root_dd(s, &guess, &x0) else {
        return (Vec::new(), 1.0);
    };
    if dd_dist(&a, &b) < 1e-9 {
        return (Vec::new(), 1.0);
    }
    let mut pairs = vec![(l0, x0, a, b)];
    let (mut lo, mut hi_l) = (l0, (sol.lambda + 1e-2).min(1.0));
    for _ in 0..120 {
        let mid = 0.5 * (lo + hi_l);
        if mid <= lo || mid >= hi_l {
            break;
        }
        let x = x_at(mid);
        // The pair moves like √(λ_fold − λ) about its midpoint: λ_fold from the last two pairs.
        let (l1, _, a1, b1) = pairs[pairs.len() - 1];
        let factor = match pairs.len() {
            1 => 1.0,
            n => {
                let (l2, _, a2, b2) = pairs[n - 2];
                let (d1, d2) = (dd_dist(&a1, &b1).powi(2), dd_dist(&a2, &b2).powi(2));
                let fold = l1 + d1 * (l1 - l2) / (d2 - d1);
                ((fold - mid) / (fold - l1)).max(0.0).sqrt()
            }
        };
        let centre: [f64; 18] = std::array::from_fn(|i| 0.5 * (a1[i].hi + b1[i].hi));
        let half: [f64; 18] = std::array::from_fn(|i| 0.5 * ((a1[i] - b1[i]).hi));
        let ga: [f64; 18] = std::array::from_fn(|i| centre[i] + factor * half[i]);
        let gb: [f64; 18] = std::array::from_fn(|i| centre[i] - factor * half[i]);
        let found = root_dd(s, &ga, &x).zip(root_dd(s, &gb, &x));
        match found {
            // Two distinct roots, each the one its guess was for.
            Some((a, b))
                if dd_dist(&a, &b) > 1e-12
                    && max_diff(&hi(&a), &ga) < max_diff(&hi(&a), &gb)
                    && max_diff(&hi(&b), &gb) < max_diff(&hi(&b), &ga) =>
            {
                lo = mid;
                pairs.push((mid, x, a, b));
                if dd_dist(&a, &b) < 1e-8 {
                    break;
                }
            }
            _ => hi_l = mid,
        }
    }
    (pairs, hi_l)
}

/// Two roots 1 mm down to a few 1e-6 mm apart where a branch folds back, along three legs' segments:
/// no certified box holds both, every enclosure holds its root, no step between them is proven.
/// Past the fold, where the two have become complex, nothing near them is certified unless a
/// real root is found in the enclosure.
#[test]
fn roots_meeting_at_a_fold_never_share_a_certified_box() {
    let s = Stewart::new();
    let mut tally = Tally::default();
    let mut past = (0, 0);
    for leg in [0, 2, 4] {
        let (pairs, beyond_fold) = fold_pairs(&s, leg);
        for (_, x, a, b) in &pairs {
            let certified = check_pair(&s, x, a, b);
            tally.add(dd_dist(a, b), certified);
        }
        let Some((_, _, a, b)) = pairs.last() else {
            continue;
        };
        // Just past the fold, from the last pair's midpoint and from Newton's wandering there.
        let start = home_start(&s).unwrap();
        let mut target = *start.x();
        target[leg] += 200.0;
        for beyond in [0.0, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4] {
            let l = beyond_fold + beyond;
            let x: [f64; 6] =
                std::array::from_fn(|j| start.x()[j] + l * (target[j] - start.x()[j]));
            let mut v: [f64; 18] = std::array::from_fn(|i| 0.5 * (a[i].hi + b[i].hi));
            for _ in 0..6 {
                past.0 += 1;
                if let Ok(c) = certify(&s, &v, &x) {
                    // A claim of a root: double-double Newton must find one in the enclosure.
                    past.1 += 1;
                    let mid = c.enclosure.map(|i| i.mid());
                    let r = root_dd(&s, &mid, &x).expect("a certified root exists");
                    assert!(dd_in_box(&r, &c.enclosure));
                }
                let mut f = [0.0; 18];
                s.residual(&v, &x, &mut f);
                let mut bm = [[0.0; 18]; 18];
                s.jacobian_dense(&v, &x, &mut bm);
                let Some(lu) = Lu::new(bm) else { break };
                lu.solve(&mut f);
                for i in 0..18 {
                    v[i] -= f[i];
                }
            }
        }
    }
    tally.print("fold");
    println!(
        "past the fold: {} points tried, {} certified (each confirmed)",
        past.0, past.1
    );
    // The pairs come within 1e-5 mm (to a few 1e-6 mm). Closer than about 1e-4 mm double
    // precision proves neither root (measured: the Newton step's rounding, about u‖B⁻¹‖|F|,
    // outgrows the box whose curvature term |B⁻¹| F'' r² still fits), which is a refusal,
    // not a wrong answer.
    let (close, _) = tally.closer_than(5);
    assert!(close >= 3, "{close} pairs closer than 1e-5 mm");
    // Not vacuous: roots under 1e-3 mm apart are certified, with boxes small enough to leave
    // out the other root.
    let (near, certified) = tally.closer_than(3);
    assert!(
        near >= 3 && certified >= 6,
        "{certified} roots certified of {near} pairs closer than 1e-3 mm"
    );
}

/// With base and platform coplanar, every root has its mirror image through the base plane;
/// with the platform a distance z above the base, the two are 2z apart. For z from 0.1 mm
/// down to 1e-7 mm (pairs the double-double refinement separates) no certified box holds both.
#[test]
fn mirror_images_close_together_never_share_a_certified_box() {
    let s = Stewart::new();
    let mut tally = Tally::default();
    for z in [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7] {
        for k in 0..4 {
            let k = k as f64;
            // Small tilts keep every pivot near the base plane but not at one height.
            let tilt = 0.1 * z * k;
            let pose = Pose::from_euler(
                0.3 * k - 0.4,
                tilt / 100.0,
                -tilt / 150.0,
                [50.0 + 5.0 * k, -10.0 * k, z],
            );
            let v = linkage::unknowns_from_pose(&s, &pose);
            let Ok(x) = s.inverse(&v, &HOME_LEGS) else {
                continue;
            };
            let Some(a) = root_dd(&s, &v, &x) else {
                continue;
            };
            let b: [Dd; 18] = std::array::from_fn(|i| if i >= 12 { -a[i] } else { a[i] });
            // The mirror image is a root: F is even in the z coordinates.
            let again = root_dd(&s, &hi(&b), &x).unwrap();
            assert!(dd_dist(&again, &b) < 1e-18);
            let distance = dd_dist(&a, &b);
            if distance < 1e-12 {
                continue;
            }
            tally.add(distance, check_pair(&s, &x, &a, &b));
        }
    }
    tally.print("mirror");
    // Down to 2e-6 mm apart; as at a fold, only pairs from about 1e-4 mm apart on are
    // certified (see there), and those with boxes that leave the mirror image out.
    let (closest, _) = tally.closer_than(5);
    assert!(closest >= 1, "no pair closer than 1e-5 mm");
    let (close, certified) = tally.closer_than(3);
    assert!(
        close >= 8 && certified >= 4,
        "{close} pairs closer than 1e-3 mm, {certified} roots certified"
    );
}

/// Every real assembly mode at every Table V point (all-modes solver), certified one by one:
/// the box of uniqueness holds that root and no other real one, and the enclosure holds the
/// root to the solver's accuracy. NR's answer from home is checked the same way, and the true
/// pivots must lie in its enclosure.
#[test]
fn every_real_mode_at_table_v_points_gets_a_box_of_its_own() {
    let s = Stewart::new();
    let modes = AllModes::<_, 18, 6, 64>::new(s.clone(), &ModesOptions::default()).unwrap();
    let start = home_start(&s).unwrap();
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/data/table_v_points.csv"
    ))
    .unwrap();
    let mut roots = Box::new(Roots::<18, 64>::new());
    let (mut real, mut certified, mut incomplete) = (0, 0, 0);
    let mut nr = [(0, 0); 2];
    for line in text.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let near = fields[0] != "normal";
        let num = |k: usize| fields[k].parse::<f64>().unwrap();
        let x: [f64; 6] = std::array::from_fn(|j| num(1 + j));
        let truth: [f64; 18] = std::array::from_fn(|i| num(13 + i));
        modes.solve(&x, &mut roots).unwrap();
        if !roots.is_complete() {
            incomplete += 1;
            continue;
        }
        let all: Vec<[f64; 18]> = roots.real().iter().map(|r| r.v).collect();
        // Roots within 1e-7 mm of the box count as in it: the solver's roots are accurate to
        // about 1e-9.
        let held = |b: &[Interval; 18]| {
            all.iter()
                .filter(|v| (0..18).all(|i| b[i].lo - 1e-7 <= v[i] && v[i] <= b[i].hi + 1e-7))
                .count()
        };
        let off = |v: &[f64; 18], b: &[Interval; 18]| {
            (0..18)
                .map(|i| (b[i].lo - v[i]).max(v[i] - b[i].hi).max(0.0))
                .fold(0.0, f64::max)
        };
        for r in &all {
            real += 1;
            if let Ok(c) = certify(&s, r, &x) {
                certified += 1;
                assert_eq!(held(&c.unique_in), 1, "{x:?}: radius {:.3e}", c.radius);
                assert!(off(r, &c.enclosure) < 1e-8);
            }
        }
        if let Ok(sol) = linkage::newton_raphson(&s, &start, &x, &Options::TIGHT) {
            if sol.is_ok() {
                nr[near as usize].0 += 1;
                if let Ok(c) = certify(&s, &sol.v, &x) {
                    nr[near as usize].1 += 1;
                    assert_eq!(held(&c.unique_in), 1);
                    // The true pivots are rounded from the pose: near-singular points
                    // magnify that.
                    assert!(near || off(&truth, &c.enclosure) < 1e-8);
                }
            }
        }
    }
    println!(
        "Table V points: {real} real modes, {certified} certified ({incomplete} points where the modes solver was incomplete); NR's answers certified: normal {}/{}, near-singular {}/{}",
        nr[0].1, nr[0].0, nr[1].1, nr[1].0
    );
    assert!(incomplete <= 10, "{incomplete}");
    assert_eq!(nr[0].0, nr[0].1, "every normal point certified");
    assert!(certified * 10 >= real * 9, "{certified} of {real}");
}

/// Non-finite input, values so large that F overflows, and a point 50 mm off a root are never
/// certified; an approximation 1e-3 mm off a root is, with the root in its enclosure.
#[test]
fn bad_input_and_points_far_from_roots_are_not_certified() {
    use linkage::CertifyError;
    let s = Stewart::new();
    let start = home_start(&s).unwrap();
    let (v, x) = (*start.v(), *start.x());
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e200, 1e150] {
        let mut vb = v;
        vb[4] = bad;
        assert!(certify(&s, &vb, &x).is_err(), "v with {bad}");
        let mut xb = x;
        xb[2] = bad;
        assert!(certify(&s, &v, &xb).is_err(), "x with {bad}");
        assert!(certify_step(&s, (&v, &x), (&vb, &x)).is_err());
        assert!(certify_step(&s, (&v, &x), (&v, &xb)).is_err());
        assert!(!CertifiedSteps::new()
            .prove(&s, (&v, &x), (&vb, &x))
            .is_proven());
    }
    assert_eq!(
        certify(&s, &[f64::NAN; 18], &x),
        Err(CertifyError::NonFinite)
    );
    // Far from a root: the start's pivots moved 50 mm at the start's legs. 5 mm off, a
    // certificate would be a claim to check: the root must then lie in its enclosure.
    assert!(certify(&s, &v.map(|c| c + 50.0), &x).is_err());
    let root = root_dd(&s, &v, &x).unwrap();
    if let Ok(c) = certify(&s, &v.map(|c| c + 5.0), &x) {
        assert!(dd_in_box(&root, &c.enclosure));
    }
    // Near one: the enclosure holds the root (refined in double-double).
    let near = v.map(|c| c + 1e-3);
    let c = certify(&s, &near, &x).expect("1e-3 mm off a regular root");
    assert!(dd_in_box(&root, &c.enclosure));
    assert!(c.error_bound >= dd_dist(&root, &near.map(Dd::from)));
}

/// A step's certificate encloses the root at its end (refined in double-double) and bounds the
/// end point's distance to it — also when the end point given is off the root by 1e-9 to 1e-4
/// mm, where the bound must grow with it or the step be refused.
#[test]
fn a_step_encloses_the_root_at_its_end() {
    let s = Stewart::new();
    let (mut checked, mut refused) = (0, 0);
    for (k, sample) in linkage_tests::stewart_pose_samples(7, 20, 0.25, 30.0, 50)
        .iter()
        .enumerate()
    {
        let x0 = sample.x;
        // Legs moved by up to 0.15 mm: a step of a fast 1 kHz trajectory.
        let x1: [f64; 6] = std::array::from_fn(|j| x0[j] + 0.05 * (((j + k) % 7) as f64 - 3.0));
        let from = linkage::Start::new(&s, sample.v, x0).unwrap();
        let next = arc_length(&s, &from, &x1, &Options::TIGHT).unwrap();
        assert!(next.is_ok());
        let root = root_dd(&s, &next.v, &x1).unwrap();
        for off in [0.0, 1e-9, 1e-6, 1e-4] {
            let v1: [f64; 18] = std::array::from_fn(|i| next.v[i] + off * (i as f64 - 8.5) / 8.5);
            match certify_step(&s, (&sample.v, &x0), (&v1, &x1)) {
                Ok(c) => {
                    checked += 1;
                    assert!(dd_in_box(&root, &c.enclosure), "sample {k}, {off} off");
                    let d = dd_dist(&root, &v1.map(Dd::from));
                    assert!(c.error_bound >= d, "{} < {d}", c.error_bound);
                    // And it is tight: a few per cent above the true distance.
                    assert!(
                        c.error_bound < 1.2 * off + 1e-9,
                        "{} for {off}",
                        c.error_bound
                    );
                }
                Err(_) => refused += 1,
            }
        }
    }
    println!("{checked} step certificates checked, {refused} refused");
    assert!(checked >= 60, "{checked}");
}
