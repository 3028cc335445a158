//! CPU rendering. (Being written.)
