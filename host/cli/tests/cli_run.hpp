#pragma once
// Runs the built `tetrapulse` binary as a user would, with its stdout, stderr and exit code.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tetrapulse::cli::testing {

struct CliRun {
  int exit = -1;
  std::string out;
  std::string err;
  // Lines on stderr (an error is exactly one).
  size_t err_lines() const { return static_cast<size_t>(std::count(err.begin(), err.end(), '\n')); }
};

class CliTempDir {
 public:
  explicit CliTempDir(const std::string& tag)
      : path_(std::filesystem::temp_directory_path() /
              ("tp_cli_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter_++))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~CliTempDir() { std::filesystem::remove_all(path_); }
  std::string path(const std::string& name) const { return (path_ / name).string(); }
  std::string file(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }

 private:
  static inline int counter_ = 0;
  std::filesystem::path path_;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `tetrapulse ARGS` (ARGS as shell words, already quoted where needed).
inline CliRun run_cli(const CliTempDir& dir, const std::string& args) {
  const std::string command = std::string("'") + TETRAPULSE_CLI + "' " + args + " >'" + dir.path("stdout") + "' 2>'" +
                              dir.path("stderr") + "'";
  const int status = std::system(command.c_str());
  CliRun r;
  r.exit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir.path("stdout"));
  r.err = slurp(dir.path("stderr"));
  return r;
}

}  // namespace tetrapulse::cli::testing
