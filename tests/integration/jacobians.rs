//! Every generated Jacobian (∂F/∂v sparse and dense, ∂F/∂x) against finite differences, and
//! every generated factorisation of ∂F/∂v against dense LU.

use linkage::Mechanism;
use linkage_examples::{rps, rss_hexapod, stewart};
use linkage_tests::{check_factorization, check_jacobians, Rng};

fn perturbed<const K: usize>(rng: &mut Rng, a: &[f64; K], by: f64) -> [f64; K] {
    std::array::from_fn(|i| a[i] + rng.uniform(-by, by))
}

fn check_around<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    dx: f64,
) {
    let mut rng = Rng::new(42);
    check_jacobians(sys, v, x);
    check_factorization(sys, v, x);
    for _ in 0..20 {
        let (v, x) = (perturbed(&mut rng, v, 30.0), perturbed(&mut rng, x, dx));
        check_jacobians(sys, &v, &x);
        check_factorization(sys, &v, &x);
    }
}

#[test]
fn stewart_jacobians_match_finite_differences() {
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    check_around(&s, st.v(), st.x(), 20.0);
}

#[test]
fn rss_hexapod_jacobians_match_finite_differences() {
    let s = rss_hexapod::RssHexapod::new();
    let st = rss_hexapod::home_start(&s).unwrap();
    check_around(&s, st.v(), st.x(), 1.0);
}

#[test]
fn rps_jacobians_match_finite_differences() {
    let s = rps::Rps3::new();
    let st = rps::home_start(&s).unwrap();
    check_around(&s, st.v(), st.x(), 20.0);
}
