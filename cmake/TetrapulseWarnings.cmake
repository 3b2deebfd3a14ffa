# Warnings for project code only (third-party headers come in as system includes).
add_library(tetrapulse_warnings INTERFACE)
target_compile_options(tetrapulse_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Woverloaded-virtual
  -Wcast-align -Wunused -Wmissing-declarations -Werror)

# tetrapulse_test(NAME SOURCES... LIBS...): one GoogleTest executable registered with CTest.
function(tetrapulse_test name)
  cmake_parse_arguments(T "" "" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main tetrapulse_warnings)
  # Line tables are all a test's backtrace needs; full debug info of gtest and
  # rapidcheck templates made up a third of the tests' compile time.
  target_compile_options(${name} PRIVATE -g1)
  if(TARGET tetrapulse_test_pch)
    target_precompile_headers(${name} REUSE_FROM tetrapulse_test_pch)
  endif()
  if(NOT T_LABELS)
    set(T_LABELS unit)
  endif()
  gtest_discover_tests(${name} PROPERTIES LABELS "${T_LABELS}" DISCOVERY_TIMEOUT 60)
endfunction()
