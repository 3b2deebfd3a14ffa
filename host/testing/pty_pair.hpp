#pragma once
// A pseudo-terminal pair standing in for a serial cable: the host opens `device()` as a
// serial port; the test holds the master end as the board's side of the line.
#include <string>

namespace tetrapulse::host::testing {

class PtyPair {
 public:
  PtyPair();  // check ok() before use
  ~PtyPair();
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  bool ok() const { return master_ >= 0 && !device_.empty(); }
  int master() const { return master_; }
  const std::string& device() const { return device_; }  // "/dev/pts/N"

 private:
  int master_ = -1;
  std::string device_;
};

}  // namespace tetrapulse::host::testing
