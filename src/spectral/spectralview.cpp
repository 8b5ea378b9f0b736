/*
  VSHMMSpectralView(): the scene, the clusters (and how they were found) and the evaluation.
*/
#include "spectralimpl.hpp"

#include <sstream>

/* The cluster detection's parameters and outcome (C's %g, as in the rest of the view). */
static std::string DescribeDetection(const VSHMMSpectral_Data *s)
{
  std::ostringstream m;
  if (!s->detection.rule.empty()) m << "cluster detection " << s->detection.rule << "\n";
  if (s->detection.dt > 0) {
    m << "cluster detection: direct simulation with " << s->N << " modes, ";
    if (s->detection.rkc_stages > 0) m << "RK3 to the first look, then RKC steps of up to " << s->detection.rkc_step << " with up to " << s->detection.rkc_stages << " stages (RK3: dt = " << s->detection.dt << ")";
    else m << "RK3 dt = " << s->detection.dt;
    m << ", snapshots at";
    for (PetscReal t : s->detection.times) m << " " << t;
    if (!s->detection.converged) m << " (the clusters still changed at -spectral_cluster_detect_max_steps " << s->detect_max_steps << ")";
    m << "\n";
    if (s->detection.merged_at > 0)
      m << "cluster detection: bands merged at t = " << s->detection.merged_at << "; the wavenumbers outside the bands of t = " << s->detection.kept << " hold at most -spectral_cluster_tolerance " << s->cluster_tol << " of ||u||: those bands are kept\n";
  }
  m << "cluster detection: lambda " << VSHMMSpectralLambda(s) << " (" << spc::normalizationName(s->norm) << " normalisation), ";
  if (s->gap >= 0) m << "gap " << s->gap;
  else m << "gap ratio " << s->gap_ratio;
  m << (s->fill_holes ? ", holes filled" : "") << ": " << s->detection.support << " wavenumbers above lambda in " << s->detection.merged << " bands, " << s->detection.scales << " clusters (bands less than " << s->scale_separation << " apart in time scale share one)\n";
  if (s->detection.widened >= 0) m << "cluster detection: the last looks agree within -spectral_cluster_tolerance " << s->cluster_tol << ": their bands widened at the edges by wavenumbers holding " << s->detection.widened << " of ||u||\n";
  if (!s->detection.dropped.empty())
    m << "cluster detection: bands left out (their share of ||u|| below -spectral_cluster_min_band_share " << s->min_band_share << " x -spectral_cluster_tolerance " << s->cluster_tol << "): " << s->detection.dropped << "\n";
  if (!s->detection.kept_band.empty()) m << "cluster detection: the thin band " << s->detection.kept_band << "\n";
  if (s->detection.left_out >= 0) m << "cluster detection: the wavenumbers outside the bands hold " << s->detection.left_out << " of ||u|| (root mean square over the DNS steps)\n";
  if (s->detection.evaluations > 0) m << "cluster detection cost: " << s->detection.steps << " DNS steps, " << s->detection.evaluations << " evaluations on " << s->N << " modes (wall time: VSHMMSpectralGetStatistics())\n";
  return m.str();
}

