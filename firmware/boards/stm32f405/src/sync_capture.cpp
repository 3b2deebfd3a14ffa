#include "tetrapulse/stm32f405/sync_capture.hpp"

namespace tetrapulse::stm32f405 {

void SyncCapture::do_configure(bool enabled, protocol::GpioEdge edge) {
  if (enabled) {
    timer_.enable_capture(edge == protocol::GpioEdge::kFalling, &SyncCapture::on_capture, this);
  } else {
    timer_.disable_capture();
  }
}

void SyncCapture::on_capture(void* context, uint64_t tick) {
  // A full queue drops the edge; the servo sees a missing sample, not a wrong one.
  static_cast<SyncCapture*>(context)->edges_.push(tick);
}

}  // namespace tetrapulse::stm32f405
