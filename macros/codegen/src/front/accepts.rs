//! What each pair kind takes: the one table every pair's arguments are checked against.

use crate::front::ast::PairKind;

#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Need {
    No,
    Optional,
    Required,
}

/// What each pair kind takes: the one table every argument is checked against.
pub struct Accepts {
    /// Names its centre pivot (`S(C)`, `U(C, ...)`).
    pub centre: bool,
    pub axis: Need,
    pub offset: bool,
    pub lead: Need,
    /// Joint variables when active; `None`: no active form is modelled.
    pub variables: Option<usize>,
    /// Whether a passive form is modelled (degree ≤ 2).
    pub passive: bool,
}

impl Accepts {
    pub fn of(kind: PairKind) -> Accepts {
        let base = Accepts {
            centre: false,
            axis: Need::Required,
            offset: false,
            lead: Need::No,
            variables: Some(1),
            passive: true,
        };
        match kind {
            // Active: yaw, pitch and roll of the link after it relative to the link before.
            PairKind::S => Accepts {
                centre: true,
                axis: Need::No,
                variables: Some(3),
                ..base
            },
            // Active: the turns about its first and its second axis.
            PairKind::U => Accepts {
                centre: true,
                axis: Need::Optional,
                variables: Some(2),
                ..base
            },
            PairKind::R => base,
            PairKind::P => Accepts {
                axis: Need::Optional,
                offset: true,
                ..base
            },
            PairKind::C => Accepts {
                variables: Some(2),
                ..base
            },
            PairKind::H => Accepts {
                lead: Need::Required,
                passive: false,
                ..base
            },
        }
    }
}
