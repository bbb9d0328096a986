//! Estimators of the light transport equation. (to be written)
