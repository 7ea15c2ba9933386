//! Sines and cosines of the inputs, evaluated once where the inputs stay fixed.

/// `[sin xⱼ, cos xⱼ]` for each input `j` that a mechanism's kernels turn by (a crank's angle),
/// zeros for the others: [`Mechanism::turns`](crate::mechanism::Mechanism::turns) evaluates them, and a
/// Newton run at fixed inputs passes them to every residual and factorisation
/// ([`Mechanism::residual_turned`](crate::mechanism::Mechanism::residual_turned),
/// [`Mechanism::factor_turned`](crate::mechanism::Mechanism::factor_turned)) instead of each evaluating
/// them again: in a rotary hexapod they were about 40 % of a Newton iteration.
///
/// Only `turns(x)` of the same mechanism at the same `x` is meaningful to pass on.
///
/// ```
/// # linkage::mechanism! {
/// #     pub struct FiveBar;
/// #     params { crank = 100.0 }
/// #     base { A1 = [-40.0, 0.0, 0.0], A1z = [-40.0, 0.0, 1.0], A2 = [40.0, 0.0, 0.0], A2z = [40.0, 0.0, 1.0] }
/// #     platform(home = [0.0, 0.0, 0.0, 0.0, crank * sin(pi / 3.0) + 120.0, 0.0]) { P = [0.0, 0.0, 0.0] }
/// #     link crank1 { C1 = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C1z = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
/// #     link crank2 { C2 = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C2z = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
/// #     link distal1 { }
/// #     link distal2 { }
/// #     chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - R(passive, axis = C1 -> C1z) - distal1 - S(P) - platform;
/// #     chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - R(passive, axis = C2 -> C2z) - distal2 - S(P) - platform;
/// # }
/// use linkage::Mechanism;
/// let five_bar = FiveBar::new();
/// let start = five_bar.home_start().unwrap();
/// let x = [0.1, -0.05];
/// let t = five_bar.turns(&x);
/// assert!((t.0[0][0] - 0.1f64.sin()).abs() < 1e-15 && (t.0[1][1] - 0.05f64.cos()).abs() < 1e-15);
/// // The same residual as the one that evaluates them itself, bit for bit.
/// let (mut f, mut g) = ([0.0; 3], [0.0; 3]);
/// five_bar.residual(start.v(), &x, &mut f);
/// five_bar.residual_turned(start.v(), &x, &t, &mut g);
/// assert_eq!(f, g);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Turns<const M: usize>(pub [[f64; 2]; M]);

impl<const M: usize> Turns<M> {
    /// No input turned: what a mechanism without angle inputs passes.
    pub const NONE: Self = Turns([[0.0; 2]; M]);
}
