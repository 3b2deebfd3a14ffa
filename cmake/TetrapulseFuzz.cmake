# tetrapulse_fuzzer(NAME SOURCES... LIBS... RUNS N [CORPUS DIR]): a libFuzzer target
# (clang, asan preset) plus a CTest test that runs it for N executions under the
# sanitizers. A finding fails the test and leaves the input under the build tree.
function(tetrapulse_fuzzer name)
  cmake_parse_arguments(F "" "RUNS;CORPUS" "SOURCES;LIBS" ${ARGN})
  if(NOT TETRAPULSE_FUZZ)
    return()
  endif()
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "tetrapulse_fuzzer(${name}): libFuzzer needs clang (use the asan preset)")
  endif()
  if(NOT F_RUNS)
    set(F_RUNS 100000)
  endif()
  add_executable(${name} ${F_SOURCES})
  target_compile_options(${name} PRIVATE -fsanitize=fuzzer)
  target_link_options(${name} PRIVATE -fsanitize=fuzzer)
  target_link_libraries(${name} PRIVATE ${F_LIBS} tetrapulse_warnings)
  set(artifacts ${CMAKE_CURRENT_BINARY_DIR}/${name}-findings/)
  set(work ${CMAKE_CURRENT_BINARY_DIR}/${name}-corpus)
  set(seed_args)
  if(F_CORPUS)
    list(APPEND seed_args ${F_CORPUS})
  endif()
  # A fixed seed keeps the run reproducible; the corpus folder grows across runs.
  add_test(NAME ${name}
    COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1
            $<TARGET_FILE:${name}> -runs=${F_RUNS} -seed=1 -max_len=4096 -print_final_stats=1
            -artifact_prefix=${artifacts} ${work} ${seed_args})
  set_tests_properties(${name} PROPERTIES LABELS "fuzz" TIMEOUT 600)
  file(MAKE_DIRECTORY ${artifacts} ${work})
endfunction()
