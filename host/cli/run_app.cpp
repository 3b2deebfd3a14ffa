#include "run_app.hpp"

#include <cstdio>
#include <exception>

#include "exit_codes.hpp"

namespace tetrapulse::cli {

int run_app(CLI::App& app, int argc, char** argv, const int& result) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tetrapulse: internal error: %s\n", e.what());
    return kExitFailure;
  }
  return result;
}

}  // namespace tetrapulse::cli
