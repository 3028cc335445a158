//! Smoothing subdivision. (Being written.)
