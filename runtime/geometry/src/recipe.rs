//! How a mechanism's derived constants follow from its geometry slots: the recipes the generator
//! writes down once per mechanism, as data, and the one interpreter that evaluates them — at
//! compile time on the declared geometry (the home check) and at run time in every generated
//! `from_geometry` (calibrated geometry). Data and one loop, rather than code emitted per
//! constant: a mechanism's constructor is a table, not thousands of lines for the compiler.

use crate::{
    along, axis_frame, check_axis, collinear_coefficients, distance, lever, normal_point, place,
    rigid_coefficients, GeometryError,
};

/// Where a point's position at the home configuration comes from, in the base frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PointRef {
    /// Three geometry slots: a base pivot, an intermediate link's pivot (declared at home), or
    /// a platform pivot in the platform's own frame (the closed-form shapes and Eq. 16 use the
    /// platform's own frame: rigid-body coefficients do not depend on the frame).
    Slots([usize; 3]),
    /// A platform pivot's platform-frame slots, placed by the declared home pose.
    PlatformHome([usize; 3]),
    /// A point the model adds to a link (see [`Auto`]), by index.
    Auto(usize),
}

/// A point the general model adds to a link, derived from others at home.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Auto {
    /// `origin + unit(toward − origin)`: the axis of a prismatic pair on its rail.
    Along { origin: PointRef, toward: PointRef },
    /// `origin + length · unit(toward − origin)`: a revolute pair's axis at the mechanism's scale.
    Lever {
        origin: PointRef,
        toward: PointRef,
        length: f64,
    },
    /// `origin + unit((a1 − a0) × (b1 − b0))`: a universal joint's second axis.
    Normal {
        origin: PointRef,
        a: [PointRef; 2],
        b: [PointRef; 2],
    },
    /// The foot of `point` on the axis `a → b` (o of [`Recipe::Axis`]): where an active pair
    /// turns `point` about.
    Foot {
        a: PointRef,
        b: PointRef,
        point: PointRef,
    },
    /// `point` turned a quarter turn about the axis `a → b` (o + w of [`Recipe::Axis`]).
    Quarter {
        a: PointRef,
        b: PointRef,
        point: PointRef,
    },
    /// `origin + by`: a point one unit along a base axis from `origin`, for the directions of
    /// a link at home.
    Shift { origin: PointRef, by: [f64; 3] },
}

/// How one constant is computed from the geometry slots.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Recipe {
    Slot(usize),
    /// Coefficient `index` of `point` in the frame: `[a, b, c, d]` with
    /// `q = a p1 + b p2 + c p3 + d (p2 − p1) × (p3 − p1)` (d = 0 in the coplanar form).
    Rigid {
        frame: [PointRef; 3],
        point: PointRef,
        index: usize,
        coplanar: bool,
    },
    /// Coefficient `index` of `point` on the line: `q = a p1 + b p2`, `a + b = 1`.
    Collinear {
        line: [PointRef; 2],
        point: PointRef,
        index: usize,
    },
    Distance {
        a: PointRef,
        b: PointRef,
    },
    /// `1 / |b − a|`: what turns a slide along the axis `a → b` into a multiple of `b − a`.
    InverseDistance {
        a: PointRef,
        b: PointRef,
    },
    /// Coordinate `index` of a point's home position.
    Coordinate {
        point: PointRef,
        index: usize,
    },
    /// Component `index` of `[e, o, u, w]` for a rotation of `point` about the axis `a → b`:
    /// e the unit axis, o the foot of `point` on it, u the radial arm, w = e × u.
    Axis {
        a: PointRef,
        b: PointRef,
        point: PointRef,
        index: usize,
    },
}

impl Recipe {
    /// The recipe with its component index cleared: two recipes with the same key compute the
    /// same vector (a frame's coefficients, an axis frame) and differ only in the entry taken.
    fn key(self) -> Recipe {
        match self {
            Recipe::Rigid {
                frame,
                point,
                coplanar,
                ..
            } => Recipe::Rigid {
                frame,
                point,
                index: 0,
                coplanar,
            },
            Recipe::Collinear { line, point, .. } => Recipe::Collinear {
                line,
                point,
                index: 0,
            },
            Recipe::Axis { a, b, point, .. } => Recipe::Axis {
                a,
                b,
                point,
                index: 0,
            },
            other => other,
        }
    }
}

/// A mechanism's recipes: its home pose (where [`PointRef::PlatformHome`] places platform
/// pivots), its added points in order (each may use the earlier ones) and one recipe per
/// constant.
#[derive(Clone, Copy, Debug)]
pub struct Recipes<'a> {
    pub home_pose: [f64; 6],
    pub auto: &'a [Auto],
    pub constants: &'a [Recipe],
}

/// Why a constant could not be derived: the error and the constant's index (or, for an added
/// point, `None`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeriveError {
    pub error: GeometryError,
    pub constant: Option<usize>,
}

