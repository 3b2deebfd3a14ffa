#pragma once
// Test support: what dfu-util 0.11 sends to a DFU device, step by step (its main.c and
// dfu_load.c, and the transcripts in its documentation), over a ControlPipe:
//   run-time: SET_INTERFACE(alt 0) by the caller, GETSTATUS (a stall reads as appIDLE),
//             DETACH(wValue = 1000 ms); with bitWillDetach it waits for the device to return
//   DFU mode: GETSTATUS, again after clearing dfuERROR (CLRSTATUS) or aborting a transfer
//             left in dfuDNLOAD-IDLE/dfuUPLOAD-IDLE (ABORT); a status other than OK is then
//             cleared and must read OK
//   -D file:  DNLOAD(wValue = block number from 0, wTransferSize bytes, the last shorter),
//             each followed by GETSTATUS until dfuDNLOAD-IDLE or dfuERROR, sleeping
//             bwPollTimeout in between; then DNLOAD(wLength 0) and GETSTATUS, sleeping
//             bwPollTimeout, plus 1 s and again while dfuMANIFEST-SYNC or dfuMANIFEST
//   -U file:  UPLOAD(wValue = block number from 0, wTransferSize) until a short block
// The device's main loop runs while the model sleeps (the `sleep` callback).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/protocol/dfu.hpp"
#include "usb_test_host.hpp"

namespace tetrapulse::fw::testing {

class DfuUtilModel {
 public:
  DfuUtilModel(ControlPipe& pipe, uint16_t interface, uint16_t transfer_size, std::function<void(uint32_t)> sleep)
      : pipe_(pipe), interface_(interface), transfer_size_(transfer_size), sleep_(std::move(sleep)) {}

  std::optional<protocol::DfuStatus> get_status();
  // Run-time: detach. False with `error` set when a request failed.
  bool detach();
  // DFU mode: the session start, then the download. True when dfu-util would print
  // "Done!" after reading dfuIDLE with status OK.
  bool download(const std::vector<uint8_t>& file);
  std::optional<std::vector<uint8_t>> upload();

  std::vector<protocol::DfuState> states;  // every state a GETSTATUS reported, in order
  std::vector<uint16_t> block_numbers;     // wValue of every DNLOAD
  protocol::DfuStatus last;                // the last GETSTATUS answer
  std::string error;                       // what dfu-util would complain about
  uint32_t slept_ms = 0;

 private:
  bool start_session();
  bool fail(const std::string& what);
  void sleep(uint32_t ms);

  ControlPipe& pipe_;
  uint16_t interface_;
  uint16_t transfer_size_;
  std::function<void(uint32_t)> sleep_;
};

}  // namespace tetrapulse::fw::testing
