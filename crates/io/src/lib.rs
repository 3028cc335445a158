//! Mesh file formats. (Being written.)
