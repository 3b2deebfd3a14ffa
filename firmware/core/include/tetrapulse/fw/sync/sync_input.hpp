#pragma once
// Hardware seam: the GPIO sync input (camera strobe or trigger line).
//
// The board time-stamps each selected edge with an input capture of the local counter
// and hands the captured tick to Firmware::on_sync_edge (from its main loop, or through
// an SpscQueue filled by the capture interrupt). Capture latency does not matter; only
// the captured tick does.
#include "tetrapulse/protocol/config.hpp"

namespace tetrapulse::fw {

class SyncInput {
 public:
  // Captures `edge` edges when `enabled`, none otherwise.
  void configure(bool enabled, protocol::GpioEdge edge) { do_configure(enabled, edge); }

 protected:
  ~SyncInput() = default;

 private:
  virtual void do_configure(bool enabled, protocol::GpioEdge edge) = 0;
};

}  // namespace tetrapulse::fw
