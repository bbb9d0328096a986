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
The learned sampling of issue 28 has its own three scenes (`tests/data/issue28/`, 128×128, \
Mitsuba 3 references): *many-lights* (420 rectangle lights and an emitting sphere of 10 000 \
triangles), where the path tracer chooses lights with the light BVH (its default there) \
against the same tracer choosing by power (`--light-bvh off`); *indirect* (a lamp facing \
the ceiling under an opaque shade) and the plain Cornell box, where the guided path tracer \
runs against the path tracer, its time including its training passes (equal total time); \
and *door* (light only through a door left ajar), where guiding meets BDPT and MLT.\n\n\
This section alone is made by `cargo run --release --features plots -p mcrt-render --example convergence -- --integrators \
[--max-spp N] [--kinds path,path-power,guided,bdpt,mlt] \
[--scenes cornell-box,veach-mis,cornell-box-caustic,many-lights,indirect,door] \
[--time-limit SECONDS] [--note TEXT]` (ladder 1, 4, …, 256 by default). It merges its \
renders into the CSV, redraws the plots and replaces only this section of the page; \
`--max-spp 0` renders nothing and rebuilds the section from the CSV. A full run of the \
study carries this section over unchanged.\n\n";

/// After the tables.
pub const FINDINGS: &str = "**What the integrator figures show** (one seed, one run on the \
otherwise idle 2-core machine, at b7e3845; the 1024-mutation MLT column is from an earlier \
run on a loaded machine. This machine's times drift by ±20%, so efficiencies within 20% of \
each other are a tie; `docs/peer-comparison.md` has the same estimators beside Mitsuba 3).\n\n\
- *Plain Cornell box: PT ahead by 1.4× at 256 spp, BDPT ahead at 1 spp.* BDPT's extra \
  strategies help per sample: at 256 spp its relMSE is 2.0× lower than PT's with Sobol \
  (2.99·10⁻⁴ against 5.91·10⁻⁴), 1.3× lower with the independent sampler. But a BDPT sample \
  costs 2.7× a PT sample (two subpaths and about 20 connections), and Sobol points pay off \
  more for PT, whose efficiency grows 2.7× from 1 to 256 spp against BDPT's 1.6×: PT with \
  Sobol reaches 158 at 256 spp, BDPT 115 (Sobol) and 80 (independent). MLT stays 4–6× below \
  both (26 at 256 mutations per pixel).\n\
- *Veach's plates: the same error per sample, PT cheaper.* BDPT's `s = 1` is the path \
  tracer's own next-event estimation (cone sampling of the sphere lights, the light chosen per \
  shading point), weighted by its exact density, so per sample the two match (relMSE at 256 spp \
  4.89·10⁻⁴ against 4.77·10⁻⁴, Sobol). The light subpaths add almost nothing on glossy plates \
  lit by four spheres and cost 2.5× in time: PT is 2.2–2.8× more efficient at 1–256 spp. MLT \
  is 6–22× below BDPT.\n\
- *Caustic box: BDPT wins by more than an order of magnitude.* The caustic the glass sphere \
  focuses on the floor comes from paths light → glass → glass → floor → camera. Light \
  tracing (t = 1) builds them directly; a path tracer finds them only when a BSDF sample \
  from the floor passes through the sphere and hits the small light, each hit a firefly: \
  PT's relMSE *rises* from 1.23 at 1 spp to 13.0 at 4 spp (its 1-spp figure is luck) and is \
  still 0.106 at 256 spp, where BDPT's is 2.21·10⁻³ (independent): 48× lower, in 2.6× the \
  time, 18–30× PT's efficiency at 64–256 spp and 80–180× at 4–16 spp. BDPT has a heavy \
  tail of its own (its line flattens between 16 and 64 spp): the caustic seen *through* the \
  sphere (specular–diffuse–specular paths) only the `s = 0` strategy can make, by hitting \
  the small light through the glass.\n\
- *MLT: correct, but it pays for its bootstrap and its correlation.* Its relMSE falls as \
  about 1/N from 4 mutations per pixel on, in all three scenes, but at equal counts it is \
  about 20× BDPT's (Sobol) on the Cornell box, 12× on the plates and 6× on the caustic box. \
  Its bootstrap (100 000 normalisation samples and 100 000 paths per length) is a fixed cost \
  of about 1 s, the whole time of a 1-mutation render. Its error is correlated (blotches, \
  not grain: on the Cornell box at 16 mutations per pixel the worst 16×16 block is about 100% \
  off, PT's at 16 spp 10%), and it places mutations in proportion to brightness while relMSE \
  weighs the dark regions heavily. It wins against PT only where light is hard to find: on \
  the caustic box from 64 mutations per pixel on (17.9–34.9 against 2.8–3.4), and still \
  loses to BDPT there by 1.8–4.6×.\n\
- *What 10⁻³ costs* (extrapolated at 1/N from 256 spp; time scaled from it): on the Cornell \
  box, PT about 150 spp (6 s), BDPT with Sobol about 75 spp (9 s); on the plates, PT about \
  120 spp (5 s), BDPT with Sobol 125 spp (12 s); on the caustic box, BDPT about 570 spp \
  (16 s), MLT about 3400 mutations per pixel (30 s), PT about 27 000 spp (5 minutes, if its \
  fireflies ever let it fall at 1/N).\n\n\
**What the learned-sampling figures show** (issue 28's lines, one seed, one run on the \
otherwise idle machine: many-lights and the door's BDPT and MLT at 52b7d42, the PT and \
guided lines of the Cornell box, the indirect room and the door at 7180e3a; \
`docs/renderer.md` has the side-by-side with Mitsuba 3 over three seeds).\n\n\
- *Many lights: the light BVH pays, by less than its error suggests.* At every budget its \
  relMSE is 1.6–1.9× below the power choice's (3.78·10⁻³ against 6.60·10⁻³ at 256 spp), \
  but a sample costs about 1.6× as much (10.5 s against 6.6 s at 256 spp): its efficiency \
  is 1.25× the power choice's at 64 spp and 1.10× at 256, and below it at 1–4 spp. Issue \
  28's target (3×) is not met.\n\
- *Indirect room and Cornell box: guiding stops where it does not pay, and then costs \
  about a tenth more than PT.* After its third training pass (7 spp) the guided integrator \
  asks its guide what guiding promises (`min_gain`, docs/renderer.md); on both scenes the \
  promise (1.21 and 1.07) is below the guided tracer's cost per sample, so the rest of the \
  budget is path traced. From 64 spp on its relMSE is the path tracer's (indirect room at \
  256 spp: 3.97·10⁻³ against 3.92·10⁻³; Cornell box 6.17·10⁻⁴ against 6.12·10⁻⁴) in \
  1.08–1.15× the time (3.74 s against 3.46 s; 11.8 s against 10.3 s): 0.86–0.91× PT's \
  efficiency at 64–256 spp, 0.64–0.73× at 4–16 spp, where the 7 guided samples of training \
  are a large share. Guided to the end (`min_gain` 0, at 5973e25), it had 0.72× PT's \
  relMSE on the indirect room at 256 spp (2.81·10⁻³) in twice the time: 0.70× PT's \
  efficiency. What it learns there (the light comes from a small bright patch of ceiling) \
  does not yet repay the cost of guiding.\n\
- *Door: MLT wins, BDPT has the least error per sample.* Light reaches the camera's room \
  only through the gap; every estimator's error is dominated by rare bright paths. BDPT's \
  relMSE at 256 spp is 3.2× below the path tracer's (0.0665 against 0.212) but costs 4× the \
  time; MLT, once its chains have found the gap, is the most efficient from 64 mutations per \
  pixel on (1.49 and 1.81 at 64 and 256, against PT's 0.91 and 0.85, BDPT's 0.71 and 0.66). \
  The guided integrator's guide promises almost nothing here (1.01 after its third pass: \
  its spatial tree learns from the paths that found the gap, which are too few at these \
  budgets), so it stops training after 7 spp and is level with PT (0.213 against 0.212 at \
  256 spp, in about the same time).\n";
