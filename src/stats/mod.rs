//! The chi-square goodness-of-fit harness and pdf-integration checks. (to be written)
