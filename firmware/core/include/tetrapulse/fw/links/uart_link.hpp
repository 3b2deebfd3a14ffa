#pragma once
// The UART transport of SPEC.md §6 (COBS frames with a CRC-16, 0x00 delimited) on top
// of a byte stream.
#include <cstdint>

#include "tetrapulse/fw/clock/tick.hpp"
#include "tetrapulse/fw/links/message_link.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"

namespace tetrapulse::fw {

// Hardware seam: a serial port's transmit side (stm32f405: USART with a FIFO or DMA).
class SerialPort {
 public:
  // Queues bytes for transmission, all or none; kBusy when they do not fit.
  protocol::Status write(protocol::ByteView bytes) { return do_write(bytes); }

 protected:
  ~SerialPort() = default;

 private:
  virtual protocol::Status do_write(protocol::ByteView bytes) = 0;
};

class UartLink final : public MessageLink {
 public:
  explicit UartLink(SerialPort& port) : port_(port) {}

  // Bytes received; every message they complete goes to `sink`, stamped `rx` (the
  // tick at which the frame's last byte arrived is good enough: UART carries no sync).
  void on_bytes(protocol::ByteView bytes, Tick rx, MessageSink& sink);

  uint16_t transport_errors() const { return transport_errors_; }

 private:
  LinkKind do_kind() const override { return LinkKind::kUart; }
  protocol::Status do_send(const ReplyPath& to, protocol::ByteView message) override;

  SerialPort& port_;
  protocol::UartFrameDecoder decoder_;
  uint16_t transport_errors_ = 0;
};

}  // namespace tetrapulse::fw
