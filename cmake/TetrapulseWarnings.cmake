# Warnings for project code only (third-party headers come in as system includes).
add_library(tetrapulse_warnings INTERFACE)
target_compile_options(tetrapulse_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Woverloaded-virtual
  -Wcast-align -Wunused -Wmissing-declarations -Werror)

# Each part's own tests (every tetrapulse_test() outside tests/) are built and run by
# the asan preset too, under the sanitizers; `make check` runs them there only and turns
# this off in the default build, which keeps tests/ (system, docs), the VM, live, ROS 2
# and QEMU tests. Off, the executables still exist as targets, outside `all`.
option(TETRAPULSE_PART_TESTS "Build and register each part's own tests (tetrapulse_test outside tests/)" ON)

# Under the sanitizers a test's own code is compiled without optimisation (it sets up
# and checks; the libraries it calls keep the preset's -O1): instrumented -O1 code of
# GoogleTest and rapidcheck templates took most of the asan build's time. A test whose
# own code does the heavy numerics (Eigen in loops: a reference renderer, thousands of
# random problems) says OPTIMIZED and keeps the preset's flags, without the shared
# precompiled header (whose flags must match).
if(TETRAPULSE_SANITIZE)
  set(TETRAPULSE_TEST_OPT -O0)
else()
  set(TETRAPULSE_TEST_OPT)
endif()

# tetrapulse_test(NAME SOURCES... LIBS...): one GoogleTest executable registered with CTest.
function(tetrapulse_test name)
  cmake_parse_arguments(T "OPTIMIZED" "" "SOURCES;LIBS;LABELS" ${ARGN})
  set(tests_dir "${PROJECT_SOURCE_DIR}/tests")
  cmake_path(IS_PREFIX tests_dir "${CMAKE_CURRENT_SOURCE_DIR}" NORMALIZE in_tests_dir)
  set(registered ON)
  if(NOT TETRAPULSE_PART_TESTS AND NOT in_tests_dir)
    set(registered OFF)
  endif()
  if(registered)
    add_executable(${name} ${T_SOURCES})
  else()
    add_executable(${name} EXCLUDE_FROM_ALL ${T_SOURCES})
  endif()
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main tetrapulse_warnings)
  # Line tables are all a test's backtrace needs; full debug info of gtest and
  # rapidcheck templates made up a third of the tests' compile time.
  set(opt ${TETRAPULSE_TEST_OPT})
  if(T_OPTIMIZED)
    set(opt)
  endif()
  target_compile_options(${name} PRIVATE -g1 ${opt})
  if(TARGET tetrapulse_test_pch AND "${opt}" STREQUAL "${TETRAPULSE_TEST_OPT}")
    target_precompile_headers(${name} REUSE_FROM tetrapulse_test_pch)
  endif()
  if(NOT T_LABELS)
    set(T_LABELS unit)
  endif()
  if(registered)
    gtest_discover_tests(${name} PROPERTIES LABELS "${T_LABELS}" DISCOVERY_TIMEOUT 60)
  endif()
endfunction()
