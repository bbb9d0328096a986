//! Multiple importance sampling weights. (to be written)
