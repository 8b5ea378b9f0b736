# Stress suite (issue #5, "Hard cases stay numerically stable"): TSVSHMM on stiff dissipative
# problems with eps down to 1e-5 (stiffness ratio ~1e10) and on relaxation chains with 2 to 6
# scales, and on the resonant oscillators, each run compared with a converged reference or with
# the averaged equation.
# docs/stress.md has the parameter rules, the measured errors and the longer runs of
# tools/stress.sh. Run only these tests with `ctest -L stress`; together they take ~11 s (~15 s of CPU).
#
# Every expected file here holds REFERENCE values (converged DNS or averaged solution), not the
# VSHMM output, so ATOL is the accepted error of the slow variable at every printed time; RTOL 0
# makes the step and evaluation counts match exactly. Every VSHMM run also checks the stability of
# all levels at set-up and after every macro step (-ts_vshmm_check_stability_interval 1): a level
# whose steps leave the RK4 stability region stops the run with an error, so the test fails.
#
# Parameter rules (RK4 inner steps, stability interval [-2.785, 0] on the real axis):
#   dissipative.c, eps:  micro step dt = eps^2 (|lambda_fast| dt = 1);
#                        alpha_2 = 0.05/eps (mean h_2 = 0.05 eps; eta's field has |lambda| <= 20/eps,
#                        so the peak step 2 h_2 gives |lambda| h <= 2);
#                        rule A: alpha_1 = 0.2/eps (mean h_1 = 0.2 eps: error <= 2.8 eps),
#                        tolerance 3 eps; rule B: alpha_1 = 2e-3/eps^2 (mean h_1 = 2e-3 fixed:
#                        cost independent of eps, error <= 2.5e-2), tolerance 3e-2.
#   chain.c, e, K+1 scales: dt = e^K; alpha_j = e^(j-1)/e^K for j = 2..K (mean h_j = e_(j-1), peak
#                        |lambda| h = 2 for level j-1, whose stiffest eigenvalue is -1/e_(j-1));
#                        alpha_1 = (e/2)/e^K (mean h_1 = e/2), tolerance e = 1e-2.

set(_stress_check -ts_vshmm_check_stability_interval 1 -no_timing)

# --- dissipative.c, eps = 1e-2 ... 1e-5 -------------------------------------------------------
# Rule A, tolerance 3 eps on xi at every sample t = 0, 0.1, ..., 2 (the largest errors are at
# t = 0.1, after the fast transient). eps = 1e-2 and 5e-3 against the converged DNS
# (docs/dissipative.md), smaller eps against the averaged equation (its own error is < 2e-5 there).
vshmm_example_test(NAME stress_dissipative_eps1e-2 EXE dissipative LABELS stress
                   ARGS -eps 1e-2 -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 20,5 -print_interval 0.1 ${_stress_check}
                   OUTPUT output/dissipative_eps1e-2.out RTOL 0 ATOL 3e-2)
vshmm_example_test(NAME stress_dissipative_eps5e-3 EXE dissipative LABELS stress
                   ARGS -eps 5e-3 -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 2.5e-5 -ts_vshmm_savings_factors 40,10 -print_interval 0.1 ${_stress_check}
                   OUTPUT output/dissipative_eps5e-3.out RTOL 0 ATOL 1.5e-2)
vshmm_example_test(NAME stress_dissipative_eps1e-3 EXE dissipative LABELS stress
                   ARGS -eps 1e-3 -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-6 -ts_vshmm_savings_factors 200,50 -print_interval 0.1 ${_stress_check}
                   OUTPUT output/dissipative_eps1e-3.out RTOL 0 ATOL 3e-3)
# eps = 1e-4 on 2 ranks with additive splits (the same sampled solution as on 1 rank)
vshmm_example_test(NAME stress_dissipative_eps1e-4_np2 EXE dissipative NP 2 LABELS stress
                   ARGS -eps 1e-4 -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-8 -ts_vshmm_savings_factors 2000,500 -split_kind additive -print_interval 0.1 ${_stress_check}
                   OUTPUT output/dissipative_eps1e-4.out RTOL 0 ATOL 3e-4)
