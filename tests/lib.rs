//! Shared helpers for the integration tests: a seeded sampler and generic checks that every
//! generated mechanism must pass.

use linkage::Mechanism;

pub mod dense;
pub mod exact_root;
pub mod invariants;
pub mod vec3;

pub use linkage_examples::case_study::sampling::Rng;

/// Checks ∂F/∂v (sparse and dense) and ∂F/∂x against central finite differences at (v, x),
/// and that the sparsity pattern holds every nonzero. Panics with the offending entry.
pub fn check_jacobians<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) {
    let mut values = vec![0.0; S::NNZ];
    sys.jacobian(v, x, &mut values);
    assert_eq!(S::PATTERN.len(), S::NNZ);
    let mut sparse = [[0.0; N]; N];
    for (k, &(r, c)) in S::PATTERN.iter().enumerate() {
        sparse[r][c] = values[k];
    }
    let mut dense = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut dense);
    let mut a = [[0.0; M]; N];
    sys.input_jacobian(v, x, &mut a);
    let mut fp = [0.0; N];
    let mut fm = [0.0; N];
    for c in 0..N {
        let h = 1e-5 * v[c].abs().max(1.0);
        let (mut vp, mut vm) = (*v, *v);
        vp[c] += h;
        vm[c] -= h;
        sys.residual(&vp, x, &mut fp);
        sys.residual(&vm, x, &mut fm);
        for r in 0..N {
            let fd = (fp[r] - fm[r]) / (2.0 * h);
            let tol = 1e-6 * (1.0 + fd.abs());
            assert!(
                (fd - sparse[r][c]).abs() <= tol,
                "{}: dF{r}/dv{c} = {} (sparse) vs {fd} (finite differences)",
                S::NAME,
                sparse[r][c]
            );
            assert_eq!(
                dense[r][c],
                sparse[r][c],
                "{}: dense and sparse differ at ({r}, {c})",
                S::NAME
            );
        }
    }
    // The kernels of a run at fixed inputs read the inputs' sines and cosines from `turns`:
    // the same F and the same factorisation as evaluated afresh, bit for bit (the generic
    // kernels evaluate them through `Scalar`, without `turns`).
    let t = sys.turns(x);
    let (mut plain, mut turned, mut generic) = ([0.0; N], [0.0; N], [0.0; N]);
    sys.residual(v, x, &mut plain);
    sys.residual_turned(v, x, &t, &mut turned);
    sys.residual_in(v, x, &mut generic);
    assert_eq!(plain, turned, "{}: residual_turned", S::NAME);
    assert_eq!(plain, generic, "{}: residual_in", S::NAME);
    let mut generic_values = vec![f64::NAN; S::NNZ];
    sys.jacobian_in(v, x, &mut generic_values);
    assert_eq!(values, generic_values, "{}: jacobian_in", S::NAME);
    let (mut f1, mut f2) = (sys.new_factor(), sys.new_factor());
    let (a1, a2) = (
        sys.factor(v, x, &mut f1),
        sys.factor_turned(v, x, &t, &mut f2),
    );
    assert_eq!(a1, a2, "{}: factor_turned", S::NAME);
    let (mut y1, mut y2) = (plain, plain);
    sys.solve(&f1, &mut y1);
    sys.solve(&f2, &mut y2);
    assert!(
        a1.is_none() || y1 == y2,
        "{}: solve after factor_turned",
        S::NAME
    );
    let dx: [f64; M] = std::array::from_fn(|j| 0.25 - 0.5 * j as f64);
    let (mut d1, mut d2) = ([0.0; N], [f64::NAN; N]);
    sys.input_derivative(v, x, &dx, &mut d1);
    sys.input_derivative_turned(v, x, &t, &dx, &mut d2);
    assert_eq!(d1, d2, "{}: input_derivative_turned", S::NAME);
    if !S::TURNS {
        assert_eq!(t, linkage::Turns::NONE, "{}", S::NAME);
    }
    // Where the generator says ∂F/∂v does not mention the inputs, B is the same at other
    // inputs, bit for bit (Newton–Raphson reuses its factorisation at the start on that word).
    if !S::JACOBIAN_USES_INPUTS {
        let other: [f64; M] = std::array::from_fn(|j| 1.5 * x[j] + 0.25 + j as f64);
        let mut at_other = vec![f64::NAN; S::NNZ];
        sys.jacobian(v, &other, &mut at_other);
        assert_eq!(values, at_other, "{}: B changed with the inputs", S::NAME);
    }
    for j in 0..M {
        let h = 1e-6 * x[j].abs().max(1.0);
        let (mut xp, mut xm) = (*x, *x);
        xp[j] += h;
        xm[j] -= h;
        sys.residual(v, &xp, &mut fp);
        sys.residual(v, &xm, &mut fm);
        for r in 0..N {
            let fd = (fp[r] - fm[r]) / (2.0 * h);
            let tol = 1e-5 * (1.0 + fd.abs());
            assert!(
                (fd - a[r][j]).abs() <= tol,
                "{}: dF{r}/dx{j} = {} vs {fd} (finite differences)",
                S::NAME,
                a[r][j]
            );
        }
    }
    // The generated (∂F/∂x) dx: the same products and sums as ∂F/∂x multiplied out.
    let dx: [f64; M] = std::array::from_fn(|j| 0.5 + j as f64 * 0.25 - (j % 2) as f64);
    let mut along = [f64::NAN; N];
    sys.input_derivative(v, x, &dx, &mut along);
    for r in 0..N {
        let product: f64 = (0..M).map(|j| a[r][j] * dx[j]).sum();
        assert!(
            along[r] == product,
            "{}: ((∂F/∂x) dx)[{r}] = {} vs {product} from ∂F/∂x",
            S::NAME,
            along[r]
        );
    }
}

