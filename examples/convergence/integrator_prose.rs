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
higher floor. Raw numbers: `convergence/integrators.csv`.\n\n\
This section alone is made by `cargo run --release --example convergence -- --integrators \
[--max-spp N] [--kinds path,bdpt,mlt] [--scenes cornell-box,veach-mis,cornell-box-caustic] \
[--time-limit SECONDS] [--note TEXT]` (ladder 1, 4, …, 256 by default). It merges its \
renders into the CSV, redraws the plots and replaces only this section of the page; \
`--max-spp 0` renders nothing and rebuilds the section from the CSV. A full run of the \
study carries this section over unchanged.\n\n";

/// After the tables.
pub const FINDINGS: &str = "**What the integrator figures show** (one seed, one run on a \
2-core machine shared with two other people's builds and tests, load average 2.5–4.3. Renders \
doing the same work differed by up to 2.4× in time: the Cornell box with BDPT at 256 spp \
took 104 s with the independent sampler and 44 s with Sobol, MLT at 256 mutations per \
pixel 10.9 s in one run and 6.6 s in the next. So times are inflated by load, and the \
relMSE ratios at equal spp are more reliable than the absolute times and efficiencies).\n\n\
- *Plain Cornell box: a near tie between PT and BDPT, and PT ahead from 64 spp.* BDPT's \
  extra strategies help: at 256 spp its relMSE is 2.3× lower than PT's with Sobol \
  (2.60·10⁻⁴ against 5.91·10⁻⁴), and 1.4× lower with the independent sampler. But a BDPT \
  sample costs about 3× a PT sample (two subpaths and all their connections). Per unit \
  time, BDPT with Sobol leads at 1–16 spp (efficiency 47–69 against 37–55). PT leads from \
  64 spp on (96 against 79, 119 against 88): Sobol points pay off more for PT, whose \
  efficiency grows 3.2× from 1 to 256 spp against BDPT's 1.9×. These gaps are smaller than \
  the timing noise. MLT is \
  4–5× less efficient than both at its best (24 at 256 mutations per pixel, against 88 \
  and 119).\n\
- *Veach's plates: PT wins clearly, and BDPT loses by more than it should.* At 256 spp, BDPT \
  has 5× PT's relMSE (2.36·10⁻³ with Sobol against 4.77·10⁻⁴), and is 3–9× less \
  efficient (9–30× with the independent sampler). BDPT contains PT's own strategies, so \
  per sample it should be about as good. The likely \
  cause is how BDPT connects to a light (s = 1): it picks a light by power and a point \
  uniformly on the light's *area* (`sample_emission`). PT picks the light per shading point \
  and samples a sphere light's visible cone by solid angle (`sample_shape`). On a sphere, \
  more than half of uniform area samples lie on its far side and are wasted, and the rest \
  are spread badly for the small, bright spheres. Sampling the s = 1 connection like PT's \
  next-event estimation should close most of the gap (not tried here: it is a change to \
  the library). MLT \
  (8.65·10⁻³ at 256 mutations, 2.37·10⁻³ at 1024) is about as efficient as BDPT with the \
  independent sampler (6.7 against 4.5–6.1) and far behind PT.\n\
- *Caustic box: BDPT wins by an order of magnitude.* The caustic that the glass sphere \
  focuses on the floor comes from paths light → glass → glass → floor → camera. Light \
  tracing (t = 1) builds them directly: a light subpath through the sphere hits the \
  floor and connects to the camera. A path tracer finds them only when a BSDF sample from \
  the floor passes through the sphere and then hits the small light. That is rare, and \
  each hit is a firefly: PT's relMSE *rises* from 1.23 at 1 spp to 13.0 at 4 spp (its \
  1-spp figures are luck), and is still 0.106 at 256 spp. At 256 spp BDPT's relMSE is \
  46–49× lower (2.16·10⁻³ independent, 2.31·10⁻³ Sobol) in about 5× the time: 8–11× \
  PT's efficiency, and 60–170× at 4–16 spp. BDPT has a heavy tail of its own: its line \
  stalls between 16 and 64 spp (7.9·10⁻³, then 6.7·10⁻³), and those images are 2–4% too \
  bright on average from a few very bright samples. At 256 spp the mean is within 0.04% \
  of the reference. With seed 7 instead of 1, it is within 0.8%, and relMSE is 3.1·10⁻³ \
  instead of 2.2·10⁻³: single-seed figures on this scene are good to about ±40%. The \
  likely source is the caustic seen *through* the sphere (specular–diffuse–specular \
  paths), which no BDPT strategy samples well; the reference's own noise adds a floor.\n\
- *MLT: correct, but it pays for its bootstrap and its correlation.* Its relMSE falls as \
  about 1/N from 4 mutations per pixel on (3–4× per 4× mutations), in all three scenes. \
  But at equal counts it is 16–24× BDPT's (Sobol) on the Cornell box, 2.4–3.7× on the \
  plates and 6–30× on the caustic box. A \
  mutation is cheaper than a BDPT sample (one path length and one strategy). The bootstrap \
  (100 000 paths, about 1–2 s, the whole time of a 1-mutation render) is a fixed cost, so \
  its efficiency climbs from 0.3–0.5 at 1 mutation per pixel (relMSE 1.7–2.0: the chains \
  have barely moved) to a plateau at 256–1024. Its error is correlated: on the Cornell box \
  at 16 mutations per pixel, the worst 16×16 block's mean is 102% off and the worst 32×32 \
  block's 31% (PT at 16 spp: 10% and 3.8%). That is 10× worse blocks for 8× the relMSE, where \
  independent pixel noise would give √8 ≈ 2.8×: blotches, not grain. MLT also places its \
  mutations in proportion to brightness, while relMSE divides by the reference squared \
  (plus 0.01). The shadows and the faces turned away from the light get few mutations and \
  weigh heavily in the metric. MLT wins only where light is hard to find: on the caustic \
  box it is 3× more efficient than PT at 64 mutations per pixel and 5–6× from 256 on \
  (16.8–17.6 against 3.1). It still loses to BDPT there, by 1.5–2× at the largest counts \
  and far more below. \
  The through-the-sphere paths it should excel at are too small a share of this image to \
  pay for its costs.\n\
- *What 10⁻³ costs* (extrapolated at 1/N from the largest count; time scaled from it): \
  on the Cornell box, PT about 150 spp (8 s), BDPT with Sobol about 70 spp (11 s), MLT \
  about 1600 mutations per pixel (about 50 s). On the plates: PT 120 spp (11 s), BDPT \
  600 spp (90 s), MLT 2400 (150 s). On the caustic box: BDPT about 550 spp (30 s), MLT \
  about 4500 (55 s), PT 27 000 spp (5–6 minutes, if its fireflies ever let it fall at \
  1/N).\n";
