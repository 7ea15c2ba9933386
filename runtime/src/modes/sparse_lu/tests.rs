//! The plan and the factorisation on small systems written out by hand.

use super::plan::compact;
use super::*;

#[test]
fn compact_lists_the_kept_indices_in_order() {
    let mut out = [0u8; 6];
    assert_eq!(compact(&mut out, |i| i % 2 == 1), 3);
    assert_eq!(head(&out, 3), &[1, 3, 5]);
    assert_eq!(compact(&mut out, |i| i == 0 || i == 4), 2);
    assert_eq!(head(&out, 2), &[0, 4]);
    assert_eq!(compact(&mut out, |_| true), 6);
    assert_eq!(out, [0, 1, 2, 3, 4, 5]);
    assert_eq!(compact(&mut out, |_| false), 0);
}

#[test]
fn an_inconsistent_plan_fails_instead_of_panicking() {
    // Two constant diagonal entries: two static pivots, no dense remainder.
    let pattern = [(0, 0), (1, 1)];
    let v = [2.0, 4.0];
    let mut plan = Plan::<2>::new(&pattern, &v, &v).unwrap();
    assert_eq!(plan.shape(), (2, 0));
    let values = [Complex::real(2.0), Complex::real(4.0)];
    let mut lu = Lu::<2>::new();
    assert!(lu.factor(&plan, &values, None));
    let mut b = [Complex::ONE; 2];
    lu.solve(&plan, &mut b);
    assert_eq!(b, [Complex::real(0.5), Complex::real(0.25)]);
    // A pivot past the matrix (which `Plan::new` never makes): a failed factorisation and
    // a NaN solution, not an index out of bounds.
    plan.pivot[1] = (7, 1);
    assert!(!lu.factor(&plan, &values, None));
    let mut b = [Complex::ONE; 2];
    lu.solve(&plan, &mut b);
    assert!(b.iter().all(|x| !x.is_finite()), "{b:?}");
}

#[test]
fn static_and_dense_pivots_solve_a_sparse_system() {
    // Rows 0 and 1 are "linear" with constant −1 on columns 2 and 3; rows 2, 3 vary.
    let pattern = [
        (0, 0),
        (0, 2),
        (1, 1),
        (1, 3),
        (2, 0),
        (2, 2),
        (3, 1),
        (3, 3),
        (3, 0),
    ];
    let a = [0.5, -1.0, 0.3, -1.0, 1.0, 2.0, 3.0, 1.0, 0.7];
    let b = [0.5, -1.0, 0.3, -1.0, 4.0, -2.0, 1.5, 2.5, 0.1];
    let plan = Plan::<4>::new(&pattern, &a, &b).unwrap();
    assert_eq!(plan.shape(), (2, 2));
    let vals = [
        Complex::real(0.5),
        Complex::real(-1.0),
        Complex::real(0.3),
        Complex::real(-1.0),
        Complex::new(1.0, 2.0),
        Complex::new(-3.0, 0.5),
        Complex::new(0.2, 0.1),
        Complex::new(2.0, -1.0),
        Complex::new(0.0, 1.0),
    ];
    let mut lu = Lu::<4>::new();
    assert!(lu.factor(&plan, &vals, None));
    let x = [
        Complex::new(1.0, 1.0),
        Complex::new(-2.0, 0.5),
        Complex::new(0.25, 0.0),
        Complex::new(0.0, -3.0),
    ];
    let mut rhs = [Complex::ZERO; 4];
    for (&(r, c), &v) in pattern.iter().zip(&vals) {
        rhs[r] += v * x[c];
    }
    lu.solve(&plan, &mut rhs);
    for i in 0..4 {
        assert!((rhs[i] - x[i]).abs() < 1e-13, "{i}: {:?}", rhs[i]);
    }
    // Bordered: [[B, col], [row, −1]] [x; σ] = [b; 0] with σ = row · x.
    let border = Border {
        col: [
            Complex::new(0.5, 1.0),
            Complex::real(-2.0),
            Complex::new(0.0, 3.0),
            Complex::ONE,
        ],
        row: [
            Complex::new(1.0, -1.0),
            Complex::real(0.25),
            Complex::new(0.3, 0.3),
            Complex::real(-0.7),
        ],
        corner: Complex::real(-1.0),
    };
    assert!(lu.factor(&plan, &vals, Some(&border)));
    let sigma = (0..4).fold(Complex::ZERO, |s, j| s + border.row[j] * x[j]);
    let mut rhs = [Complex::ZERO; 4];
    for (&(r, c), &v) in pattern.iter().zip(&vals) {
        rhs[r] += v * x[c];
    }
    for i in 0..4 {
        rhs[i] += border.col[i] * sigma;
    }
    lu.solve(&plan, &mut rhs);
    for i in 0..4 {
        assert!((rhs[i] - x[i]).abs() < 1e-13, "bordered {i}: {:?}", rhs[i]);
    }
}
