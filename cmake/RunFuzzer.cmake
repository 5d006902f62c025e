# One fuzzer on a budget: the repository corpus and the regression inputs (crashes found before,
# which must stay fixed) are read; new interesting inputs go to WORK/corpus; a crash leaves its
# input in WORK/ (crash-*, leak-*, timeout-*) and fails the test naming it.
# Usage: cmake -DFUZZER=... -DCORPUS=... -DREGRESSIONS=... -DWORK=... -DBUDGET=-runs=N -P RunFuzzer.cmake
foreach(v FUZZER CORPUS WORK BUDGET)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "RunFuzzer.cmake: -D${v}=... is required")
  endif()
endforeach()
if(NOT EXISTS ${FUZZER})
  message(FATAL_ERROR "${FUZZER}: missing (the fixture fuzz.build did not build it)")
endif()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/corpus)
set(dirs ${WORK}/corpus ${CORPUS})
if(DEFINED REGRESSIONS AND IS_DIRECTORY ${REGRESSIONS})
  list(APPEND dirs ${REGRESSIONS})
endif()
# Deterministic: a fixed seed; inputs up to 16 KiB; 10 s per input at most (a hang is a bug too).
execute_process(COMMAND ${FUZZER} ${BUDGET} -seed=1 -max_len=16384 -timeout=10 -rss_limit_mb=2048
                        -artifact_prefix=${WORK}/ -print_final_stats=1 ${dirs}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  file(GLOB found ${WORK}/crash-* ${WORK}/leak-* ${WORK}/timeout-* ${WORK}/oom-*)
  message(FATAL_ERROR "${FUZZER} found a failing input (exit ${rc}): ${found}\n"
                      "Reproduce: ${FUZZER} <input>; once fixed, copy the input into ${REGRESSIONS}/")
endif()