# eps = 1e-5 (stiffness ratio ~1e10, micro step 1e-10), reduced to t = 0.5 (4.8e6 split
# evaluations, ~1.5 s; tools/stress.sh runs it to t = 2), xi printed every 0.1
vshmm_example_test(NAME stress_dissipative_eps1e-5 EXE dissipative LABELS stress
                   ARGS -eps 1e-5 -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-10 -ts_vshmm_savings_factors 2e4,5e3 -ts_max_time 0.5 -print_interval 0.1 ${_stress_check}
                   OUTPUT output/dissipative_eps1e-5_t0.5.out RTOL 0 ATOL 3e-5)
# Rule B at eps = 1e-5: the fixed mean step h_1 = 2e-3 (alpha_1 = 2e7), 24,960 split evaluations
# to t = 2, about as many as for eps = 1e-3; error 2.4e-2 (at t = 0.1), tolerance 3e-2
vshmm_example_test(NAME stress_dissipative_eps1e-5_fixed_h1 EXE dissipative LABELS stress
                   ARGS -eps 1e-5 -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 1e-10 -ts_vshmm_savings_factors 2e7,5e3 -print_interval 0.1 ${_stress_check}
                   OUTPUT output/dissipative_eps1e-5_fixed_h1.out RTOL 0 ATOL 3e-2)

# --- chain.c, 2 to 6 scales, e = 1e-2 ------------------------------------------------------------
# x0 does not depend on x2..xK, so the converged DNS of the 2-scale chain (RK4, dt <= 1e-4,
# converged to 1e-10) is the exact reference for every number of scales. Tolerance e = 1e-2 on
# x0 at every sample t = 0, 0.1, ..., 2 and on the largest |x_k| over all steps.
set(_chain_rule_2 -ts_vshmm_micro_dt 1e-2 -ts_vshmm_savings_factors 0.5)
set(_chain_rule_3 -ts_vshmm_micro_dt 1e-4 -ts_vshmm_savings_factors 50,100)
set(_chain_rule_4 -ts_vshmm_micro_dt 1e-6 -ts_vshmm_savings_factors 5e3,1e4,100)
set(_chain_rule_5 -ts_vshmm_micro_dt 1e-8 -ts_vshmm_savings_factors 5e5,1e6,1e4,100)
set(_chain_rule_6 -ts_vshmm_micro_dt 1e-10 -ts_vshmm_savings_factors 5e7,1e8,1e6,1e4,100)
foreach(n 2 3 4 5 6)
  vshmm_example_test(NAME stress_chain_${n}scales EXE chain LABELS stress
                     ARGS -scales ${n} -ts_type vshmm -ts_dt 0.1 ${_chain_rule_${n}} -print_interval 0.1 ${_stress_check}
                     OUTPUT output/chain_${n}scales.out RTOL 0 ATOL 1e-2)
endforeach()
# -ts_vshmm_adapt on the 4-scale chain at tol 1e-2 (x0 observed) against the exact reference:
# measured 0.15 of the weighted tolerance 1e-2 (1 + |x0|) at most (0.21 before a macro step's first
# comparison inherited the faster levels' lag, docs/accuracy.md section 22; 0.24 before the micro step of a
# decaying fastest level kept 0.8 of its stability limit, not 0.9; 1.28 at t = 0.5 before the
# initial layer's saturation was in the error model: the layer's step was accepted above its share);
# ATOL 4.3e-2 is twice the tolerance at the smallest |x0|. The work counts must match exactly:
# 14,604 evaluations in all (14,240 before the lag; 12,576 before the layer's saturation, docs/accuracy.md section 3; 15,184 before steady steps left out their comparisons and a scheduled
# calibration at a step far below its share waited for the next step's cheaper parameters; 20,596 with the decaying pair's first ratio capped at 1 + s_l, not
# 1 + s_l / 2, and every scheduled calibration made; 40,840 before that; 76,264 when a step
# accepted above its share handed its last try's finer parameters on; docs/accuracy.md, section 3).
vshmm_example_test(NAME stress_chain_4scales_adapt EXE chain LABELS stress
                   ARGS -scales 4 -ts_type vshmm -ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -no_timing
                   OUTPUT output/chain_4scales_adapt.out RTOL 0 ATOL 4.3e-2)