impl Recipes<'_> {
    /// Evaluates the recipes on the slots `g`: the added points into `auto` (at least as long
    /// as [`Recipes::auto`]) and the constants into `out` (at least as long as
    /// [`Recipes::constants`]). A vector several constants take entries of (a frame's rigid
    /// coefficients, an axis frame) is computed once when they follow each other, as the
    /// generator orders them.
    ///
    /// ```
    /// use linkage_geometry::recipe::{PointRef, Recipe, Recipes};
    /// // The distance between two points held in slots 0..3 and 3..6, then slot 6 itself.
    /// let recipes = Recipes {
    ///     home_pose: [0.0; 6],
    ///     auto: &[],
    ///     constants: &[
    ///         Recipe::Distance { a: PointRef::Slots([0, 1, 2]), b: PointRef::Slots([3, 4, 5]) },
    ///         Recipe::Slot(6),
    ///     ],
    /// };
    /// let mut c = [0.0; 2];
    /// recipes.derive(&[0.0, 0.0, 0.0, 3.0, 4.0, 0.0, 7.5], &mut [], &mut c).unwrap();
    /// assert_eq!(c, [5.0, 7.5]);
    /// ```
    pub fn derive(
        &self,
        g: &[f64],
        auto: &mut [[f64; 3]],
        out: &mut [f64],
    ) -> Result<(), DeriveError> {
        // An index past its table (a slot, an added point, a coefficient) or buffers shorter
        // than the recipes would be the generator's bug: `UnknownName` (no value has that
        // name), never a panic, so that a generated `from_geometry` is total.
        let unknown = |constant| DeriveError {
            error: GeometryError::UnknownName,
            constant,
        };
        for (i, a) in self.auto.iter().enumerate() {
            let Some((done, [slot, ..])) = auto.split_at_mut_checked(i) else {
                return Err(unknown(None));
            };
            *slot = self.added_point(g, done, a).map_err(|error| DeriveError {
                error,
                constant: None,
            })?;
        }
        let auto = auto.get(..self.auto.len()).ok_or(unknown(None))?;
        if out.len() < self.constants.len() {
            return Err(unknown(None));
        }
        let mut last: Option<(Recipe, [f64; 12])> = None;
        for (i, (r, out)) in self.constants.iter().zip(out.iter_mut()).enumerate() {
            let at = |p: PointRef| self.point(g, auto, p);
            let fail = |error| DeriveError {
                error,
                constant: Some(i),
            };
            let vector = |r: &Recipe| -> Result<[f64; 12], GeometryError> {
                let mut v = [0.0; 12];
                match *r {
                    Recipe::Rigid {
                        frame,
                        point,
                        coplanar,
                        ..
                    } => v[..4].copy_from_slice(&rigid_coefficients(
                        frame.map(at),
                        at(point),
                        coplanar,
                    )?),
                    Recipe::Collinear { line, point, .. } => {
                        v[..2].copy_from_slice(&collinear_coefficients(line.map(at), at(point))?)
                    }
                    Recipe::Axis { a, b, point, .. } => v = axis_frame(at(a), at(b), at(point))?,
                    _ => {}
                }
                Ok(v)
            };
            let value = match *r {
                Recipe::Slot(s) => g.get(s).copied(),
                Recipe::Distance { a, b } => Some(distance(at(a), at(b))),
                Recipe::InverseDistance { a, b } => {
                    // A slide's axis: refused by the rule of every axis, not only at zero (an
                    // axis 1e-12 of its size long would give a constant of 1e12).
                    check_axis(at(a), at(b)).map_err(fail)?;
                    Some(1.0 / distance(at(a), at(b)))
                }
                Recipe::Coordinate { point, index } => at(point).get(index).copied(),
                Recipe::Rigid { index, .. }
                | Recipe::Collinear { index, .. }
                | Recipe::Axis { index, .. } => {
                    let key = r.key();
                    let v = match last {
                        Some((k, v)) if k == key => v,
                        _ => vector(r).map_err(fail)?,
                    };
                    last = Some((key, v));
                    v.get(index).copied()
                }
            };
            *out = value.ok_or(unknown(Some(i)))?;
        }
        Ok(())
    }

    /// A point's home position, with the added points computed so far. A slot or added point
    /// past its table is not a point: NaN, which the kernels report as a degenerate axis.
    pub fn point(&self, g: &[f64], auto: &[[f64; 3]], p: PointRef) -> [f64; 3] {
        let slot = |i: usize| g.get(i).copied().unwrap_or(f64::NAN);
        match p {
            PointRef::Slots(s) => s.map(slot),
            PointRef::PlatformHome(s) => place(self.home_pose, s.map(slot)),
            // The generator orders added points so that each uses earlier ones only; anything
            // else is not a point.
            PointRef::Auto(i) => auto.get(i).copied().unwrap_or([f64::NAN; 3]),
        }
    }

    /// An added point's home position, from the slots and the added points before it.
    pub fn added_point(
        &self,
        g: &[f64],
        auto: &[[f64; 3]],
        a: &Auto,
    ) -> Result<[f64; 3], GeometryError> {
        let at = |p: PointRef| self.point(g, auto, p);
        match *a {
            Auto::Along { origin, toward } => along(at(origin), at(toward)),
            Auto::Lever {
                origin,
                toward,
                length,
            } => lever(at(origin), at(toward), length),
            Auto::Normal { origin, a, b } => normal_point(at(origin), a.map(at), b.map(at)),
            Auto::Foot { a, b, point } => {
                axis_frame(at(a), at(b), at(point)).map(|f| [f[3], f[4], f[5]])
            }
            Auto::Quarter { a, b, point } => axis_frame(at(a), at(b), at(point))
                .map(|f| [f[3] + f[9], f[4] + f[10], f[5] + f[11]]),
            Auto::Shift { origin, by } => {
                let o = at(origin);
                Ok([o[0] + by[0], o[1] + by[1], o[2] + by[2]])
            }
        }
    }
}
