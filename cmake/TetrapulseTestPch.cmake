# One precompiled header for every test (tetrapulse_test reuses it): GoogleTest,
# rapidcheck, Eigen and OpenCV's core took 3-6 s to parse in each of some 120
# test files, in each of two builds. The tests' flags are the same (warnings,
# -g1, the preset's), so one header serves them all; a test's own definitions
# do not touch these headers.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenCV 4 REQUIRED COMPONENTS core)
add_library(tetrapulse_test_pch STATIC ${CMAKE_CURRENT_LIST_DIR}/pch/test_pch.cpp)
target_link_libraries(tetrapulse_test_pch PRIVATE GTest::gtest rapidcheck Eigen3::Eigen opencv_core tetrapulse_warnings)
target_include_directories(tetrapulse_test_pch PRIVATE ${OpenCV_INCLUDE_DIRS})
target_compile_options(tetrapulse_test_pch PRIVATE -g1 ${TETRAPULSE_TEST_OPT})
target_precompile_headers(tetrapulse_test_pch PRIVATE
  <algorithm> <array> <cmath> <cstdint> <cstdio> <functional> <map> <memory> <optional>
  <string> <string_view> <utility> <vector>
  <gtest/gtest.h> <rapidcheck.h> <rapidcheck/gtest.h>
  <Eigen/Core> <Eigen/Geometry> <opencv2/core.hpp>)
