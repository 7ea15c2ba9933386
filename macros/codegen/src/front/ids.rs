//! Typed indices into the resolved declaration ([`crate::front::resolved::Decl`]): only the
//! resolver makes them, each from a name it has found, so a lookup by id cannot miss.

macro_rules! id {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
        pub struct $name(u32);

        impl $name {
            /// Made by the resolver only, from a position it has just filled.
            pub(in crate::front) fn new(index: usize) -> Self {
                $name(index as u32)
            }

            /// The position in its table of the declaration.
            pub fn index(self) -> usize {
                self.0 as usize
            }
        }
    };
}

id!(
    /// A link: `base` is the first, `platform` the second, then the declared links in order.
    LinkId
);
id!(
    /// A pivot, in declaration order over the links.
    PivotId
);
id!(
    /// A joint input, in chain order: its position in `x`.
    InputId
);
id!(
    /// A parameter of `params { ... }`.
    ParamId
);
id!(
    /// A chain, in declaration order.
    ChainId
);

/// A pair: its chain and its place there.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct PairId {
    pub chain: ChainId,
    pub index: usize,
}

impl LinkId {
    /// `base`: the resolver puts it first.
    pub const BASE: LinkId = LinkId(0);
    /// `platform`: the resolver puts it second.
    pub const PLATFORM: LinkId = LinkId(1);
}
