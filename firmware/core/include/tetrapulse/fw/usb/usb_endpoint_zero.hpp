#pragma once
// Endpoint 0 of a device controller that moves single packets (STM32 OTG FS): turns the
// SETUP, data and status packets of control transfers (USB 2.0 §8.5.3) into UsbControl's
// three stages, and tells the driver what to do with the endpoint next.
//
//   driver                               UsbEndpointZero
//   SETUP packet received        ->      on_setup()          -> Action
//   IN packet taken by the host  ->      on_in_complete()    -> Action
//   OUT packet received          ->      on_out_packet()     -> Action
//   Action::kSendPacket: load in_packet() (0..64 bytes) on EP0 IN
//   Action::kReceivePacket: arm EP0 OUT for one data packet
//   Action::kSendStatus / kReceiveStatus: a zero-length status packet in / out
//   Action::kStall: stall EP0 both ways until the next SETUP
// A driver that reads its receive FIFO itself can put an OUT packet straight where it
// belongs (out_target(), then on_out_received()) instead of copying it (on_out_packet()).
//
// The IN data stage sends min(answer, wLength) bytes in 64-byte packets and ends with a
// zero-length packet when that is shorter than wLength and a multiple of 64. The OUT data
// stage ends at wLength bytes or at a short packet; more than wLength stalls.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/usb/usb_control.hpp"
#include "tetrapulse/fw/usb/usb_setup.hpp"
#include "tetrapulse/protocol/bytes.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::fw {

class UsbEndpointZero {
 public:
  enum class Action : uint8_t { kNone, kSendPacket, kReceivePacket, kSendStatus, kReceiveStatus, kStall };

  explicit UsbEndpointZero(UsbControl& control) : control_(control) {}

  Action on_setup(const uint8_t (&packet)[kUsbSetupSize]);
  Action on_in_complete();
  Action on_out_packet(protocol::ByteView packet);
  // Where the next OUT packet's bytes go: `*room` bytes at the returned address (0 bytes,
  // and any address, when only a status ZLP is expected). A packet longer than `*room`
  // is dropped by the driver and reported with its full size (on_out_received stalls).
  uint8_t* out_target(size_t* room);
  Action on_out_received(size_t size);
  // USB reset: forgets the transfer in progress (UsbControl's bus_reset is the driver's call).
  void reset();

  // The IN packet to load now (after Action::kSendPacket).
  protocol::ByteView in_packet() const;

 private:
  enum class Stage : uint8_t { kIdle, kDataIn, kDataOut, kStatusIn, kStatusOut };

  Action finish_out_stage();
  Action take_out(size_t size);
  Action status_done();

  UsbControl& control_;
  Stage stage_ = Stage::kIdle;
  UsbSetup setup_;
  UsbControlReply reply_;
  size_t total_ = 0;     // bytes of the data stage (IN: to send; OUT: received so far)
  size_t sent_ = 0;      // IN: bytes handed to the controller, the loaded packet included
  size_t packet_ = 0;    // IN: size of the loaded packet
  bool zlp_ = false;     // IN: a zero-length packet still ends the data stage
};

}  // namespace tetrapulse::fw
