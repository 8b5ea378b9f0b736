# CTest runs of examples/ode/dissipative.c (included by the top-level CMakeLists.txt;
# vshmm_example_test() is in cmake/VSHMMTesting.cmake). Expected outputs are in output/. Every run passes
# -no_timing so that its output is deterministic. Numbers are compared by tests/numdiff.sh:
# |a - b| <= ATOL or |a - b| <= RTOL max(|a|,|b|); with RTOL 0 the step and evaluation counts
# must match exactly. Total time of these tests: a few seconds (the DNS runs take ~1 s each).
#
# Reference values (docs/dissipative.md): the converged DNS of the dissipative example,
# eps = 1e-2, x0 = (5,-10,5), RK4 refined from dt = 1e-5 to 6.25e-7 (4th order, converged to
# ~1e-11): xi(0.5) = 3.5919081136, xi(1) = 2.5925732631, xi(1.5) = 1.7508010332,
# xi(2) = 1.4816640204.

set(_diss_vshmm -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-4)

# DNS with RK4, dt = 1e-5 (stable: dt < ~2.8e-4): within 2e-8 of the converged reference
# (expected file = the reference values; the dt = 1e-5 run differs from it by < 1e-9).
foreach(np 1 2)
  set(_sfx "")
  if(np GREATER 1)
    set(_sfx _np${np})
  endif()
  vshmm_example_test(NAME dissipative_dns${_sfx} EXE dissipative NP ${np}
                     ARGS -ts_type rk -ts_rk_type 4 -ts_dt 1e-5 -no_timing
                     OUTPUT output/dissipative_dns.out RTOL 0 ATOL 2e-8)
  # The averaged equation dXi/dt = sin(2 Xi) - Xi^2/5 (on 2 ranks one rank owns nothing):
  # RK4 dt = 1e-3, within 2e-8 of its converged values.
  vshmm_example_test(NAME dissipative_averaged${_sfx} EXE dissipative NP ${np}
                     ARGS -mode averaged -ts_type rk -ts_rk_type 4 -ts_dt 1e-3 -no_timing
                     OUTPUT output/dissipative_averaged.out RTOL 0 ATOL 2e-8)
endforeach()

# VSHMM with the paper's parameters (dt = 1e-4, alpha = 100,10, DeltaT = 0.1), component and
# additive splits, 1 and 2 ranks: all four must reproduce the same sampled solution (and the same
# 4320 split evaluations). The expected values agree to 10 digits with an independent plain-C
# implementation of the method. They are NOT within 2e-2 of the DNS at every sampled time:
# with alpha_1 = 100 the method's own error is 0.12, 0.15, 0.05, 0.008 at t = 0.5, 1, 1.5, 2.
foreach(kind component additive)
  foreach(np 1 2)
    vshmm_example_test(NAME dissipative_vshmm_${kind}_np${np} EXE dissipative NP ${np}
                       ARGS ${_diss_vshmm} -ts_vshmm_savings_factors 100,10 -split_kind ${kind} -no_timing
                       OUTPUT output/dissipative_vshmm_paper.out RTOL 1e-7 ATOL 1e-9)
  endforeach()
endforeach()

# Accuracy against the converged DNS (expected files hold the DNS reference values), ATOL 2e-2:
# - the paper's parameters at the final time t = 2 (error 8.1e-3);
vshmm_example_test(NAME dissipative_vshmm_paper_vs_dns EXE dissipative NP 1
                   ARGS ${_diss_vshmm} -ts_vshmm_savings_factors 100,10 -print_interval 2 -no_timing
                   OUTPUT output/dissipative_vshmm_paper_vs_dns.out RTOL 0 ATOL 2e-2)
