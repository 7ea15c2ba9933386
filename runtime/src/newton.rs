//! Newton's method at fixed inputs, ending by the rule every solver shares ([`newton`]): the
//! corrector of continuation, the tracker's and Newton homotopy's steps, and all of
//! Newton–Raphson (`newton_raphson.rs`).

use crate::convergence::{Chords, Convergence};
use crate::correction::{Correction, Failure};
use crate::math::size;
use crate::mechanism::Mechanism;
use crate::solution::{Linear, Options};
use crate::turns::Turns;

/// Corrections that did not shrink at the rounding floor before a final run ends `Stalled`.
const MAX_STALLS: u32 = 3;

/// How a Newton run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Ending {
    /// Final rule: the correction measured at the returned point is within the tolerance (a
    /// Newton correction, or a chord correction that stands for it: [`Chords`]).
    /// Intermediate rule: the point is within it as far as the contraction predicts.
    Converged,
    /// The corrections stopped decreasing at the rounding floor, above the tolerance.
    Stalled,
    /// B was singular at an iterate.
    Singular,
    /// The iterates overflowed.
    NonFinite,
    /// The iteration limit came first.
    Exhausted,
}

/// Which stopping rule a Newton run follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Rule {
    /// For an answer: stop at a point whose own correction is within the tolerance and return
    /// that point, so that its error estimate is measured there, not extrapolated (with chord
    /// steps, B may have been factored at a point so near that it is the same within 0.1 %:
    /// [`Chords`]).
    Final,
    /// For a point on the way (a homotopy step): the extrapolated estimate suffices, and a
    /// stall at the rounding floor is good enough to go on from.
    Intermediate,
}

/// Newton's method at fixed `x` from `v`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Newton<const N: usize> {
    /// The point reached: with the final rule, the last point B was factored at (or the best
    /// one, for a stall); never a non-finite point.
    pub v: [f64; N],
    pub ending: Ending,
    pub iterations: u32,
    /// ‖B⁻¹F‖ at `v` (final rule; a chord correction enlarged by B's change if one measured
    /// `v`), or its extrapolation (intermediate rule).
    pub estimate: f64,
    /// det B at `v` (final rule; where a chord correction measured `v`, at the point B was
    /// factored, of the same sign), or at the iterate before the last correction
    /// (intermediate).
    pub det: f64,
}

/// The smallest correction met so far, at the best point factored so far: what a stall or an
/// exhausted run returns under the final rule.
#[derive(Clone, Copy)]
struct Best {
    estimate: f64,
    det: f64,
}

/// B factored at the point a Newton run starts from, ahead of the run (the run's first
/// correction is then a residual and a solve).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Prefactored<F> {
    pub factor: F,
    /// det B there.
    pub det: f64,
}

/// Work a Newton–Raphson run can skip that a plain run cannot.
#[derive(Clone, Copy)]
pub(crate) struct Shortcuts<'a, F> {
    /// Chord steps where they save a factorisation ([`Chords`]; final rule and generated
    /// factorisation only).
    pub chords: bool,
    /// B factored at the start with the generated factorisation, valid for every target (the
    /// caller's promise: B does not depend on the inputs); ignored for the dense baseline.
    pub at_start: Option<&'a Prefactored<F>>,
}

impl<F> Shortcuts<'_, F> {
    /// A plain Newton run.
    pub(crate) const NONE: Self = Shortcuts {
        chords: false,
        at_start: None,
    };
}

#[inline]
pub(crate) fn newton<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: [f64; N],
    x: &[f64; M],
    options: &Options,
    rule: Rule,
) -> Newton<N> {
    newton_scaled(sys, &v, size(&v), x, options, rule, Shortcuts::NONE)
}

/// [`newton`] with `scale` = ‖v‖ known (a [`Start`](crate::start::Start)'s, computed once), and the
/// `shortcuts` Newton–Raphson takes. Chord steps pay in a long run from a distant start; a
/// final correction after continuation starts next to the root, where they would save nothing
/// and, near a singularity, would only move the answer to another point of the rounding floor.
pub(crate) fn newton_scaled<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    scale: f64,
    x: &[f64; M],
    options: &Options,
    rule: Rule,
    shortcuts: Shortcuts<'_, S::Factor>,
) -> Newton<N> {
    crate::dispatch::fastest(
        #[inline(always)]
        || newton_loop(sys, v, scale, x, options, rule, shortcuts),
    )
}

