//! Built-in primitives. (Being written.)
