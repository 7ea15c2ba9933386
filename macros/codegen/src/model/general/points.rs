//! The points of the general model: every declared pivot (a [`PointId`] per [`PivotId`], in the
//! same order), then the points the pairs add (a slide's axis tip, a U's second axis, a
//! cylinder's copies of its axis), each with its name in the listing and its home position.

use crate::front::ids::PivotId;
use crate::front::resolved::{Decl, LinkRole};
use crate::model::{Builder, PointRef};

/// A point of the general model.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct PointId(usize);

impl PointId {
    /// A declared pivot's point: the pivots come first, in their order.
    pub fn of(p: PivotId) -> PointId {
        PointId(p.index())
    }

    pub fn index(self) -> usize {
        self.0
    }
}

/// What an added point is, so that a pair adding the same point twice gets the one point.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Addition {
    /// The tip of a slide's axis, one unit from `origin` towards `towards`.
    AxisTip { origin: PointId, towards: PointId },
    /// A revolute pair's axis at the mechanism's scale: on the axis `origin → towards`, as far
    /// from `origin` as the mechanism is large (see `topology::levers`).
    AxisLever { origin: PointId, towards: PointId },
    /// A universal joint's second axis, one unit from its centre.
    SecondAxis { centre: PointId },
    /// A cylindrical pair's slider's own copy of an end of the rail's axis (0: its origin, 1:
    /// its tip `axis`).
    Copy { axis: PointId, end: usize },
    /// The rail's own point where a slide's axis origin, declared on the slider, is at home.
    RailOrigin { origin: PointId },
    /// A point of the base one unit off a slide's axis (its tip `axis`), where the base holds
    /// none off it.
    OffAxis { axis: PointId },
}

pub struct Points {
    names: Vec<String>,
    homes: Vec<PointRef>,
    pivots: Vec<PivotId>,
    added: Vec<(Addition, PointId)>,
}

impl Points {
    /// Every declared pivot, at its declared position (a platform pivot placed by the home
    /// pose).
    pub fn new(b: &Builder, d: &Decl) -> Points {
        let mut names = Vec::new();
        let mut homes = Vec::new();
        let mut pivots = Vec::new();
        for (id, link) in d.links_with_ids() {
            for &p in &link.pivots {
                let slots = b.pivot_slots(p);
                names.push(d.pivot(p).name.to_string());
                homes.push(if link.role == LinkRole::Platform {
                    PointRef::PlatformHome(slots)
                } else {
                    PointRef::Slots(slots)
                });
                debug_assert_eq!((d.pivot(p).link, p.index()), (id, pivots.len()));
                pivots.push(p);
            }
        }
        Points {
            names,
            homes,
            pivots,
            added: Vec::new(),
        }
    }

    pub fn len(&self) -> usize {
        self.names.len()
    }

    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    pub fn name(&self, q: PointId) -> &str {
        &self.names[q.index()]
    }

    pub fn home(&self, q: PointId) -> PointRef {
        self.homes[q.index()]
    }

    /// Every point's home position, in order.
    pub fn homes(&self) -> impl Iterator<Item = PointRef> + '_ {
        self.homes.iter().copied()
    }

    /// The declared pivot a point is, if it is one.
    pub fn pivot(&self, q: PointId) -> Option<PivotId> {
        self.pivots.get(q.index()).copied()
    }

    /// Adds a point (or, for one added already, moves it to `home`).
    pub fn add(&mut self, what: Addition, name: String, home: PointRef) -> PointId {
        if let Some(&(_, q)) = self.added.iter().find(|(a, _)| *a == what) {
            self.homes[q.index()] = home;
            return q;
        }
        let q = PointId(self.names.len());
        self.names.push(name);
        self.homes.push(home);
        self.added.push((what, q));
        q
    }
}
