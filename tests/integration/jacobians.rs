//! Every generated Jacobian (∂F/∂v sparse and dense, ∂F/∂x) against finite differences, and
//! every generated factorisation of ∂F/∂v against dense LU.

use linkage::Mechanism;
use linkage_examples::{rps, rss_hexapod, stewart};
use linkage_tests::{
    check_factorization, check_jacobians, near_singularities, vanishing_entries, Rng,
};

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

/// Near a singularity of B the pivot order fixed at generation time meets large multipliers
/// and hands over to partial pivoting; both must then agree with dense LU (backward-stable
/// solves, determinants as exact as the conditioning allows). Both paths are exercised.
#[test]
fn fixed_pivot_order_and_its_fallback_both_hold_near_singularities() {
    let mut rng = Rng::new(7);
    let mut direction = || -> [f64; 32] { std::array::from_fn(|_| rng.symmetric()) };
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    let g = stewart::StewartGeneral::new();
    let gs = g.home_start().unwrap();
    let r = rps::Rps3::new();
    let rs = rps::home_start(&r).unwrap();
    let h = rss_hexapod::RssHexapod::new();
    let hs = rss_hexapod::home_start(&h).unwrap();
    let mut total = [(0, 0); 4];
    for _ in 0..25 {
        let add = |t: &mut (usize, usize), c: (usize, usize)| {
            t.0 += c.0;
            t.1 += c.1;
        };
        add(
            &mut total[0],
            near_singularities(&s, &st, &direction(), 120.0, 1.0),
        );
        add(
            &mut total[1],
            near_singularities(&g, &gs, &direction(), 120.0, 1.0),
        );
        add(
            &mut total[2],
            near_singularities(&r, &rs, &direction(), 60.0, 1.0),
        );
        add(
            &mut total[3],
            near_singularities(&h, &hs, &direction(), 150.0, 0.5),
        );
    }
    for (name, (fixed, fallback)) in ["stewart", "stewart general", "rps", "rss hexapod"]
        .iter()
        .zip(total)
    {
        assert!(fixed > 0, "{name}: the fixed order was never used");
        assert!(
            fallback > 0,
            "{name}: the fallback was never taken ({fixed} fixed)"
        );
    }
}

/// Where an entry of B vanishes the pivot order fixed at generation time may meet a zero pivot
/// although B is regular; the multiplier check must hand over to partial pivoting before the
/// factors grow (the backward-error check in `check_factorization` sees growth).
#[test]
fn a_vanishing_fixed_pivot_hands_over_to_partial_pivoting() {
    let mut rng = Rng::new(11);
    let mut direction = |by: f64| -> [f64; 18] { std::array::from_fn(|_| by * rng.symmetric()) };
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    let g = stewart::StewartGeneral::new();
    let gs = g.home_start().unwrap();
    let h = rss_hexapod::RssHexapod::new();
    let hs = rss_hexapod::home_start(&h).unwrap();
    let r = rps::Rps3::new();
    let rs = rps::home_start(&r).unwrap();
    let mut total = [(0, 0); 4];
    for _ in 0..4 {
        let add = |t: &mut (usize, usize), c: (usize, usize)| {
            t.0 += c.0;
            t.1 += c.1;
        };
        add(
            &mut total[0],
            vanishing_entries(&s, st.v(), &direction(300.0), st.x()),
        );
        add(
            &mut total[1],
            vanishing_entries(&g, gs.v(), &direction(300.0), gs.x()),
        );
        add(
            &mut total[2],
            vanishing_entries(&h, hs.v(), &direction(300.0), hs.x()),
        );
        let d: [f64; 9] = std::array::from_fn(|i| direction(200.0)[i]);
        add(&mut total[3], vanishing_entries(&r, rs.v(), &d, rs.x()));
    }
    for (name, (fixed, fallback)) in ["stewart", "stewart general", "rss hexapod", "rps"]
        .iter()
        .zip(total)
    {
        assert!(
            fallback > 0,
            "{name}: the fallback was never taken ({fixed} fixed)"
        );
    }
}

/// A non-finite B is never factored: `factor` returns `None` for NaN or infinite entries,
/// whichever path (fixed pivot order or fallback) they reach.
fn non_finite_is_refused<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) {
    for i in 0..N {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut w = *v;
            w[i] = bad;
            let mut b = [[0.0; N]; N];
            sys.jacobian_dense(&w, x, &mut b);
            if b.iter().flatten().all(|e| e.is_finite()) {
                continue;
            }
            let mut fac = sys.new_factor();
            assert!(
                sys.factor(&w, x, &mut fac).is_none(),
                "{}: B with v[{i}] = {bad} was factored",
                S::NAME
            );
        }
    }
}

#[test]
fn non_finite_jacobians_are_never_factored() {
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    non_finite_is_refused(&s, st.v(), st.x());
    let g = stewart::StewartGeneral::new();
    let gs = g.home_start().unwrap();
    non_finite_is_refused(&g, gs.v(), gs.x());
    let h = rss_hexapod::RssHexapod::new();
    let hs = rss_hexapod::home_start(&h).unwrap();
    non_finite_is_refused(&h, hs.v(), hs.x());
    let r = rps::Rps3::new();
    let rs = rps::home_start(&r).unwrap();
    non_finite_is_refused(&r, rs.v(), rs.x());
}