/// How many cases a sweep runs: `quick` on a plain `cargo test`, `full` when `LINKAGE_STRESS`
/// is set (to any k ≥ 1; `.ci/run` sets it). Sweeps number their cases 0, 1, …, so the quick
/// sample is the full sweep's first cases: every check runs on both, the full sweep on more
/// random machines.
pub fn sweep(quick: usize, full: usize) -> usize {
    match std::env::var("LINKAGE_STRESS") {
        Ok(_) => full,
        Err(_) => quick,
    }
}

/// A sweep's seed: `seed`, or where `LINKAGE_STRESS_SEED` is set to a number `s`, `seed ^ s`:
/// other random cases for a hunt, the default ones replayed without it.
pub fn sweep_seed(seed: u64) -> u64 {
    env_number("LINKAGE_STRESS_SEED").map_or(seed, |s| seed ^ s)
}

/// The whole number in the environment variable `name`, if it is set; a panic naming it if it
/// is set to anything else (a mistyped seed must not run the default cases unnoticed).
pub fn env_number(name: &str) -> Option<u64> {
    let text = std::env::var(name).ok()?;
    match text.trim().parse() {
        Ok(n) => Some(n),
        Err(_) => panic!("{name}={text:?} is not a whole number"),
    }
}

/// Runs `f` on a thread with a stack of `mib` MiB and passes on its panic: an all-modes solver
/// of capacity 256 to 1024 is hundreds of kB to a few MB, moved by value, more than a test
/// thread's stack.
pub fn on_big_stack(mib: usize, f: impl FnOnce() + Send + 'static) {
    let joined = std::thread::Builder::new()
        .stack_size(mib << 20)
        .spawn(f)
        .expect("a thread with a big stack")
        .join();
    if let Err(panic) = joined {
        std::panic::resume_unwind(panic);
    }
}

/// Largest coordinate difference.
pub fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).abs())
        .fold(0.0, f64::max)
}

/// ‖F(v, x)‖∞.
pub fn residual_norm<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> f64 {
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    f.iter().fold(0.0, |m, r| m.max(r.abs()))
}

pub use linkage::reference::straight_segment as straight_path_truth;

/// A Stewart pose reached from home by a straight path in pose space along which det B keeps
/// the start's sign (checked at `checks` points): the ground truth v and its leg lengths.
pub struct PoseSample {
    pub pose: linkage::Pose,
    pub x: [f64; 6],
    pub v: [f64; 18],
}

