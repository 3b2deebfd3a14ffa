#pragma once
// CAN1 (bxCAN, RM0090 §32) as the fw::CanBus seam: extended data frames only, two 32-bit
// mask filters from protocol::can_node_filters (IDE set, RTR clear), transmit mailboxes
// fed in request order (TXFP) from a queue that holds a whole transfer, received frames
// stamped with the local clock in the FIFO 0 interrupt and queued for the main loop.
//
// The stamp is taken on entry to the receive interrupt, i.e. the end of the frame on the
// bus plus the interrupt latency (a fixed ~1 us at the highest priority but one).
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/app/spsc_queue.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/stm32f405/local_timer.hpp"

namespace tetrapulse::stm32f405 {

struct ReceivedFrame {
  protocol::CanFrame frame;
  fw::Tick rx = 0;
};

class BxCan final : public fw::CanBus {
 public:
  // Not constexpr on purpose: a constant-initialised object with a vtable lands in .data
  // and costs its whole size in flash as well (its copy there); this one is built at first
  // use in zeroed RAM (.bss) instead.
  BxCan();
  static constexpr uint32_t kDefaultBitrate = 1'000'000;

  // Starts CAN1 at `bitrate` from the APB1 clock; false when the controller does not
  // leave initialisation (no transceiver power, or no bxCAN as under QEMU).
  bool start(uint32_t apb1_hz, uint32_t bitrate, LocalTimer& clock);
  bool running() const { return running_; }

  // Main loop: the next received frame.
  bool receive(ReceivedFrame* out) { return rx_.pop(out); }
  // Every queued frame has left the transmit mailboxes (or the controller is not running).
  bool tx_idle() const;

  void on_receive_interrupt();
  void on_transmit_interrupt();
  void on_status_interrupt();

 private:
  protocol::Status do_send(const protocol::CanFrame& frame) override;
  void do_set_filters(const protocol::CanNodeFilters& filters) override;
  uint16_t do_error_count() const override { return errors_; }
  bool do_bus_off() const override;

  void fill_mailboxes();

  LocalTimer* clock_ = nullptr;
  bool running_ = false;
  fw::SpscQueue<ReceivedFrame, 32> rx_;
  // One whole transfer (46 frames at most) and a little more: an answer is queued whole.
  protocol::CanFrame tx_[protocol::kCanMaxFramesPerTransfer + 2];
  size_t tx_head_ = 0;
  size_t tx_count_ = 0;
  volatile uint16_t errors_ = 0;
};

BxCan& bx_can();

}  // namespace tetrapulse::stm32f405
