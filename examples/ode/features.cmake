# End-to-end runs of features that otherwise rest on unit tests alone (issue 12): subintervals
# m_j > 1, every kernel chosen by option, scales made of groups of splits. Each expected file is
# the run's own sampled solution and evaluation count (regression, RTOL 1e-7: the count must
# match exactly); the comments give each run's error against the converged reference. About 2 s
# in all. Included by the top-level CMakeLists.txt; vshmm_example_test() is in
# cmake/VSHMMTesting.cmake.
#
# Dissipative example (examples/ode/dissipative.c), the paper's dt = 1e-4, alpha = 100,10,
# DeltaT = 0.1. Errors of xi against the converged DNS (docs/dissipative.md) at t = 0.5, 1, 1.5, 2:
#   cosine (the default)       0.117 0.149 0.048 0.008   4320 split evaluations
#   constant                   0.152 0.189 0.066 0.015   4560
#   polynomial, order 3        0.103 0.131 0.039 0.005   3840
#   exponential                0.255 0.303 0.099 0.022   3360
#   cosine, subintervals 2,4   0.160 0.201 0.066 0.013   3840
set(_feat_diss -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 100,10 -no_timing)
foreach(kernel cosine constant polynomial exponential)
  set(_order)
  if(kernel STREQUAL "polynomial")
    set(_order -ts_vshmm_kernel_order 3)
  endif()
  vshmm_example_test(NAME features_kernel_${kernel} EXE dissipative NP 1
                     ARGS ${_feat_diss} -ts_vshmm_kernel ${kernel} ${_order}
                     OUTPUT output/dissipative_kernel_${kernel}.out RTOL 1e-7 ATOL 1e-9)
endforeach()
# the exponential kernel on 2 ranks with additive splits: the same solution
vshmm_example_test(NAME features_kernel_exponential_np2 EXE dissipative NP 2
                   ARGS ${_feat_diss} -ts_vshmm_kernel exponential -split_kind additive
                   OUTPUT output/dissipative_kernel_exponential.out RTOL 1e-7 ATOL 1e-9)
foreach(np 1 2)
  vshmm_example_test(NAME features_subintervals_np${np} EXE dissipative NP ${np}
                     ARGS ${_feat_diss} -ts_vshmm_subintervals 2,4
                     OUTPUT output/dissipative_subintervals_2_4.out RTOL 1e-7 ATOL 1e-9)
endforeach()

# Split groups: the 4-scale relaxation chain (examples/stress/chain.c, e = 1e-2) run as three
# scales, the two fastest splits in one: -ts_vshmm_splits s0,s1,s2+s3. The micro step 1e-6
# resolves e_3 = 1e-6; mean h_2 = 1e-2 = e_1, mean h_1 = 5e-3 (stress.cmake's rule for 4 scales
# without its third factor). x0 against the converged reference (stress/output/chain_4scales.out):
# error 4.7e-3 at t = 1, 3.4e-3 at t = 2. Stability checked after every macro step. On 2 ranks
# with additive and component splits mixed: the same solution and counts.
set(_feat_chain -scales 4 -ts_vshmm_splits s0,s1,s2+s3 -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-6
                -ts_vshmm_savings_factors 5e3,1e4 -print_interval 0.5 -ts_vshmm_check_stability_interval 1 -no_timing)
if(TARGET chain)
  vshmm_example_test(NAME features_split_groups EXE chain NP 1 ARGS ${_feat_chain}
                     OUTPUT output/chain_split_groups.out RTOL 1e-7 ATOL 1e-9)
  vshmm_example_test(NAME features_split_groups_mixed_np2 EXE chain NP 2 ARGS ${_feat_chain} -split_kind mixed
                     OUTPUT output/chain_split_groups.out RTOL 1e-7 ATOL 1e-9)
endif()
