static const char help[] = "Multiscale diffusion u_t = (d(x) u_x)_x on [0, 2 pi), periodic (Lee & Engquist, sparse spectral methods).\n\
\n\
Defaults (the paper's): d = (exp(sin 64x) + exp(sin 256x))/4, u0 = exp(-(x - pi)^2), N = 2048,\n\
final time 1. Every option of the scene is in docs/spectral.md; the paper's experiment is\n\
examples/scenes/diffusion.yaml. Typical runs:\n\
  DNS:    -spectral_mode dns -ts_type rk -ts_rk_type 3 -ts_dt 1e-6 -output_times 0.25,0.5,0.75,1\n\
  sparse: -spectral_mode sparse -spectral_clusters 0:3,62:66,192:193,255:257 -ts_type rk -ts_rk_type 3 -ts_dt 1e-5\n\
  VSHMM:  -options_file_yaml examples/scenes/diffusion.yaml\n\
Output: -output_times t1,t2,... and -grid_solution_file PREFIX write PREFIX_<t>.txt (N lines x u(x)).\n\n";

#include "spectral_example.h"

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(RunSpectralExample("diffusion", 1.0));
  PetscCall(PetscFinalize());
  return 0;
}
