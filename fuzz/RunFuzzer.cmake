# Runs one fuzz target for a short fixed budget, for ctest (see fuzz/CMakeLists.txt):
#   cmake -DFUZZER=<binary> -DSEEDS=<seed dir>[|<seed dir>...] -DWORK=<scratch dir> -DRUNS=<n>
#         -DSECONDS=<cap> -P RunFuzzer.cmake
# The run starts from the seeds alone (the ones the build generates, plus the committed hand-made
# ones for fuzz_scene) with a fixed -seed, so it is repeatable; inputs it finds go to
# WORK/corpus, never into the seeds. It fails on any crash, leak, sanitizer report or input
# slower than -timeout; the reproducer is then WORK/crash-* (or leak-, timeout-, oom-): run the
# fuzzer on that file alone to see the report again.

foreach(v FUZZER SEEDS WORK RUNS SECONDS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "RunFuzzer.cmake: -D${v}=... is missing")
  endif()
endforeach()

# A missing or empty folder would only make the run start from nothing, and pass.
string(REPLACE "|" ";" seeds "${SEEDS}")
foreach(dir IN LISTS seeds)
  file(GLOB files "${dir}/*")
  if(NOT files)
    message(FATAL_ERROR "RunFuzzer.cmake: no seeds in ${dir}: build the fuzz target first "
                        "(it brings the target fuzz_<name>_seeds, which writes them)")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/corpus")
execute_process(COMMAND "${FUZZER}" -seed=1 -runs=${RUNS} -max_total_time=${SECONDS}
                        -timeout=30 -print_final_stats=1 "-artifact_prefix=${WORK}/"
                        "${WORK}/corpus" ${seeds}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (exit ${rc}); the reproducer is in ${WORK}/")
endif()
