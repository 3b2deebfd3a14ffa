#pragma once
// Programs a test or benchmark starts beside itself (inside the same network namespace): their
// standard output read line by line and their end waited for, each with a bound,
// on events (poll on a pipe and on a pidfd), never on sleeps.
#include <string>
#include <vector>

namespace tetrapulse::ros2::testing {

class ChildProcess {
 public:
  // argv[0] is the program's path; `env` adds or replaces variables ("NAME=value");
  // stderr goes to `stderr_path`.
  ChildProcess(const std::vector<std::string>& argv, const std::vector<std::string>& env,
               const std::string& stderr_path);
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();  // kills a child still running

  // The next line of its stdout (without newline); false at its end or after timeout_ms.
  bool read_line(std::string* line, int timeout_ms);
  // Everything it wrote to stdout that was not read yet, up to its end (bounded by timeout_ms).
  std::string read_rest(int timeout_ms);
  // Its exit code; -1 when it did not end within timeout_ms (it is killed then) or died of a signal.
  int wait(int timeout_ms);

 private:
  int pid_ = -1;
  int pidfd_ = -1;
  int out_ = -1;
  std::string buffer_;
  bool reaped_ = false;
  int status_ = -1;
};

}  // namespace tetrapulse::ros2::testing
