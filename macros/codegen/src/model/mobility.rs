//! Mobility by the Grübler–Kutzbach criterion, M = 6(L − 1 − J) + Σ fᵢ, less the idle
//! freedoms it counts but no input can drive: the spin of a leg or rod about the line through
//! its two spherical joints.

use crate::front::ids::LinkId;
use crate::front::resolved::{Chain, Decl, Pair, PairKind};
use crate::model::Model;

pub struct Mobility {
    pub links: usize,
    pub joints: usize,
    pub freedoms: usize,
    pub idle: usize,
}

impl Mobility {
    pub fn gruebler(&self) -> i64 {
        6 * (self.links as i64 - 1 - self.joints as i64) + self.freedoms as i64
    }

    /// Whether the pairs join the links without a closed loop (J = L − 1).
    pub fn is_tree(&self) -> bool {
        self.joints + 1 == self.links
    }

    pub fn effective(&self) -> i64 {
        self.gruebler() - self.idle as i64
    }

    pub fn describe(&self) -> String {
        format!(
            "Grübler–Kutzbach: M = 6(L − 1 − J) + Σf = 6({} − 1 − {}) + {} = {}, less {} idle spin{} = {}",
            self.links,
            self.joints,
            self.freedoms,
            self.gruebler(),
            self.idle,
            if self.idle == 1 { "" } else { "s" },
            self.effective()
        )
    }
}

fn freedoms(kind: PairKind) -> usize {
    match kind {
        PairKind::R | PairKind::P | PairKind::H => 1,
        PairKind::C | PairKind::U => 2,
        PairKind::S => 3,
    }
}

/// A chain's last two joints both spherical: the link between them can spin about the line
/// through their centres without moving anything.
fn idle_spin(n: &Chain) -> usize {
    let spherical = |p: &Pair| p.kind == PairKind::S && !p.active;
    match n.pairs.as_slice() {
        [.., a, b] if spherical(a) && spherical(b) => 1,
        [a, slider, b] if spherical(a) && slider.kind == PairKind::P && spherical(b) => 1,
        _ => 0,
    }
}

pub fn of(d: &Decl) -> Mobility {
    // Every link once: the base and the platform, each declared link however many chains
    // start, end or pass through it, and each unnamed link between two pairs of a chain.
    let mut declared: Vec<LinkId> = vec![LinkId::BASE, LinkId::PLATFORM];
    let mut mob = Mobility {
        links: 0,
        joints: 0,
        freedoms: 0,
        idle: 0,
    };
    for n in &d.chains {
        for link in &n.links {
            match link {
                Some(id) if declared.contains(id) => {}
                Some(id) => declared.push(*id),
                None => mob.links += 1,
            }
        }
        mob.joints += n.pairs.len();
        mob.freedoms += n.pairs.iter().map(|p| freedoms(p.kind)).sum::<usize>();
        mob.idle += idle_spin(n);
    }
    mob.links += declared.len();
    mob
}

/// The error for a declaration whose active joint variables do not match its `mobility`
/// (found by `rule`, which the message quotes).
pub fn mismatch(d: &Decl, model: &Model, mobility: i64, rule: &str) -> syn::Error {
    let inputs = model.inputs.len();
    // A platform whose pivots are collinear is a line: its spin about itself is no freedom,
    // which a declaration meant for a located platform may not expect.
    let line = if !model.located && model.points.len() >= 2 {
        "; the platform's pivots are on one line, which places it by a point and a direction (five freedoms: its spin about the line is none)"
    } else {
        ""
    };
    syn::Error::new(
        d.name.span(),
        format!(
            "the mechanism has {inputs} active joint variable{} but mobility {mobility} ({rule}){line}; declare one active pair per degree of freedom",
            if inputs == 1 { "" } else { "s" },
        ),
    )
}
