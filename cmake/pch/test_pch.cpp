// Compiles the tests' precompiled header (cmake/TetrapulseTestPch.cmake); defines nothing.
