//! Measures of an arbitrary polygon soup. (Being written.)
