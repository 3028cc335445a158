//! Typed, generational handles.
//!
//! Every entity of the DLFL lives in a slot of an [`Arena`](crate::arena::Arena).
//! A handle names the slot *and* the generation the slot had when the entity
//! was created, so a handle that outlives its entity is detected as stale
//! instead of silently naming whatever reused the slot.

use std::fmt;

macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident, $prefix:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub struct $name {
            pub(crate) index: u32,
            pub(crate) generation: u32,
        }

        impl $name {
            /// The slot index. Stable for the life of the entity, reused after it is removed.
            pub fn index(self) -> usize {
                self.index as usize
            }

            /// The generation of the slot when this handle was made.
            pub fn generation(self) -> u32 {
                self.generation
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, concat!($prefix, "{}v{}"), self.index, self.generation)
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Debug::fmt(self, f)
            }
        }
    };
}

id_type!(
    /// A vertex: a point in space and the corners that refer to it.
    VertexId,
    "v"
);
id_type!(
    /// An edge: the two corners at which it originates, one on each of its sides.
    EdgeId,
    "e"
);
id_type!(
    /// A face: a cyclic, doubly linked sequence of corners.
    FaceId,
    "f"
);
id_type!(
    /// A corner: a vertex–face pair, one step of a face's boundary walk.
    CornerId,
    "c"
);

/// The kind of entity a handle names, for error messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EntityKind {
    /// A vertex, named by a [`VertexId`].
    Vertex,
    /// An edge, named by an [`EdgeId`].
    Edge,
    /// A face, named by a [`FaceId`].
    Face,
    /// A corner, named by a [`CornerId`].
    Corner,
}

impl fmt::Display for EntityKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            EntityKind::Vertex => "vertex",
            EntityKind::Edge => "edge",
            EntityKind::Face => "face",
            EntityKind::Corner => "corner",
        })
    }
}
