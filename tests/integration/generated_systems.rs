//! The generated systems: Eq. 19 and Table A1 for the Stewart platform, snapshots for all.

use linkage::Mechanism;
use linkage_examples::{rps::Rps3, rss_hexapod::RssHexapod, stewart::Stewart};

#[test]
fn stewart_listing_snapshot() {
    insta::assert_snapshot!("stewart", Stewart::LISTING);
}

#[test]
fn rss_hexapod_listing_snapshot() {
    insta::assert_snapshot!("rss_hexapod", RssHexapod::LISTING);
}

#[test]
fn rps_listing_snapshot() {
    insta::assert_snapshot!("rps", Rps3::LISTING);
}

#[test]
fn stewart_is_eq_19_in_the_papers_order() {
    let names: Vec<String> = ["x", "y", "z"]
        .iter()
        .flat_map(|a| (1..=6).map(move |i| format!("{a}_G{i}")))
        .collect();
    assert_eq!(Stewart::UNKNOWNS.to_vec(), names);
    assert_eq!(Stewart::INPUTS, ["L1", "L2", "L3", "L4", "L5", "L6"]);
    for i in 1..=6 {
        assert_eq!(
            Stewart::EQUATIONS[i - 1],
            format!("(x_G{i} - x_D{i})^2 + (y_G{i} - y_D{i})^2 + (z_G{i} - z_D{i})^2 - L{i}^2")
        );
    }
    let rigid = [(2, 1), (4, 4), (6, 7)];
    for (k, (g, e)) in rigid.iter().enumerate() {
        for (a, axis) in ["x", "y", "z"].iter().enumerate() {
            assert_eq!(
                Stewart::EQUATIONS[6 + 3 * k + a],
                format!(
                    "E{e}*{axis}_G1 + E{}*{axis}_G3 + E{}*{axis}_G5 - {axis}_G{g}",
                    e + 1,
                    e + 2
                )
            );
        }
    }
    assert_eq!(
        Stewart::EQUATIONS[15],
        "(x_G1 - x_G3)^2 + (y_G1 - y_G3)^2 + (z_G1 - z_G3)^2 - E10^2"
    );
    assert_eq!(
        Stewart::EQUATIONS[16],
        "(x_G3 - x_G5)^2 + (y_G3 - y_G5)^2 + (z_G3 - z_G5)^2 - E11^2"
    );
    assert_eq!(
        Stewart::EQUATIONS[17],
        "(x_G5 - x_G1)^2 + (y_G5 - y_G1)^2 + (z_G5 - z_G1)^2 - E12^2"
    );
}

/// Table A1's nonzeros, 1-based (row, column), transcribed from the paper.
const TABLE_A1: [(usize, usize); 72] = [
    (1, 1),
    (1, 7),
    (1, 13),
    (2, 2),
    (2, 8),
    (2, 14),
    (3, 3),
    (3, 9),
    (3, 15),
    (4, 4),
    (4, 10),
    (4, 16),
    (5, 5),
    (5, 11),
    (5, 17),
    (6, 6),
    (6, 12),
    (6, 18),
    (7, 1),
    (7, 2),
    (7, 3),
    (7, 5),
    (8, 7),
    (8, 8),
    (8, 9),
    (8, 11),
    (9, 13),
    (9, 14),
    (9, 15),
    (9, 17),
    (10, 1),
    (10, 3),
    (10, 4),
    (10, 5),
    (11, 7),
    (11, 9),
    (11, 10),
    (11, 11),
    (12, 13),
    (12, 15),
    (12, 16),
    (12, 17),
    (13, 1),
    (13, 3),
    (13, 5),
    (13, 6),
    (14, 7),
    (14, 9),
    (14, 11),
    (14, 12),
    (15, 13),
    (15, 15),
    (15, 17),
    (15, 18),
    (16, 1),
    (16, 3),
    (16, 7),
    (16, 9),
    (16, 13),
    (16, 15),
    (17, 3),
    (17, 5),
    (17, 9),
    (17, 11),
    (17, 15),
    (17, 17),
    (18, 1),
    (18, 5),
    (18, 7),
    (18, 11),
    (18, 13),
    (18, 17),
];