/// [`newton_scaled`]'s work, inlined into each of [`fastest`](crate::dispatch::fastest)'s
/// twins.
#[inline(always)]
fn newton_loop<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    scale: f64,
    x: &[f64; M],
    options: &Options,
    rule: Rule,
    shortcuts: Shortcuts<'_, S::Factor>,
) -> Newton<N> {
    let tolerance = options.tolerance;
    let mut convergence = Convergence::with_scale(tolerance, scale);
    let mut fac = sys.new_factor();
    let mut c = Correction::new();
    let mut current = *v;
    let mut best: Option<Best> = None;
    // The best point is `current` itself until the step moves it, then `best_v`: it is copied
    // only as the step is taken, and only while the corrections keep shrinking.
    let mut best_v = *v;
    let mut best_here = false;
    let mut iterations = 0;
    let mut previous = f64::INFINITY;
    let mut stalls = 0;
    // Under the final rule only (intermediate points stop early anyway), and only with the
    // generated factorisation (the dense baseline stays plain Newton).
    let generated = options.linear == Linear::Generated;
    let use_chords = shortcuts.chords && rule == Rule::Final && generated;
    let mut chords = Chords::new();
    let mut finish_tried = false;
    // The inputs stay fixed: their sines and cosines are evaluated once, not in every
    // residual and factorisation.
    let mut turned = Turns::NONE;
    let t = Turns::of(sys, x, &mut turned);
    // The first correction with B factored ahead: bit for bit the one `update` would compute,
    // B being the same at the start for every target. No chord step can follow it (`fac` is
    // still empty): `Chords` knows no contraction after a single correction.
    // Checked again here, at compile time: where B depends on the inputs the branch is gone.
    let mut at_start = shortcuts
        .at_start
        .filter(|_| generated && !S::JACOBIAN_USES_INPUTS);
    let ending = loop {
        if iterations >= options.max_iterations {
            break Ending::Exhausted;
        }
        let corrected = match at_start.take() {
            Some(pre) => c
                .chord(sys, &current, x, t, &pre.factor)
                .map(|()| c.det = pre.det),
            None => c.update(sys, &current, x, t, options.linear, &mut fac),
        };
        match corrected {
            Ok(()) => {}
            Err(Failure::Singular) => {
                return Newton {
                    v: current,
                    ending: Ending::Singular,
                    iterations,
                    estimate: f64::INFINITY,
                    det: 0.0,
                };
            }
            Err(Failure::NonFinite) => break Ending::NonFinite,
        }
        iterations += 1;
        chords.newton(c.size);
        if rule == Rule::Final {
            if c.size <= tolerance {
                return Newton {
                    v: current,
                    ending: Ending::Converged,
                    iterations,
                    estimate: c.size,
                    det: c.det,
                };
            }
            if best.as_ref().is_none_or(|b| c.size < b.estimate) {
                best = Some(Best {
                    estimate: c.size,
                    det: c.det,
                });
                best_here = true;
            }
            // At the rounding floor the corrections scatter: one that did not shrink may be
            // followed by one within the tolerance (seen where the floor is just below it).
            // The best point is kept, so a few more tries cost nothing but time.
            if convergence.stalled(c.size, previous) {
                stalls += 1;
                if stalls >= MAX_STALLS {
                    break Ending::Stalled;
                }
            }
        }
        if best_here {
            // One pass copies and steps (clippy sees only the copy).
            #[allow(clippy::manual_memcpy)]
            for i in 0..N {
                best_v[i] = current[i];
                current[i] -= c.delta[i];
            }
            best_here = false;
        } else {
            for i in 0..N {
                current[i] -= c.delta[i];
            }
        }
        if use_chords {
            // Under the final rule, with B factored before the step just taken (`fac`): at
            // most one chord step, then at most one chord correction to measure the point
            // ([`Chords`]). Each chord is a residual and a solve, no factorisation.
            let newton_size = c.size;
            // How far the point now is from where B was factored.
            let mut moved = newton_size;
            let mut finish = chords.may_finish(chords.predicted(newton_size), moved, tolerance);
            // The error estimate, where a chord correction vouches for the point.
            let mut vouched = None;
            if chords.worthwhile(newton_size, tolerance) {
                if iterations >= options.max_iterations {
                    break Ending::Exhausted;
                }
                iterations += 1;
                if c.chord(sys, &current, x, t, &fac).is_ok() {
                    // The prediction may have been pessimistic: this correction may measure
                    // the point.
                    vouched = chords.vouched(c.size, moved, tolerance);
                    // Else a chord correction that does not contract is dropped: B is
                    // factored at the same point next.
                    if vouched.is_none() && c.size > tolerance && chords.admits(c.size) {
                        for i in 0..N {
                            current[i] -= c.delta[i];
                        }
                        moved += c.size;
                        finish = chords.may_finish(
                            chords.left_by_chord(c.size, moved),
                            moved,
                            tolerance,
                        );
                    }
                }
            }
            if vouched.is_none() && finish && !finish_tried {
                // Once a run: where one did not vouch, the next would rarely do better (a
                // point at the rounding floor, a pessimistic q).
                finish_tried = true;
                if iterations >= options.max_iterations {
                    break Ending::Exhausted;
                }
                iterations += 1;
                vouched = c
                    .chord(sys, &current, x, t, &fac)
                    .ok()
                    .and_then(|()| chords.vouched(c.size, moved, tolerance));
            }
            if let Some(estimate) = vouched {
                return Newton {
                    v: current,
                    ending: Ending::Converged,
                    iterations,
                    estimate,
                    det: c.det,
                };
            }
            previous = newton_size;
            continue;
        }
        if rule == Rule::Intermediate {
            let stalled = convergence.stalled(c.size, previous);
            if convergence.reached(c.size) || stalled {
                return Newton {
                    v: current,
                    ending: Ending::Converged,
                    iterations,
                    estimate: convergence.estimate,
                    det: c.det,
                };
            }
        }
        previous = c.size;
    };
    match best {
        Some(b) => Newton {
            v: if best_here { current } else { best_v },
            ending,
            iterations,
            estimate: b.estimate,
            det: b.det,
        },
        // The last iterate if finite, else the start point.
        None => Newton {
            v: if size(&current).is_finite() {
                current
            } else {
                *v
            },
            ending,
            iterations,
            estimate: f64::INFINITY,
            det: 0.0,
        },
    }
}