# The 5-scale chain at tol 1e-2: the first macro step's retries measure the split between the
# error terms again when an estimate comes out more than twice what the model predicted (the
# stale split refined dt and every ratio together: 2.0e5 evaluations without that, 20,740 with
# it, 26,604 since the first ratio is capped at 1 + s_l / 2: the first step's retries take another
# path through the estimate's noise; 22,832 since steady steps may leave out their comparisons;
# 17,204 since a decaying fastest level's micro step keeps 0.8 of its stability limit, not 0.9;
# 17,504 later, 17,744 since a macro step's first comparison inherits the faster levels' lag,
# docs/accuracy.md section 22); measured 0.26 of the weighted tolerance at most (0.24 before).
vshmm_example_test(NAME stress_chain_5scales_adapt EXE chain LABELS stress
                   ARGS -scales 5 -ts_type vshmm -ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -no_timing
                   OUTPUT output/chain_5scales_adapt.out RTOL 0 ATOL 4.3e-2)
# The 5-scale chain at tol 1e-3 with -ts_vshmm_adapt_global_estimate: the carried comparison's
# estimate of the error at the sampled times stays below 1 tolerance (0.048 at most; true 0.082
# at most, against the chain's DNS, docs/accuracy.md section 21) and raises no warning. Converted
# by the model's factor for the carried parameters instead of each step's own (E / d), the first
# step's factor 1469 read its difference 0.037 as 54 tolerances and warned.
vshmm_example_test(NAME stress_chain_5scales_adapt_global_estimate EXE chain LABELS stress
                   ARGS -scales 5 -ts_type vshmm -ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_vshmm_adapt_global_estimate -ts_view -no_timing
                   REGEX "t 2.0000 x0 1.58.*largest 0[.][0-9]+ over the run.*adapt: global_estimate [0-9][.][0-9]+e-0[1-9] [(]the carried comparison at the last sampled time; largest [0-9][.][0-9]+e-0[1-9][)]" STDERR_REGEX "^$")
# The 2-scale chain at tol 1e-3 with the sampling interval 0.5 (-ts_dt 0.5: four macro steps): the
# first one is an initial layer taken with the micro step at its stability bound (h |lambda| = 2.2
# for x1's rate 100), whose transient it resolves badly; no comparison could coarsen that micro
# step, its term read 0, and x0(0.5) ended 3.85 tol off (8.3e-3). The first macro step now measures
# that term from the finer side (a run at 3/4 of the micro step): 0.34 tol at t = 0.5, 0.44 at most
# (docs/accuracy.md section 12). ATOL 4.3e-3 is twice the tolerance at the smallest |x0|; the work
# counts must match exactly.
vshmm_example_test(NAME stress_chain_2scales_adapt_dt0.5_tol1e-3 EXE chain LABELS stress
                   ARGS -scales 2 -ts_dt 0.5 -ts_type vshmm -ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -no_timing
                   OUTPUT output/chain_2scales_adapt_dt0.5_tol1e-3.out RTOL 0 ATOL 4.3e-3)
# -ts_view shows where adapt's error model lets each pair's term saturate: the chain's slow pair at
# r_0 - 1 = DeltaT / e = 10 (x1 relaxes at rate 100 within the macro step 0.1), the faster pairs
# at DeltaT lambda_{l+1} / (r_0 ... r_{l-1}) (1e3 with r_0 = 1 once the layer has merged the pair;
# 783 where the last calibration came while r_0 was 1.28), and the last step's r_0 = 1.
vshmm_example_test(NAME stress_chain_4scales_adapt_view EXE chain LABELS stress
                   ARGS -scales 4 -ts_type vshmm -ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -ts_view -no_timing
                   REGEX "error model: each level pair's term saturates at r_l - 1 = +10 +[0-9.e+]+ +[0-9.e+]+ +[(]- linear; time ratios of the last macro step: +1 ")
# The 6-scale chain at tol 1e-3: the initial layer (x1 relaxes at rate 100 from 0 to x0) saturates
# the slow pair's error at r_0 - 1 = DeltaT / e = 10; with that in the model the first macro step
# merges the pair and the later ones run at the levels' stability limits. Measured 0.002 of the
# weighted tolerance at most (0.11 since a retry's calibration leaves out the terms the macro
# step's last two calibrations measured below a tenth of the largest; 0.04 with 43,584 evaluations
# since a decaying fastest level's micro step keeps 0.8 of its stability limit, not 0.9), 41,656
# evaluations in all before that; its steps pinned at every bound are compared with the micro step
# at 3/4, not 1/2: 16,204 + 26,580, was + 27,380
# (73,364 with a twentieth, 122,884 measuring every term, 121,444 before steady steps left out
# their comparisons) (0.056 and 65,936 with the first ratio
# capped at 1 + s_l, not 1 + s_l / 2: ten tries of the first step now; 1.3e7 before the saturation
# was modelled; the benchmark's hand-set ladder: 1.9e4 for 6e-4); ATOL 4.3e-3 is twice the tolerance.
vshmm_example_test(NAME stress_chain_6scales_adapt_tol1e-3 EXE chain LABELS stress
                   ARGS -scales 6 -ts_type vshmm -ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -no_timing
                   OUTPUT output/chain_6scales_adapt_tol1e-3.out RTOL 0 ATOL 4.3e-3)
