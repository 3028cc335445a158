//! Exact geometry. (Being written.)