pub fn stewart_pose_samples(
    seed: u64,
    count: usize,
    rot: f64,
    trans: f64,
    checks: usize,
) -> Vec<PoseSample> {
    use linkage_examples::stewart::{home_start, legs_for_pose, Stewart};
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let home = linkage::pose_from_unknowns(&s, st.v()).unwrap();
    let [hy, hp, hr] = home.euler();
    let ht = home.translation;
    let mut rng = Rng::new(seed);
    let mut out = Vec::new();
    while out.len() < count {
        let u: [f64; 6] = std::array::from_fn(|i| {
            if i < 3 {
                rng.uniform(-rot, rot)
            } else {
                rng.uniform(-trans, trans)
            }
        });
        let at = |t: f64| {
            linkage::Pose::from_euler(
                hy + t * u[0],
                hp + t * u[1],
                hr + t * u[2],
                [ht[0] + t * u[3], ht[1] + t * u[4], ht[2] + t * u[5]],
            )
        };
        let valid = (0..=checks).all(|k| {
            let p = at(k as f64 / checks as f64);
            legs_for_pose(&s, &p).is_some_and(|(x, v)| {
                x.iter().all(|l| *l > 20.0) && linkage::det_b(&s, &v, &x) * st.det() > 0.0
            })
        });
        if valid {
            let pose = at(1.0);
            let (x, v) = legs_for_pose(&s, &pose).unwrap();
            out.push(PoseSample { pose, x, v });
        }
    }
    out
}

/// The generated factorisation of B against dense LU with partial pivoting, at any
/// conditioning: the generated solve is backward stable (‖B y − b‖∞ ≤ 1e-12 (‖B‖∞ ‖y‖∞ +
/// ‖b‖∞)) and its determinant agrees with dense LU's to what the condition number κ∞(B) allows
/// (relative difference ≤ 1e-12 κ∞), with the same sign wherever that bound is below ½. Where
/// dense LU finds B exactly singular nothing is asserted. Returns the factor storage, or
/// `None` when B was singular to dense LU.
pub fn check_factorization<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Option<S::Factor> {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    let dense = b;
    let lu = linkage::lu::Lu::new(b)?;
    let inf_norm = |m: &[[f64; N]; N]| {
        m.iter()
            .map(|row| row.iter().map(|a| a.abs()).sum::<f64>())
            .fold(0.0, f64::max)
    };
    let mut inverse = [[0.0; N]; N];
    for j in 0..N {
        let mut e = [0.0; N];
        e[j] = 1.0;
        lu.solve(&mut e);
        for i in 0..N {
            inverse[i][j] = e[i];
        }
    }
    let kappa = inf_norm(&dense) * inf_norm(&inverse);
    let bound = 1e-12 * kappa;
    let mut fac = sys.new_factor();
    let Some(info) = sys.factor(v, x, &mut fac) else {
        // Singular to rounding, found by other pivots: as much an answer as dense LU's.
        assert!(
            bound >= 0.5,
            "{}: the generated factorisation calls B singular where dense LU does not (κ∞ {kappa:e})",
            S::NAME
        );
        return None;
    };
    assert!(
        (info.det - lu.det()).abs() <= bound.max(1e-12) * lu.det().abs(),
        "{}: det {:e} vs {:e} (κ∞ {kappa:e})",
        S::NAME,
        info.det,
        lu.det()
    );
    if bound < 0.5 {
        assert_eq!(
            info.det.signum(),
            lu.det().signum(),
            "{}: det sign (κ∞ {kappa:e})",
            S::NAME
        );
    }
    assert!(
        info.pivot_ratio > 0.0 && info.pivot_ratio <= 1.0,
        "{}: pivot ratio {}",
        S::NAME,
        info.pivot_ratio
    );
    let rhs: [f64; N] = std::array::from_fn(|i| (i as f64 * 0.7).sin() * 100.0);
    let mut y = rhs;
    sys.solve(&fac, &mut y);
    let norm = |a: &[f64; N]| a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let scale = inf_norm(&dense) * norm(&y) + norm(&rhs);
    for r in 0..N {
        let back: f64 = (0..N).map(|c| dense[r][c] * y[c]).sum();
        assert!(
            (back - rhs[r]).abs() <= 1e-12 * scale,
            "{}: row {r}: {back} vs {} (κ∞ {kappa:e})",
            S::NAME,
            rhs[r]
        );
    }
    Some(fac)
}

