//! Samplers: per-pixel sample values, independent, stratified and low-discrepancy. (to be written)