/* The scene, its clusters and its evaluation, as VSHMMSpectralView() prints them. */
static std::string DescribeScene(const VSHMMSpectral_Data *s)
{
  std::ostringstream m;
  if (s->mode == VSHMMSPECTRAL_MODE_SPARSE && s->detection.support > 0 && !s->widenings) m << DescribeDetection(s); /* the clusters were detected (once: a widening does not detect again) */
  m << "scene: N = " << s->N << " grid points on [0, 2 pi), wavenumbers 0.." << spc::maxWavenumber((int)s->N) << "\n";
  for (const std::string &t : s->terms) {
    if (t == "diffusion") m << "  term diffusion: u_t += (d u_x)_x, d = " << s->diff.describe() << "\n";
    else if (t == "advection") m << "  term advection: u_t += -a u_x, a = " << s->vel.describe() << "\n";
    else if (t == "burgers") m << "  term burgers: u_t += -(c u^2/2)_x, c = " << s->burgers.describe() << "\n";
    else if (t == "reaction") {
      m << "  term reaction: u_t += r (c0 + c1 u + c2 u^2 + c3 u^3), c =";
      for (size_t i = 0; i < 4; ++i) m << (i ? "," : " ") << (i < s->reaction.size() ? s->reaction[i] : 0.0);
      m << ", r = " << s->rate.describe() << "\n";
    } else m << "  term source: u_t += s, s = " << s->source.describe() << "\n";
  }
  m << "  u0 = " << s->u0.describe() << "\n";
  if (s->mode == VSHMMSPECTRAL_MODE_DNS) m << "mode dns: every wavenumber, " << s->layout->size() << " coefficients\n";
  else {
    m << "mode sparse: " << s->layout->modeCount() << " wavenumbers (" << s->layout->size() << " coefficients) in " << s->layout->clusterCount() << " clusters, one RHS split each (slowest first)";
    if (s->widenings) m << "; widened " << s->widenings << (s->widenings > 1 ? " times" : " time") << " as the truncation check asked (-spectral_truncation_check widen)";
    m << "\n";
    for (int j = 0; j < s->layout->clusterCount(); ++j) {
      std::vector<int> modes(s->cluster_modes[j].begin(), s->cluster_modes[j].end());
      m << "  K" << j << " = {" << spc::formatModes(modes) << "}: " << modes.size() << " wavenumbers, coefficients " << s->layout->clusterOffsetBegin(j) << ".." << s->layout->clusterOffsetEnd(j) - 1 << "\n";
    }
  }
  if (s->evaluation == VSHMMSPECTRAL_EVALUATION_MATRIX) m << "evaluation: dense operator on the retained modes (" << s->layout->size() << " x " << s->layout->size() << ")\n";
  else m << "evaluation: pseudo-spectral with FFTW (" << VSHMMSpectralPlanners[s->planner] << " planner), cluster projection " << VSHMMSpectralProjections[s->projection] << "\n";
  if (s->op && s->op->hasPadded()) m << "  burgers/reaction products on a padded grid of M = " << s->op->paddedSize() << " points (no aliasing on the retained modes), projected by FFT\n";
  return m.str();
}

/*@C
   VSHMMSpectralView - Prints the scene: grid, terms and fields, initial data, mode, clusters
   (and how they were detected), evaluation

   Collective

   Input Parameters:
+  sp     - the object (set up here if it is not)
-  viewer - an ASCII or string viewer (NULL: stdout of the object's communicator)

   Level: beginner

.seealso: `VSHMMSpectralSetUp()`, `VSHMMSpectralViewFromOptions()`
@*/
PetscErrorCode VSHMMSpectralView(VSHMMSpectral sp, PetscViewer viewer)
{
  PetscBool isascii, isstring;

  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(PetscObjectComm((PetscObject)sp), &viewer));
  VSHMMValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCheckSameComm(sp, 1, viewer, 2);
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERSTRING, &isstring));
  if (!isascii && !isstring) PetscFunctionReturn(0);
  PetscCall(VSHMMSpectralSetUp(sp));
  const std::string text = DescribeScene(sp->data);
  if (isascii) PetscCall(PetscViewerASCIIPrintf(viewer, "%s", text.c_str()));
  else PetscCall(PetscViewerStringSPrintf(viewer, "%s", text.c_str()));
  PetscFunctionReturn(0);
}

/*@C
   VSHMMSpectralViewFromOptions - Views the object if an option asks for it

   Collective

   Input Parameters:
+  sp   - the object
.  obj  - an object whose options prefix is used (NULL: the object's own)
-  name - the option, e.g. "-spectral_view"

   Level: intermediate

.seealso: `VSHMMSpectralView()`, `PetscObjectViewFromOptions()`
@*/
PetscErrorCode VSHMMSpectralViewFromOptions(VSHMMSpectral sp, PetscObject obj, const char name[])
{
  PetscFunctionBegin;
  VSHMMValidHeaderSpecific(sp, VSHMMSPECTRAL_CLASSID, 1);
  PetscCall(PetscObjectViewFromOptions((PetscObject)sp, obj, name));
  PetscFunctionReturn(0);
}
