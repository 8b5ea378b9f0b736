static const char help[] = "Multiscale advection u_t + a(x) u_x = 0 on [0, 2 pi), periodic (Lee & Engquist, sparse spectral methods).\n\
\n\
Defaults: a = exp((0.6 + 0.2 cos 3x)/(1 + 0.35 sin 64x + 0.35 sin 256x))/4 (the paper's),\n\
u0 = exp(-(x - pi)^2) (the paper gives no u0: our choice), N = 1024, final time 36.\n\
Every option of the scene is in docs/spectral.md; the paper's experiment is\n\
examples/scenes/advection.yaml. Typical runs:\n\
  DNS:    -spectral_mode dns -ts_type rk -ts_rk_type 3 -ts_dt 1.6e-4 -output_times 9,18,27,36\n\
  sparse: -spectral_mode sparse -spectral_clusters 0:24,40:88,114:162,246:266 -ts_type rk -ts_rk_type 3 -ts_dt 1e-3\n\
  VSHMM:  -options_file_yaml examples/scenes/advection.yaml\n\
Output: -output_times t1,t2,... and -grid_solution_file PREFIX write PREFIX_<t>.txt (N lines x u(x)).\n\n";

#include "spectral_example.h"

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(RunSpectralExample("advection", 36.0));
  PetscCall(PetscFinalize());
  return 0;
}
