# Runs one fuzz target for a short fixed budget, for ctest (see fuzz/CMakeLists.txt):
#   cmake -DFUZZER=<binary> -DSEEDS=<seed dir> -DWORK=<scratch dir> -DRUNS=<n> -DSECONDS=<cap>
#         -P RunFuzzer.cmake
# The run starts from the committed seeds alone with a fixed -seed, so it is repeatable; inputs
# it finds go to WORK/corpus, never into the seeds. It fails on any crash, leak, sanitizer
# report or input slower than -timeout; the reproducer is then WORK/crash-* (or leak-, timeout-,
# oom-): run the fuzzer on that file alone to see the report again.

foreach(v FUZZER SEEDS WORK RUNS SECONDS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "RunFuzzer.cmake: -D${v}=... is missing")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/corpus")
execute_process(COMMAND "${FUZZER}" -seed=1 -runs=${RUNS} -max_total_time=${SECONDS}
                        -timeout=30 -print_final_stats=1 "-artifact_prefix=${WORK}/"
                        "${WORK}/corpus" "${SEEDS}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (exit ${rc}); the reproducer is in ${WORK}/")
endif()
