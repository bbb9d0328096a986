//! Change of variables between measures, and numerical Jacobians of any warp. (to be written)