/// Unknowns at which B is ever closer to singular: [`toward_zero`] of det B.
pub fn toward_singular<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    d: &[f64; N],
    x: &[f64; M],
    steps: usize,
) -> Vec<[f64; N]> {
    toward_zero(&|v| linkage::det_b(sys, v, x), v, d, steps)
}

/// Points ever closer to a zero of `f` along `v + t d`, t ∈ [0, 1]: the first change of sign
/// (checked at 64 steps), then `steps` bisections of it; every midpoint. Empty if `f` keeps its
/// sign.
pub fn toward_zero<const N: usize>(
    f: &dyn Fn(&[f64; N]) -> f64,
    v: &[f64; N],
    d: &[f64; N],
    steps: usize,
) -> Vec<[f64; N]> {
    let at = |t: f64| -> [f64; N] { std::array::from_fn(|i| v[i] + t * d[i]) };
    let first = f(&at(0.0));
    let Some(end) = (1..=64)
        .map(|k| k as f64 / 64.0)
        .find(|&t| f(&at(t)) * first <= 0.0)
    else {
        return Vec::new();
    };
    let (mut lo, mut hi) = (end - 1.0 / 64.0, end);
    let mut out = Vec::new();
    for _ in 0..steps {
        let mid = 0.5 * (lo + hi);
        out.push(at(mid));
        if f(&at(mid)) * first > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    out
}

/// [`check_factorization`] where one entry of B after another vanishes while B stays regular,
/// along the line `v + t d` at inputs `x`: a pivot fixed at generation time may be one of them,
/// and then its multipliers grow without bound unless the fallback takes over. `(fixed,
/// fallback)` as [`near_singularities`].
pub fn vanishing_entries<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    d: &[f64; N],
    x: &[f64; M],
) -> (usize, usize)
where
    S::Factor: std::ops::Index<usize, Output = f64>,
{
    let (mut fixed, mut fallback) = (0, 0);
    for k in 0..S::NNZ {
        let entry = |v: &[f64; N]| {
            let mut values = vec![0.0; S::NNZ];
            sys.jacobian(v, x, &mut values);
            values[k]
        };
        for v in toward_zero(&entry, v, d, 40) {
            match check_factorization(sys, &v, x) {
                Some(f) if f[0] == 0.0 => fixed += 1,
                Some(_) => fallback += 1,
                None => {}
            }
        }
    }
    (fixed, fallback)
}

/// [`check_factorization`] on a line from `start` (unknowns moved by up to `by` along
/// `dv[..N]`, inputs by up to `dx` along `dv[32 − M..]`) toward a singularity of B, at ever
/// closer points; `(fixed, fallback)`: how many took the pivot order fixed at generation time
/// and how many the partial-pivoting fallback.
pub fn near_singularities<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &linkage::Start<N, M>,
    dv: &[f64; 32],
    by: f64,
    dx: f64,
) -> (usize, usize)
where
    S::Factor: std::ops::Index<usize, Output = f64>,
{
    let d: [f64; N] = std::array::from_fn(|i| by * dv[i]);
    let x: [f64; M] = std::array::from_fn(|j| start.x()[j] + dx * dv[31 - j]);
    let (mut fixed, mut fallback) = (0, 0);
    for v in toward_singular(sys, start.v(), &d, &x, 48) {
        // Entry 0 of the generated storage says which factors are valid (0: the fixed order).
        match check_factorization(sys, &v, &x) {
            Some(f) if f[0] == 0.0 => fixed += 1,
            Some(_) => fallback += 1,
            None => {}
        }
    }
    (fixed, fallback)
}

/// A smooth 2 s manoeuvre of the Table III platform around home (heave, sway and a wobble),
/// clear of singularities and periodic: sampled at 1 kHz it can be replayed in a loop.
pub fn manoeuvre(t: f64) -> linkage::Pose {
    let w = std::f64::consts::PI;
    linkage::Pose::from_euler(
        0.15 * (w * t).sin(),
        0.1 * (2.0 * w * t).sin(),
        -0.08 * (w * t).sin(),
        [
            58.971 + 15.0 * (w * t).sin(),
            -11.739 + 10.0 * (1.0 - (w * t).cos()),
            159.011 + 20.0 * (w * t).sin(),
        ],
    )
}
