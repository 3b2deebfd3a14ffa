#pragma once
// Exit codes of every `tetrapulse` subcommand (documented in `tetrapulse --help`
// and README.md). Scripts may rely on them; never renumber.

namespace tetrapulse::cli {

enum ExitCode : int {
  kExitOk = 0,           // success
  kExitFailure = 1,      // the operation ran and failed (e.g. nothing localized)
  kExitUsage = 2,        // bad command line: unknown option, malformed value
  kExitBadInput = 3,     // an input file or dataset is missing, unreadable or malformed
  kExitNoDevice = 4,     // no board found, or a link (USB, CAN, serial, GPIO) cannot be opened
  kExitDeviceError = 5,  // the board answered with an error, timed out or went away
  kExitCheckFailed = 6,  // a check, verification or evaluation threshold did not hold
  kExitPublishFailed = 7,  // localize: the poses were computed and written, but publishing (--ros2) failed
  kExitSkipped = 8,        // localize, demo: done, but frames (or frames.csv lines) were skipped, each named on stderr
};

constexpr const char* kExitCodesHelp =
    "Exit codes: 0 ok, 1 failure, 2 bad command line, 3 bad input file, 4 no device,\n"
    "            5 device error or timeout, 6 check or verification failed,\n"
    "            7 poses computed but not published (localize --ros2: DDS could not start or failed),\n"
    "            8 done, but broken frames were skipped (localize, demo: each named on stderr).";

}  // namespace tetrapulse::cli