# the same on two ranks: the same choices, work counts and values
vshmm_example_test(NAME stress_chain_6scales_adapt_tol1e-3_np2 EXE chain NP 2 LABELS stress
                   ARGS -scales 6 -ts_type vshmm -ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -no_timing
                   OUTPUT output/chain_6scales_adapt_tol1e-3.out RTOL 0 ATOL 4.3e-3)
# 6 scales on 2 ranks, additive and component splits mixed: the same evaluation counts
vshmm_example_test(NAME stress_chain_6scales_mixed_np2 EXE chain NP 2 LABELS stress
                   ARGS -scales 6 -split_kind mixed -ts_type vshmm -ts_dt 0.1 ${_chain_rule_6} -print_interval 0.1 ${_stress_check}
                   OUTPUT output/chain_6scales.out RTOL 0 ATOL 1e-2)
# The references themselves: the DNS of the 3-scale chain (RK4, dt = 1e-4) reproduces the 2-scale
# reference to 1e-8, and the averaged equation dX/dt = sin(X) - X/2 (RK4, dt = 1e-3, converged to
# 1e-12) is within 0.8 e of it.
vshmm_example_test(NAME stress_chain_dns EXE chain LABELS stress
                   ARGS -scales 3 -ts_type rk -ts_rk_type 4 -ts_dt 1e-4 -no_timing
                   OUTPUT output/chain_dns.out RTOL 0 ATOL 1e-8)
vshmm_example_test(NAME stress_chain_averaged_np2 EXE chain NP 2 LABELS stress
                   ARGS -mode averaged -ts_type rk -ts_rk_type 4 -ts_dt 1e-3 -no_timing
                   OUTPUT output/chain_averaged.out RTOL 0 ATOL 1e-8)

# --- oscillatory.c (resonant oscillators), eps = 1e-4 ---------------------------------------------
# Reduced to t = 8 (a little more than one period, 6.86, of the slow dynamics); tools/stress.sh
# runs eps = 1e-3 and 1e-4 to t = 50.
# Reference: the averaged equations of I1, I2, the Lotka-Volterra system
# I1' = I1/2 - 3/2 I1 I2, I2' = -2 I2 + I1 I2 (RK4, step 1e-3, converged to 1e-12; within 1.1e-2
# of a converged DNS at eps = 1e-3 up to t = 50, see docs/stress.md). Rule: dt = 0.1 eps^2,
# alpha_2 = 0.1/eps, mean h_1 = 2e-4, DeltaT = 0.5; error 1.1e-2 at most, tolerance 2e-2.
# The stability check runs after every macro step here too (it needs the fix of commit ac2e5f3:
# before it, the check rejected the micro step of this problem, see docs/stress.md).
if(TARGET oscillatory)
  vshmm_example_test(NAME stress_oscillatory_eps1e-4 EXE oscillatory LABELS stress
                     ARGS -eps 1e-4 -ts_type vshmm -ts_dt 0.5 -ts_vshmm_micro_dt 1e-9 -ts_vshmm_savings_factors 2e5,1e3 -ts_max_time 8 -print_interval 1 ${_stress_check}
                     OUTPUT output/oscillatory_eps1e-4_t8.out RTOL 0 ATOL 2e-2)
endif()