# - smaller savings factors alpha = 20,5 at every printed time (max error 1.2e-2 at t = 1).
vshmm_example_test(NAME dissipative_vshmm_alpha20_vs_dns_np2 EXE dissipative NP 2
                   ARGS ${_diss_vshmm} -ts_vshmm_savings_factors 20,5 -split_kind additive -no_timing
                   OUTPUT output/dissipative_vshmm_alpha20_vs_dns.out RTOL 0 ATOL 2e-2)

# Accuracy on request: -ts_vshmm_adapt with -ts_rtol = -ts_atol = 1e-2 on xi (the example's
# observable), against the converged DNS (expected file = the reference values): measured errors
# 0.49 of the weighted tolerance 1e-2 (1 + |xi|) at most (0.55 before a macro step's first comparison
# inherited the faster levels' lag, docs/accuracy.md section 22; 0.13 before the first macro step measured
# the micro step's term from the finer side, docs/accuracy.md section 12; 0.31 before the micro step of a decaying
# fastest level kept 0.8 of its stability limit, not 0.9); ATOL 4.9e-2 is twice the tolerance at the
# smallest |xi|. The work counts must match exactly (26,472 split evaluations in all; 22,716 before
# the lag; 16,468 before
# the finer side; 16,412 before
# that; 17,256 before
# the stable steps were estimated again after the first macro step as well; 17,480 with
# the decaying pair's first ratio capped at 1 + s_l, not 1 + s_l / 2; 34,636 with at
# least 20 micro cycles per macro step and the first ratios at sigma 10, 166,704 before the levels'
# stable steps were estimated again at each calibration, docs/accuracy.md).
vshmm_example_test(NAME dissipative_vshmm_adapt_vs_ref EXE dissipative NP 1
                   ARGS -ts_type vshmm -ts_dt 0.1 -ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -no_timing
                   OUTPUT output/dissipative_vshmm_adapt_vs_ref.out RTOL 0 ATOL 4.9e-2)

# PETSc's own allocations are all freed at PetscFinalize: -malloc_dump prints nothing more.
vshmm_example_test(NAME dissipative_vshmm_malloc_dump EXE dissipative NP 1
                   ARGS ${_diss_vshmm} -ts_vshmm_savings_factors 100,10 -no_timing -malloc_debug -malloc_dump
                   OUTPUT output/dissipative_vshmm_paper.out RTOL 1e-7 ATOL 1e-9)

# Bad input to the ODE examples: a clear error naming the option (PETSc's readers accept inf and
# would drop extra -x0 values).
vshmm_mpiexec_command(_ode_launch 1)
function(_ode_error_test name exe regex)
  add_test(NAME ode_error_${name} COMMAND ${_ode_launch} $<TARGET_FILE:${exe}> ${ARGN})
  set_tests_properties(ode_error_${name} PROPERTIES PASS_REGULAR_EXPRESSION "${regex}" LABELS example TIMEOUT 60)
endfunction()
_ode_error_test(dissipative_eps_inf dissipative "-eps must be positive and finite, got inf" -eps inf)
_ode_error_test(dissipative_x0_extra dissipative "-x0 takes 3 values xi,eta,zeta, got more than 3" -x0 1,2,3,4)
_ode_error_test(dissipative_x0_short dissipative "-x0 takes 3 values xi,eta,zeta, got 2" -x0 1,2)
_ode_error_test(dissipative_x0_nan dissipative "-x0 value 2 is nan.*: the initial state must be finite" -x0 1,nan,3)
_ode_error_test(oscillatory_eps_inf oscillatory "-eps must be positive and finite, got inf" -eps inf)
_ode_error_test(oscillatory_x0_extra oscillatory "-x0 takes 4 values x1,x2,y1,y2, got more than 4" -x0 1,2,3,4,5)
_ode_error_test(chain_x0_extra chain "-x0 takes 1 to 3 values x0,...,xK, got more than 3" -scales 3 -x0 1,2,3,4)
# A macro step's first comparison inherits the faster levels' lag (docs/accuracy.md section 22), and
# -ts_view says on which components: with additive splits (every split returns a full-size term)
# those where the slowest field is zero and a faster one is not, here eta and zeta. At eps = 3e-3,
# tol 3e-3, xi(1.7) = 1.600869 against RK4's 1.6005409 (dt = eps^2 / 8 and / 16 agree to 1e-10):
# 0.04 tol (2.38 tol before, silently).
vshmm_example_test(NAME dissipative_vshmm_adapt_lag_additive_view EXE dissipative NP 1
                   ARGS -ts_type vshmm -eps 3e-3 -ts_vshmm_adapt -ts_rtol 3e-3 -ts_atol 3e-3 -ts_max_time 1.7 -print_interval 0.1 -split_kind additive -ts_view -no_timing
                   REGEX "t 1.7000 xi 1.60[0-9]*e[+]00.*first comparison starts from the last one's end state on the 2 components only faster levels write [(]seen from the fields' values")
