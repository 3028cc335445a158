//! Conversion between polygon soups and the DLFL kernel. (Being written.)
