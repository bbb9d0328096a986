//! The explanatory text of section 4 of `convergence.md` (the integrator study), written
//! from the figures of the run named in it; the tables beside it are regenerated.

/// The section's heading (also what [`crate::integrator_study::splice`] looks for).
pub const HEADING: &str = "## 4. Integrators: path tracing, BDPT, MLT";

/// Before the tables.
pub const INTRO: &str = "## 4. Integrators: path tracing, BDPT, MLT\n\n\
Three estimators of the same images: the path tracer (PT: next-event estimation and BSDF \
sampling combined by MIS with the power heuristic, Sobol sampler, lights on triangles and \
rectangles sampled by solid angle), bidirectional path tracing (BDPT: every (s, t) \
strategy, power heuristic; independent and Sobol samplers) and Metropolis light transport \
in primary sample space over BDPT paths (MLT: 100 000 bootstrap paths, 1000 chains, large \
steps with probability 0.3, small steps σ = 0.01; the spp column counts mutations per \
pixel, and MLT's time includes its bootstrap). The scenes are the files \
`tests/data/cornell-box.xml`, `veach-mis.xml` and `cornell-box-caustic.xml` (the Cornell \
box with a glass sphere under a light of 1/16 the area, 128×128) with their Mitsuba 3 \
references; relMSE and efficiency are as in section 3, seed 1 throughout. All three \
files leave the path depth unlimited. PT and BDPT follow them with Russian roulette. MLT \
needs a limit and gets 12 segments: the longer paths carry about 0.1% of the Cornell \
box's light, below the errors measured here. The caustic box's reference is noisier than \
the others (its own two halves differ by 0.72% on 32×32 blocks), so its relMSE has a \
higher floor. Raw numbers: `convergence/integrators.csv`.\n\n";

/// After the tables.
pub const FINDINGS: &str = "**What the integrator figures show.** (Not yet written.)\n";
