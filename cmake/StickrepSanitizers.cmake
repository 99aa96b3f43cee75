# Sanitizers and libFuzzer instrumentation for every target of the build.
#
#   -DSTICKREP_SANITIZE=address,undefined   AddressSanitizer (with LeakSanitizer) and UBSan
#   -DSTICKREP_SANITIZE=thread              ThreadSanitizer (cannot be combined with address)
#   -DSTICKREP_FUZZ=ON                      clang only: the libFuzzer targets of test/fuzz
#
# A sanitizer report ends the program with a non-zero exit (no recovery), so a test that
# triggers one fails. Fast DDS, OpenCV and the other Debian libraries are not instrumented:
# ASan still checks every access our code makes, TSan sees only the synchronisation our
# code does (docs/reliability.md).

set(STICKREP_SANITIZE "" CACHE STRING
    "Sanitizers for every target: address, undefined, address,undefined or thread (empty: none)")

if(STICKREP_SANITIZE)
  string(REPLACE "," ";" sanitizers "${STICKREP_SANITIZE}")
  foreach(s ${sanitizers})
    if(NOT s MATCHES "^(address|undefined|thread)$")
      message(FATAL_ERROR "STICKREP_SANITIZE: unknown sanitizer '${s}' "
                          "(address, undefined, thread)")
    endif()
  endforeach()
  if("thread" IN_LIST sanitizers AND "address" IN_LIST sanitizers)
    message(FATAL_ERROR "STICKREP_SANITIZE: thread and address cannot be combined")
  endif()
  # Test names and label: asan.* (address, with or without undefined), tsan.*, ubsan.*.
  if("address" IN_LIST sanitizers)
    set(STICKREP_SANITIZE_LABEL asan)
  elseif("thread" IN_LIST sanitizers)
    set(STICKREP_SANITIZE_LABEL tsan)
  else()
    set(STICKREP_SANITIZE_LABEL ubsan)
  endif()
  set(STICKREP_TEST_PREFIX "${STICKREP_SANITIZE_LABEL}.")
  add_compile_options(-fsanitize=${STICKREP_SANITIZE} -fno-sanitize-recover=all
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${STICKREP_SANITIZE})
  message(STATUS "StickRep: sanitizers ${STICKREP_SANITIZE}")
endif()

option(STICKREP_FUZZ "Build only the libFuzzer targets (test/fuzz) and what they use; clang only"
       OFF)
if(STICKREP_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "STICKREP_FUZZ needs clang (libFuzzer): configure with "
                        "-DCMAKE_CXX_COMPILER=clang++")
  endif()
  # Coverage feedback in every library; the fuzz targets link libFuzzer's main.
  add_compile_options(-fsanitize=fuzzer-no-link)
  set(STICKREP_BUILD_TESTS OFF CACHE BOOL "" FORCE)
  set(STICKREP_BUILD_BENCHMARKS OFF CACHE BOOL "" FORCE)
endif()
