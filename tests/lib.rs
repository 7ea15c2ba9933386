//! Shared helpers for the integration tests: a seeded sampler and generic checks that every
//! generated mechanism must pass.

use linkage::Mechanism;

pub mod dense;
pub mod invariants;

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

pub use linkage_examples::case_study::straight_segment as straight_path_truth;

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
    let home = linkage::pose_from_unknowns(&s, &st.v).unwrap();
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
                x.iter().all(|l| *l > 20.0) && linkage::det_b(&s, &v, &x) * st.det > 0.0
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

/// The generated factorisation of B against dense LU: same determinant, same solution.
pub fn check_factorization<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) {
    let mut fac = sys.new_factor();
    let info = sys.factor(v, x, &mut fac).expect("nonsingular");
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    let dense = b;
    let piv = linkage::lu::factor::<N, _>(&mut b).expect("nonsingular");
    assert!(
        (info.det - piv.det).abs() <= 1e-9 * piv.det.abs(),
        "{}: det {} vs {}",
        S::NAME,
        info.det,
        piv.det
    );
    let rhs: [f64; N] = std::array::from_fn(|i| (i as f64 * 0.7).sin() * 100.0);
    let mut y = rhs;
    sys.solve(&fac, &mut y);
    for r in 0..N {
        let back: f64 = (0..N).map(|c| dense[r][c] * y[c]).sum();
        assert!(
            (back - rhs[r]).abs() <= 1e-9 * (1.0 + rhs[r].abs()),
            "{}: row {r}: {back} vs {}",
            S::NAME,
            rhs[r]
        );
    }
}
