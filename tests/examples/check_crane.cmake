# Runs the crane example and checks what it reports (cmake -P, so the test compiles nothing):
# the far-field stress at rest against beam theory (DESIGN's sanity figure: moment about
# 2.9 kNm at the detail, sigma = M c / I), a hot spot above the nominal stress, finite results,
# determinism (two runs write bit-identical histories), the energy balance of the work cycle
# (work-energy theorem: |E - E0 - W_driver + D_damping| at most 1e-3 of max |E - E0|, and
# smaller at h = 1 ms than at 2 ms), a looser Newton tolerance, other mode counts (one with
# fixed-size kernels, one with the bounded ones), the hydraulic drive (its stroke within 10 % of the planned 0.2 m lift, its energy balance with the
# oil force's work), the batch of operators (parallel equals serial), the game loop (rendering
# does not change the physics), the crane from C (the exported crane built and run through
# flexstress.h by c_api/demo.c), and bad options' messages.
#   cmake -DCRANE=<exe> -DOUT=<dir> [-DCRANE_C_DEMO=<exe>] -P check_crane.cmake
foreach(run 1 2)
  execute_process(COMMAND "${CRANE}" --quiet --output "${OUT}/run${run}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "crane run ${run} failed (${rc}):\n${out}\n${err}")
  endif()
endforeach()
message(STATUS "${out}")
function(key name var)
  if(NOT out MATCHES "\n${name}: ([-+0-9.eE]+)")
    message(FATAL_ERROR "crane did not report '${name}'")
  endif()
  set(${var} "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()
key(static_nominal_MPa nominal)
key(beam_theory_nominal_MPa theory)
key(hotspot_max_MPa hot_max)
key(static_hotspot_MPa hot_rest)
key(steps steps)
key(energy_balance_rel balance)
key(energy_balance_J balance_j)
key(damage_per_cycle damage_single)
# |nominal - theory| < 5 % of theory (the joints and the payload's point mass make the boom
# differ slightly from a cantilever; measured 2.6 %). CMake has no floating point: whole MPa.
string(REGEX REPLACE "\\..*" "" n_int "${nominal}")
string(REGEX REPLACE "\\..*" "" t_int "${theory}")
math(EXPR diff "${n_int} - ${t_int}")
if(diff LESS 0)
  math(EXPR diff "-${diff}")
endif()
math(EXPR limit "(-${t_int}) / 20 + 1")
if(diff GREATER limit)
  message(FATAL_ERROR "nominal stress at rest ${nominal} MPa vs beam theory ${theory} MPa")
endif()
string(REGEX REPLACE "\\..*" "" hot_int "${hot_rest}")
math(EXPR minus_nominal "-${n_int}")
if(NOT hot_int GREATER minus_nominal)
  message(FATAL_ERROR "hot spot at rest ${hot_rest} MPa not above the nominal ${nominal} MPa")
endif()
if(NOT steps EQUAL 11000)
  message(FATAL_ERROR "expected 11000 steps, got ${steps}")
endif()
file(SHA256 "${OUT}/run1/crane_history.csv" h1)
file(SHA256 "${OUT}/run2/crane_history.csv" h2)
if(NOT h1 STREQUAL h2)
  message(FATAL_ERROR "two runs wrote different histories")
endif()
if(NOT balance LESS 1e-3)
  message(FATAL_ERROR "energy balance off by ${balance} of the energy the cycle moves")
endif()

# Halving the step from 2 ms must shrink the balance's residual (second order: measured 4x from
# 4 ms to 2 ms and 2.9x from 2 ms to 1 ms; below 1 ms the Newton tolerance dominates).
function(run_crane name)
  execute_process(COMMAND "${CRANE}" --quiet --output "${OUT}/${name}" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE run_out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "crane ${ARGN} failed (${rc}):\n${run_out}\n${err}")
  endif()
  set(out "${run_out}" PARENT_SCOPE)
endfunction()
run_crane(h2ms --step 0.002)
key(energy_balance_J balance_j_2ms)
if(NOT balance_j LESS balance_j_2ms)
  message(FATAL_ERROR "energy residual ${balance_j} J at h = 1 ms, not below ${balance_j_2ms} J at 2 ms")
endif()
# A looser Newton tolerance (--tolerance 1e-3, the pick of docs/accuracy-vs-time.md) must give
# the same hot-spot maximum and damage to the printed digits and still balance the energy
# (measured: the hot-spot history moves by 2e-4 MPa of its 19 MPa range, the balance 1e-5).
run_crane(tolerance --tolerance 1e-3)
key(hotspot_max_MPa hot_max_tolerance)
key(damage_per_cycle damage_tolerance)
key(energy_balance_rel balance_tolerance)
if(NOT hot_max_tolerance STREQUAL hot_max OR NOT damage_tolerance STREQUAL damage_single
   OR NOT balance_tolerance LESS 1e-3)
  message(FATAL_ERROR "--tolerance 1e-3: hot spot max ${hot_max_tolerance} MPa (${hot_max}), "
                      "damage ${damage_tolerance} (${damage_single}), balance ${balance_tolerance}")
endif()
# A real-time budget of two Newton iterations (docs/dynamics.md, "A real-time budget") runs the
# whole cycle, and its hot-spot maximum and damage are the converged run's to the printed digits
# (measured: 4742 steps end at the budget; the hot-spot history stays within 0.0081 MPa).
run_crane(budget2 --newton-budget 2)
key(steps steps_budget)
key(hotspot_max_MPa hot_max_budget)
key(damage_per_cycle damage_budget)
if(NOT steps_budget EQUAL 11000 OR NOT hot_max_budget STREQUAL hot_max
   OR NOT damage_budget STREQUAL damage_single)
  message(FATAL_ERROR "--newton-budget 2: ${steps_budget} steps, hot spot max ${hot_max_budget} "
                      "MPa (${hot_max}), damage ${damage_budget} (${damage_single})")
endif()
# Other mode counts from the same build: 16 (kernels of a fixed size) and 13 (the bounded ones).
# docs/accuracy-vs-time.md: 16 modes are within 0.1 % of the converged hot-spot history, 10
# within 2.4 %; 13 lies between.
foreach(modes 16 13)
  run_crane(modes${modes} --modes ${modes})
  key(steps steps)
  key(energy_balance_rel balance)
  key(hotspot_max_MPa hot_max_modes)
  set(hot_max_${modes} "${hot_max_modes}")  # for the crane from C
  key(damage_per_cycle damage_${modes})
  string(REGEX REPLACE "\\..*" "" hm_int "${hot_max_modes}")
  string(REGEX REPLACE "\\..*" "" h10_int "${hot_max}")
  math(EXPR hm_diff "${hm_int} - ${h10_int}")
  if(hm_diff LESS 0)
    math(EXPR hm_diff "-${hm_diff}")
  endif()
  math(EXPR hm_limit "${h10_int} * 5 / 100 + 1")
  if(NOT steps EQUAL 11000 OR NOT balance LESS 1e-3 OR hm_diff GREATER hm_limit)
    message(FATAL_ERROR "--modes ${modes}: ${steps} steps, energy balance ${balance}, hot spot "
                        "max ${hot_max_modes} MPa (10 modes: ${hot_max})")
  endif()
endforeach()
execute_process(COMMAND "${CRANE}" --modes 99 RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "--modes: a boom mode count from 1 to 64, got '99'")
  message(FATAL_ERROR "--modes 99 should fail naming the option and the range (exit ${rc}): ${err}")
endif()
# The far end driven by the boom's section force (--force-driven): a brick model of the whole
# boom (bench/accuracy_vs_time/whole_boom.cpp) puts the paper's displacement-driven hot spot 11 %
# high at the static pose and this one 3 % high, so it must read lower, by about 7 %.
run_crane(force_driven --force-driven)
key(steps steps_force)
key(static_hotspot_MPa hot_rest_force)
string(REGEX REPLACE "\\..*" "" hot_rest_int "${hot_rest}")
math(EXPR low "${hot_rest_int} * 90 / 100")
math(EXPR high "${hot_rest_int} * 96 / 100")
if(NOT steps_force EQUAL 11000 OR hot_rest_force LESS low OR hot_rest_force GREATER high)
  message(FATAL_ERROR "--force-driven: ${steps_force} steps, static hot spot ${hot_rest_force} MPa, "
                      "expected 90-96 % of the displacement-driven ${hot_rest} MPa")
endif()
run_crane(hydraulic --hydraulic)
key(steps steps)
key(energy_balance_rel balance)
key(hydraulic_stroke_max_m lift)
if(NOT steps EQUAL 11000 OR NOT balance LESS 1e-3 OR lift LESS 0.18 OR lift GREATER 0.22)
  message(FATAL_ERROR "--hydraulic: ${steps} steps, energy balance ${balance}, lift ${lift} m")
endif()

# The batch of operators (--operators): two threads give the serial results line for line and
# file for file, a range of operators run alone gives the same lines as in the whole batch (how a
# job array splits a campaign), and operator 0, who drives the base cycle, has the single run's
# damage.
function(operator_lines var)
  string(REGEX MATCHALL "  operator [0-9]+: [^\n]*" lines "${out}")
  set(${var} "${lines}" PARENT_SCOPE)
endfunction()
run_crane(operators_serial --operators 4 --threads 1)
operator_lines(serial)
run_crane(operators_parallel --operators 4 --threads 2)
operator_lines(parallel)
key(threads threads)
run_crane(operators_range --operators 2 --first-operator 2)
operator_lines(range)
list(LENGTH serial n)
list(SUBLIST serial 2 2 serial_tail)
list(GET serial 0 operator0)
file(SHA256 "${OUT}/operators_serial/operators.csv" c1)
file(SHA256 "${OUT}/operators_parallel/operators.csv" c2)
if(NOT n EQUAL 4 OR NOT threads EQUAL 2 OR NOT serial STREQUAL parallel OR NOT c1 STREQUAL c2)
  message(FATAL_ERROR "--operators 4: serial and parallel batches differ (threads ${threads}):\n"
                      "${serial}\n${parallel}")
endif()
if(NOT range STREQUAL serial_tail)
  message(FATAL_ERROR "operators 2 and 3 run alone differ from the whole batch:\n${range}\n${serial_tail}")
endif()
if(NOT operator0 MATCHES "damage per cycle ${damage_single}$")
  message(FATAL_ERROR "operator 0 drives the base cycle: damage ${damage_single} expected: ${operator0}")
endif()
message(STATUS "operators:\n${out}")

# The game loop (--game-loop): frames at 60 Hz with jitter, fixed steps of 1 ms in between.
# The rendering must not change the physics: the same 11000 steps and the single run's damage.
run_crane(game_loop --game-loop)
key(steps loop_steps)
key(frames frames)
key(max_steps_per_frame most_steps)
key(damage_per_cycle loop_damage)
if(NOT loop_steps EQUAL 11000 OR NOT loop_damage STREQUAL damage_single OR frames LESS 600 OR
   frames GREATER 720 OR most_steps GREATER 23 OR NOT EXISTS "${OUT}/game_loop/game_loop.csv")
  message(FATAL_ERROR "--game-loop: ${loop_steps} steps, ${frames} frames, up to ${most_steps} "
                      "steps a frame, damage ${loop_damage} (single run ${damage_single})")
endif()

# The crane from C (c_api/demo.c on flexstress.h alone): the crane exported as files, built and
# run by the C program, must give the program's single run: the same 11000 steps, hot-spot
# maximum and damage to the printed digits; and the 16-mode export the 16-mode run's figures
# (the boom file keeps the modes asked). A folder without the files is refused, naming the file.
if(CRANE_C_DEMO)
  function(run_c_demo name)
    execute_process(COMMAND "${CRANE}" --export-c-model "${OUT}/${name}" ${ARGN}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE export_out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0 OR NOT EXISTS "${OUT}/${name}/boom.fsmodal")
      message(FATAL_ERROR "crane --export-c-model ${ARGN} failed (${rc}):\n${export_out}\n${err}")
    endif()
    execute_process(COMMAND "${CRANE_C_DEMO}" "${OUT}/${name}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE c_out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "crane_c_demo ${name} failed (${rc}):\n${c_out}\n${err}")
    endif()
    set(out "${c_out}" PARENT_SCOPE)
  endfunction()
  run_c_demo(c_model)
  key(steps c_steps)
  key(hotspot_max_MPa c_hot_max)
  key(damage_per_cycle c_damage)
  if(NOT c_steps EQUAL 11000 OR NOT c_hot_max STREQUAL hot_max OR NOT c_damage STREQUAL damage_single)
    message(FATAL_ERROR "the C program differs from the crane program: ${c_steps} steps, hot spot "
                        "max ${c_hot_max} (${hot_max}), damage ${c_damage} (${damage_single}):\n${out}")
  endif()
  message(STATUS "crane from C:\n${out}")
  run_c_demo(c_model16 --modes 16)
  key(hotspot_max_MPa c_hot_max_16)
  key(damage_per_cycle c_damage_16)
  if(NOT out MATCHES "a boom of 16 modes" OR NOT c_hot_max_16 STREQUAL hot_max_16
     OR NOT c_damage_16 STREQUAL damage_16)
    message(FATAL_ERROR "the C program at 16 modes differs: hot spot max ${c_hot_max_16} "
                        "(${hot_max_16}), damage ${c_damage_16} (${damage_16}):\n${out}")
  endif()
  execute_process(COMMAND "${CRANE_C_DEMO}" "${OUT}/no-such-model"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "cannot open [^\n]*no-such-model/crane.txt")
    message(FATAL_ERROR "crane_c_demo on a missing folder should fail naming crane.txt (exit ${rc}): "
                        "${err}")
  endif()
endif()

# Bad flags and bad stroke files: a message naming the flag or the line, a non-zero exit.
function(expect_refusal pattern)
  execute_process(COMMAND "${CRANE}" --quiet --output "${OUT}/refused" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "crane ${ARGN} should fail with '${pattern}' (exit ${rc}): ${err}")
  endif()
endfunction()
expect_refusal("unknown option '--speed'" --speed 2)
expect_refusal("--payload expects a number, got 'heavy'" --payload heavy)
expect_refusal("bad value '-5' for --payload" --payload -5)
expect_refusal("bad value '0' for --step" --step 0)
expect_refusal("bad value '0' for --tolerance" --tolerance 0)
expect_refusal("bad value '0' for --operators" --operators 0)
expect_refusal("--operators drives the stroke; it has no --hydraulic form" --operators 2 --hydraulic)
expect_refusal("--game-loop and --operators are separate runs" --game-loop --operators 2)
expect_refusal("--export-c-model writes the stroke-driven crane; it has no --hydraulic"
               --export-c-model "${OUT}/refused-c-model" --hydraulic)
expect_refusal("bad value '0' for --render-hz" --render-hz 0)
expect_refusal("--density needs a value" --density)
expect_refusal("cannot open stroke file" --stroke "${OUT}/no-such-cycle.csv")
file(WRITE "${OUT}/bad-cycle.csv" "time,stroke\n0,0\n1,0.1\n2,oops\n")
expect_refusal("bad-cycle.csv line 4: expected 'time,stroke', got '2,oops'"
               --stroke "${OUT}/bad-cycle.csv")
file(WRITE "${OUT}/short-cycle.csv" "0,0\n")
expect_refusal("short-cycle.csv: needs at least two rows" --stroke "${OUT}/short-cycle.csv")
file(WRITE "${OUT}/long-cycle.csv" "0,0\n1,0.1\n2,5\n")
expect_refusal("long-cycle.csv line 3: stroke 5 m takes the piston out of the cylinder"
               --stroke "${OUT}/long-cycle.csv")
file(WRITE "${OUT}/backwards-cycle.csv" "0,0\n1,0.1\n0.5,0.2\n")
expect_refusal("time at row 3 \\(0.5\\) does not increase" --stroke "${OUT}/backwards-cycle.csv")
