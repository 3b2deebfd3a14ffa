#pragma once
// The USB transport of SPEC.md §5: messages in bulk transfers ([length u16][message])
// and through the MESSAGE_OUT / MESSAGE_IN vendor control requests. A request is
// answered on the path it came by (§5.3).
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/links/message_link.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"

namespace tetrapulse::fw {

constexpr uint8_t kUsbBulkPath = 0;     // ReplyPath::peer: answer on bulk IN
constexpr uint8_t kUsbControlPath = 1;  // ReplyPath::peer: answer through MESSAGE_IN

// Hardware seam: the bulk IN endpoint (stm32f405: OTG FS; boards/sim: the host side).
class UsbPipe {
 public:
  // Sends one bulk IN transfer (the device adds the zero-length packet when the size is
  // a multiple of 64). kBusy when the endpoint cannot take it now.
  protocol::Status send_bulk(protocol::ByteView transfer) { return do_send_bulk(transfer); }

 protected:
  ~UsbPipe() = default;

 private:
  virtual protocol::Status do_send_bulk(protocol::ByteView transfer) = 0;
};

class UsbLink final : public MessageLink {
 public:
  static constexpr size_t kControlQueue = 4;  // answers waiting for MESSAGE_IN

  explicit UsbLink(UsbPipe& pipe) : pipe_(pipe) {}

  // A whole bulk OUT transfer (a controller that hands over whole transfers).
  void on_bulk_transfer(protocol::ByteView transfer, Tick rx, MessageSink& sink);
  // One bulk OUT packet (a controller that hands over packets, e.g. STM32 OTG FS).
  void on_bulk_packet(protocol::ByteView packet, Tick rx, MessageSink& sink);
  // The data stage of MESSAGE_OUT: one message.
  void on_control_message(protocol::ByteView message, Tick rx, MessageSink& sink);

  // MESSAGE_IN: copies the oldest pending control-path answer into `out` and returns
  // its size (0: none pending). kBufferTooSmall when it does not fit (it stays pending).
  protocol::Result<size_t> take_control_response(uint8_t* out, size_t capacity);
  // True while MESSAGE_OUT would find no room for its answer (the device stalls it).
  bool control_queue_full() const { return control_count_ == kControlQueue; }

  uint16_t transport_errors() const { return transport_errors_; }

 private:
  LinkKind do_kind() const override { return LinkKind::kUsb; }
  protocol::Status do_send(const ReplyPath& to, protocol::ByteView message) override;
  void deliver(protocol::ByteView message, Tick rx, uint8_t path, MessageSink& sink);

  struct Pending {
    uint16_t size = 0;
    uint8_t bytes[protocol::kMaxMessageSize] = {};
  };

  UsbPipe& pipe_;
  protocol::UsbBulkFrameReceiver packets_;
  Pending control_[kControlQueue];
  size_t control_head_ = 0;
  size_t control_count_ = 0;
  uint16_t transport_errors_ = 0;
};

}  // namespace tetrapulse::fw