#[test]
fn stewart_jacobian_has_table_a1_nonzeros() {
    assert_eq!(Stewart::NNZ, 72);
    let ours: Vec<(usize, usize)> = Stewart::PATTERN
        .iter()
        .map(|&(r, c)| (r + 1, c + 1))
        .collect();
    assert_eq!(ours, TABLE_A1.to_vec());
    let expr = |r: usize, c: usize| {
        let k = Stewart::PATTERN
            .iter()
            .position(|&p| p == (r - 1, c - 1))
            .unwrap();
        Stewart::JACOBIAN[k]
    };
    assert_eq!(expr(1, 1), "2*(x_G1 - x_D1)");
    assert_eq!(expr(7, 2), "-1");
    assert_eq!(expr(10, 5), "E6");
    assert_eq!(expr(16, 3), "2*(x_G3 - x_G1)");
    assert_eq!(expr(18, 17), "2*(z_G5 - z_G1)");
}

#[test]
fn stewart_constants_match_table_iv() {
    let s = Stewart::new();
    let names = Stewart::CONSTANT_NAMES;
    let get = |n: &str| s.constants()[names.iter().position(|m| *m == n).unwrap()];
    let table_iv = [
        0.3333, 0.9107, -0.2440, -0.2440, 0.3333, 0.9107, 0.9107, -0.2440, 0.3333,
    ];
    for (j, want) in table_iv.iter().enumerate() {
        let e = get(&format!("E{}", j + 1));
        assert!((e - want).abs() < 5e-5, "E{} = {e}, Table IV {want}", j + 1);
    }
    // E10..E12: the triangle G1'G3'G5' has sides 100·√3 (ERRATA.md: Table IV prints 207.846).
    for j in 10..=12 {
        assert!((get(&format!("E{j}")) - 173.205).abs() < 2e-3);
    }
}

#[test]
fn geometry_can_change_at_run_time() {
    let mut s = Stewart::new();
    let before = *s.constants();
    s.set_pivot("platform", "G2", [60.0, 5.0, 0.0]).unwrap();
    assert_ne!(before, *s.constants(), "the E_j must be recomputed");
    let names = Stewart::CONSTANT_NAMES;
    let e1 = s.constants()[names.iter().position(|m| *m == "E1").unwrap()];
    assert!((e1 - 0.3333).abs() > 1e-3);
    // An off-plane pivot cannot be expressed in the coplanar form: typed error, state kept.
    let kept = s.clone();
    assert_eq!(
        s.set_pivot("platform", "G2", [60.0, 5.0, 3.0]),
        Err(linkage::GeometryError::NotCoplanar)
    );
    assert_eq!(s, kept);
    assert_eq!(
        s.set_geometry("base.D1.x", f64::NAN),
        Err(linkage::GeometryError::NonFinite { name: "base.D1.x" })
    );
    assert_eq!(
        s.set_geometry("nope", 1.0),
        Err(linkage::GeometryError::UnknownName)
    );
    // Collinear frame.
    let mut t = Stewart::new();
    assert_eq!(
        t.set_pivot("platform", "G3", [38.823, 144.889, 0.0]).err(),
        Some(linkage::GeometryError::CollinearFrame)
    );
}

#[test]
fn every_equation_is_at_most_quadratic_in_the_unknowns() {
    // Checked by the generator; here numerically: third differences along random directions vanish.
    fn check<S: Mechanism<N, M>, const N: usize, const M: usize>(
        sys: &S,
        v: &[f64; N],
        x: &[f64; M],
    ) {
        let mut rng = linkage_tests::Rng::new(7);
        let d: [f64; N] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
        let at = |t: f64| {
            let w: [f64; N] = std::array::from_fn(|i| v[i] + t * d[i]);
            let mut f = [0.0; N];
            sys.residual(&w, x, &mut f);
            f
        };
        let (f0, f1, f2, f3) = (at(0.0), at(1.0), at(2.0), at(3.0));
        for r in 0..N {
            let third = f3[r] - 3.0 * f2[r] + 3.0 * f1[r] - f0[r];
            assert!(
                third.abs() < 1e-6 * (1.0 + f0[r].abs()),
                "{} row {r}: cubic term {third}",
                S::NAME
            );
        }
    }
    let s = Stewart::new();
    let st = linkage_examples::stewart::home_start(&s).unwrap();
    check(&s, st.v(), st.x());
    let h = RssHexapod::new();
    let hs = linkage_examples::rss_hexapod::home_start(&h).unwrap();
    check(&h, hs.v(), hs.x());
    let r = Rps3::new();
    let rs = linkage_examples::rps::home_start(&r).unwrap();
    check(&r, rs.v(), rs.x());
}
