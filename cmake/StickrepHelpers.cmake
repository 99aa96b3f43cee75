# Small helpers so every folder declares its targets the same way.

# stickrep_add_library(NAME SOURCES ... [DEPS ...])
# A static library whose headers are included as "<folder>/<file>.h" from components/.
function(stickrep_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/components)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  target_compile_definitions(${name} PRIVATE STICKREP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endfunction()

# AddressSanitizer's defaults (cmake/sanitizer_options.cpp) in an executable of an ASan build.
function(stickrep_add_sanitizer_options name)
  if(STICKREP_SANITIZE MATCHES "address")
    target_sources(${name} PRIVATE ${PROJECT_SOURCE_DIR}/cmake/sanitizer_options.cpp)
  endif()
endfunction()

# stickrep_add_gtest(NAME SOURCES ... [DEPS ...] [LABELS ...])
# A GoogleTest executable in build/bin whose tests are registered one by one with ctest.
function(stickrep_add_gtest name)
  if(NOT STICKREP_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "SERIAL" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE STICKREP_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                             STICKREP_BINARY_DIR="${CMAKE_BINARY_DIR}")
  stickrep_add_sanitizer_options(${name})
  set(serial FALSE)
  if(ARG_SERIAL)
    set(serial TRUE)
  endif()
  # Under sanitizers the tests are named asan.* or tsan.* and labelled so: the main build's
  # ctest may run them beside its own (STICKREP_EXTRA_TEST_DIRS), so their gtest temporary
  # files go to a directory of their own build.
  set(labels "${ARG_LABELS}")
  set(tmp_dir /tmp)
  if(STICKREP_SANITIZE)
    if(NOT labels)
      set(labels ${STICKREP_SANITIZE_LABEL})
    endif()
    set(tmp_dir ${CMAKE_BINARY_DIR}/test-tmp)
    file(MAKE_DIRECTORY ${tmp_dir})
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 TEST_PREFIX "${STICKREP_TEST_PREFIX}"
    PROPERTIES LABELS "${labels}" RUN_SERIAL ${serial} ENVIRONMENT "TEST_TMPDIR=${tmp_dir}")
endfunction()

# stickrep_add_benchmark(NAME SOURCES ... [DEPS ...])
function(stickrep_add_benchmark name)
  if(NOT STICKREP_BUILD_BENCHMARKS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark)
  target_compile_definitions(${name} PRIVATE STICKREP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endfunction()

# stickrep_add_program(NAME SOURCES ... [DEPS ...]) — an executable in build/bin.
function(stickrep_add_program name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  stickrep_add_sanitizer_options(${name})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS})
  target_compile_definitions(${name} PRIVATE STICKREP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  install(TARGETS ${name} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# stickrep_add_tool_library(NAME SOURCES ... [DEPS ...])
# A tool's library (reports, generators, study runners) in tools/: its headers are included
# as "<folder>/<file>.h" from tools/; the algorithm libraries it uses come through DEPS.
function(stickrep_add_tool_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  stickrep_add_library(${name} SOURCES ${ARG_SOURCES} DEPS ${ARG_DEPS})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/tools)
endfunction()