# A decaying pair less than 2 apart among separated ones takes no savings, and -ts_view says so:
# at eps = 3e-2 the medium and fast levels are 1.31 apart (slow/medium 667); tol 3e-3, xi
# observed: 4,420 + 8,516 split evaluations (4,344 + 8,276 before the growth probe of docs/accuracy.md
# section 35, which measures an error growing 1.10-1.13 times per macro step at t = 0.6-0.9, shrinks
# the later shares, and finds 0.82 at t = 1.4 (-ts_view: two probes, the last found none); 5,128 + 9,216 before a macro step's first comparison
# inherited the faster levels' lag, docs/accuracy.md section 22; 4,980 + 8,864 before the decaying medium level's rate
# was followed too, docs/accuracy.md section 17: it fell by half at t = 1.5; 7,472 + 7,900 before the stable steps were also
# estimated at the end of a first try whose fast rate grew; 4,784 + 7,692 before the first macro
# step measured the micro step's term from the finer side; 3.6e5 when the pair's ratio was left to
# the choice), xi(2) = 1.480474 (1.480843 before the probe, 1.481299 before the lag, 1.481651 before that) against RK4's 1.48150 (dt 5e-5; 1e-4 agrees to 2e-9): 0.14 tol (0.09 before the probe).
vshmm_example_test(NAME dissipative_vshmm_adapt_unseparated_pair_view EXE dissipative NP 1
                   ARGS -ts_type vshmm -eps 3e-2 -ts_vshmm_adapt -ts_rtol 3e-3 -ts_atol 3e-3 -ts_view -no_timing
                   REGEX "the slow dynamics do not grow an error [(]a growing mode of the slowest level's Jacobian, probed 2 times: the last probe found none[)].*levels 1/2: no savings between them [(]they are 1.31 apart, less than 2, and the faster only decays[)].*final t 2.0000 xi 1.48[01][0-9]*e[+]00\nrhs_evaluations 4420\n")
# -ts_adapt_monitor (PETSc's option for adaptive controllers) prints a line per try of a macro step
# that got an error estimate, what became of it and its parameters: the first step, an initial
# layer, refined twice; on two ranks once (the next line is the next step's, not a copy)
foreach(_np 1 2)
  vshmm_example_test(NAME dissipative_vshmm_adapt_monitor_np${_np} EXE dissipative NP ${_np}
                     ARGS -ts_type vshmm -ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -ts_adapt_monitor -ts_max_time 0.3 -no_timing
                     REGEX "TSAdapt vshmm: step +0 rejected t=0 +[+] 1.000e-01 try 1 estimate 6.56[0-9]e[+]00 of its share 5.774e-01 [(]11.4[)], micro step [0-9.]+e-04, time ratios [0-9.]+,[0-9.]+, 6 micro cycles\n[^\n]*step +0 rejected[^\n]*\n[^\n]*step +0 accepted t=0 [^\n]*try 3 [^\n]*\n[^\n]*step +1 accepted t=0.1 [^\n]*\n[^\n]*step +2 accepted t=0.2 ")
endforeach()
