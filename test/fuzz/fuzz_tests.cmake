# The fuzz targets in the main build's ctest: build/fuzz is configured and built by clang as a
# sub-build (ExternalProject, re-built incrementally with the main build), then every target
# runs for STICKREP_FUZZ_SECONDS from its seed corpus (label fuzz) and every input of its
# regression corpus (regressions/<target>/) is replayed. build/fuzz/targets.tsv lists each
# run's arguments for the longer run (fuzz_long.sh).
include(ExternalProject)
include(${CMAKE_CURRENT_LIST_DIR}/targets.cmake)

find_program(STICKREP_CLANGXX NAMES clang++ clang++-14)
find_program(STICKREP_CLANG NAMES clang clang-14)
set(libfuzzer "")
if(STICKREP_CLANGXX)
  execute_process(COMMAND ${STICKREP_CLANGXX} -print-file-name=libclang_rt.fuzzer-x86_64.a
                  OUTPUT_VARIABLE libfuzzer OUTPUT_STRIP_TRAILING_WHITESPACE)
endif()
if(NOT STICKREP_CLANGXX OR NOT STICKREP_CLANG OR NOT EXISTS "${libfuzzer}")
  message(FATAL_ERROR "The fuzz tests need clang with libFuzzer (Debian: clang, "
                      "libclang-rt-14-dev; deploy/setup.sh installs them). Configure with "
                      "-DSTICKREP_FUZZ_TESTS=OFF to build without them.")
endif()

set(STICKREP_FUZZ_SECONDS 20 CACHE STRING "How long ctest runs each fuzz target (seconds)")
set(fuzz_dir ${CMAKE_BINARY_DIR}/fuzz)
# -O1 with line tables: readable sanitizer reports; assertions stay on.
ExternalProject_Add(stickrep_fuzz_build
  SOURCE_DIR ${PROJECT_SOURCE_DIR}
  BINARY_DIR ${fuzz_dir}
  CMAKE_ARGS -DCMAKE_CXX_COMPILER=${STICKREP_CLANGXX} -DCMAKE_C_COMPILER=${STICKREP_CLANG}
             -DSTICKREP_FUZZ=ON -DSTICKREP_SANITIZE=address,undefined
             -DCMAKE_BUILD_TYPE=RelWithDebInfo
             "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only"
  BUILD_ALWAYS ON
  INSTALL_COMMAND ""
  USES_TERMINAL_BUILD OFF)

set(run ${CMAKE_CURRENT_LIST_DIR}/run_fuzz.sh)
set(tsv "")
foreach(t ${STICKREP_FUZZ_YAML_TARGETS} ${STICKREP_FUZZ_CDR_TARGETS})
  set(args --fuzzer ${fuzz_dir}/bin/fuzz_${t})
  if(t IN_LIST STICKREP_FUZZ_CDR_TARGETS)
    list(APPEND args --cdr-seeds)
  else()
    list(APPEND args --dict ${CMAKE_CURRENT_LIST_DIR}/yaml.dict)
    set(seeds)
    foreach(pattern ${fuzz_${t}_seeds})
      file(GLOB found ${PROJECT_SOURCE_DIR}/${pattern})
      list(APPEND seeds ${found})
    endforeach()
    if(NOT seeds)
      message(FATAL_ERROR "fuzz target ${t}: no seed file matches ${fuzz_${t}_seeds}")
    endif()
    list(APPEND args ${seeds})
  endif()
  set(regressions ${CMAKE_CURRENT_LIST_DIR}/regressions/${t})
  file(GLOB regression_inputs ${regressions}/*)
  if(regression_inputs)
    list(APPEND args --corpus-dir ${regressions})
    add_test(NAME fuzz_regressions.${t}
             COMMAND bash ${run} --fuzzer ${fuzz_dir}/bin/fuzz_${t} --replay ${regression_inputs})
    set_tests_properties(fuzz_regressions.${t} PROPERTIES LABELS fuzz TIMEOUT 120)
  endif()
  add_test(NAME fuzz.${t} COMMAND bash ${run} ${args} --work ${CMAKE_BINARY_DIR}/fuzz-runs/${t}
                                  --seconds ${STICKREP_FUZZ_SECONDS} --seed 1)
  math(EXPR timeout "${STICKREP_FUZZ_SECONDS} + 120")
  set_tests_properties(fuzz.${t} PROPERTIES LABELS fuzz TIMEOUT ${timeout})
  string(REPLACE ";" "\t" line "${t};${args}")
  string(APPEND tsv "${line}\n")
endforeach()
file(WRITE ${fuzz_dir}/targets.tsv "${tsv}")