# --- fpu.c: the stiff-spring Fermi-Pasta-Ulam chain (omega = 50, m = 3) with the kinematics q' = p
# in the slow split (issue 8): every level is stable alone, yet the mesoscopic steps can pump energy
# into the stiff springs. Reference: I(10) = 0.98194398275 (DNS, RK4 dt = 1e-4 and 5e-5 agree to
# 1e-11). I itself fluctuates by O(1/omega) = 2e-2 at the sampled times.
set(_fpu -ts_type vshmm -ts_dt 0.1 -ts_vshmm_micro_dt 2e-3 -no_timing -reference_I 0.98194398275)
# savings factor 0.1: I within 2.5e-2 of the DNS (measured 1.9e-2; alpha = 3 gives 0.56, alpha =
# 0.85 gives 17), and no warning from the stability checks every 10 macro steps
vshmm_example_test(NAME stress_fpu_small_savings EXE fpu LABELS stress
                   ARGS ${_fpu} -ts_vshmm_savings_factors 0.1 -ts_vshmm_check_stability_interval 10
                   VALUE_REGEX "I_error ([0-9.e+-]+)" VALUE_MAX 2.5e-2 STDERR_REGEX "^$")
# the same with the checks after every macro step: the fast split moves I at omega I and the slow
# one moves it back (the oscillation is written across the splits), so I does not turn with the
# fast level and nothing is said (judged by the fast split alone, it was said at t = 2.9)
vshmm_example_test(NAME stress_fpu_small_savings_every_step EXE fpu LABELS stress
                   ARGS ${_fpu} -ts_vshmm_savings_factors 0.1 -ts_vshmm_check_stability_interval 1
                   VALUE_REGEX "I_error ([0-9.e+-]+)" VALUE_MAX 2.5e-2 STDERR_REGEX "^$")
# savings factor 1: the composed steps grow the stiff springs' oscillation by 1.27 per macro step
# (a linear instability of the coupled levels; the run reaches I = 9e5 without the check): stopped
# at set-up by the coupled-level check, with savings factors that keep it stable
vshmm_example_test(NAME stress_fpu_coupling_unstable EXE fpu LABELS stress EXPECT_FAILURE
                   ARGS ${_fpu} -ts_vshmm_savings_factors 1
                   STDERR_REGEX "steps composed in a micro cycle grow some mode by a factor 1.2[0-9]* over a macro step \\(at most 1.05 is tolerated\\).*Savings factors 0.8[0-9]* \\(now 1")
# savings factor 3: linearly stable at every check, but the energy of the stiff springs grows (I
# ends at 1.54): the fast-energy check warns (growth 6 by t = 5, the warning threshold is 4)
vshmm_example_test(NAME stress_fpu_fast_energy_warning EXE fpu LABELS stress
                   ARGS ${_fpu} -ts_vshmm_savings_factors 3 -ts_vshmm_check_stability_interval 10
                   STDERR_REGEX "energy of the fastest scale's oscillation \\(split fast, frequency 50[.0-9]*\\) has grown by a factor [4-9]")
# -ts_vshmm_adapt at tol 1e-2 (observables I, H): any savings shift the fast phase that I carries,
# so the run takes none (a time ratio below 1.05 is dropped for the rest of the solve): error 8.2e-3
# in 17,252 split evaluations. Without that rule the ratios fall geometrically and the micro step
# with them: 2.9e-2 in 13 million evaluations.
vshmm_example_test(NAME stress_fpu_adapt EXE fpu LABELS stress
                   ARGS -ts_type vshmm -ts_dt 0.1 -ts_vshmm_adapt -ts_rtol 1e-2 -ts_atol 1e-2 -no_timing -reference_I 0.98194398275
                   VALUE_REGEX "I_error ([0-9.e+-]+)" VALUE_MAX 2e-2)
# the same on the whole state (-observe_state) at 1e-3: the state holds the stiff springs' phase,
# whose RK4 lag adds up over the 100 macro steps; the micro step is bounded by it (the state within
# 0.81 tol of the DNS, I within 1.03e-3; 0.79 and 1.01e-3 before the four phases of
# docs/accuracy.md section 25). With the amplitude error alone the comparisons' estimates,
# shared out for errors of random sign, summed to 2.1 and the state ended 3.6 tol off (I 6.5e-3).
vshmm_example_test(NAME stress_fpu_adapt_whole_state EXE fpu LABELS stress
                   ARGS -ts_type vshmm -ts_dt 0.1 -ts_vshmm_adapt -ts_rtol 1e-3 -ts_atol 1e-3 -observe_state -no_timing -reference_I 0.98194398275
                   VALUE_REGEX "I_error ([0-9.e+-]+)" VALUE_MAX 3e-3)
