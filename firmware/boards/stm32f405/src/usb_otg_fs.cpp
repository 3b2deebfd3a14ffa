#include "tetrapulse/stm32f405/usb_otg_fs.hpp"

#include "tetrapulse/stm32f405/gpio_setup.hpp"
#include "tetrapulse/stm32f405/pinout.hpp"
#include "tetrapulse/stm32f405/registers/otg_fs.hpp"
#include "tetrapulse/stm32f405/registers/rcc.hpp"
#include "tetrapulse/stm32f405/usb_fifo_plan.hpp"

namespace tetrapulse::stm32f405 {
namespace {

namespace tp = protocol;
using Action = fw::UsbEndpointZero::Action;

constexpr uint32_t kReadyPolls = 200'000;  // AHB idle and resets take a few AHB/PHY clocks
constexpr uint32_t kPacket = tp::kUsbMaxPacketSize;
constexpr uint32_t kAllTxFifos = 0x10;

bool wait_bits(Reg& reg, uint32_t bits, uint32_t value) {
  for (uint32_t i = 0; i < kReadyPolls; ++i) {
    if ((reg & bits) == value) return true;
  }
  return false;
}

void flush_tx(uint32_t fifo) {
  otg::GRSTCTL() = otg::kGrstTxfflsh | field(fifo, otg::kGrstTxfnum);
  wait_bits(otg::GRSTCTL(), otg::kGrstTxfflsh, 0);
}

void flush_rx() {
  otg::GRSTCTL() = otg::kGrstRxfflsh;
  wait_bits(otg::GRSTCTL(), otg::kGrstRxfflsh, 0);
}

// Pops `count` bytes of the packet at the head of the receive FIFO into `out` (up to
// `capacity`; the rest is dropped). Every access takes a whole word.
void read_fifo(uint8_t* out, size_t capacity, size_t count) {
  for (size_t i = 0; i < words_for(count); ++i) store_fifo_word(otg::FIFO(0), i, count, out, capacity);
}

// Disables an enabled bulk endpoint (RM0090 §34.17.6 "IN/OUT endpoint disable"), bounded.
void disable_in(unsigned ep) {
  if ((otg::DIEPCTL(ep) & otg::kEpEpena) != 0) {
    otg::DIEPCTL(ep) = otg::DIEPCTL(ep) | otg::kEpSnak;
    wait_bits(otg::DIEPINT(ep), otg::kEpInepne, otg::kEpInepne);
    otg::DIEPCTL(ep) = otg::DIEPCTL(ep) | otg::kEpEpdis | otg::kEpSnak;
    wait_bits(otg::DIEPINT(ep), otg::kEpEpdisd, otg::kEpEpdisd);
  }
  otg::DIEPCTL(ep) = otg::kEpSnak;  // USBAEP cleared: not part of the configuration
  otg::DIEPINT(ep) = 0xFF;
  flush_tx(ep);
}

void disable_out(unsigned ep) {
  if ((otg::DOEPCTL(ep) & otg::kEpEpena) != 0) {
    // An OUT endpoint is disabled under the global OUT NAK.
    otg::DCTL() = otg::DCTL() | otg::kDctlSgonak;
    wait_bits(otg::GINTSTS(), otg::kGintGonakeff, otg::kGintGonakeff);
    otg::DOEPCTL(ep) = otg::DOEPCTL(ep) | otg::kEpEpdis | otg::kEpSnak;
    wait_bits(otg::DOEPINT(ep), otg::kEpEpdisd, otg::kEpEpdisd);
    otg::DCTL() = otg::DCTL() | otg::kDctlCgonak;
  }
  otg::DOEPCTL(ep) = otg::kEpSnak;
  otg::DOEPINT(ep) = 0xFF;
}

}  // namespace

UsbOtgFs::UsbOtgFs() {}

bool UsbOtgFs::start(fw::UsbEndpointZero& ep0, fw::UsbControl& control, fw::UsbMessageFunction* bulk,
                     const fw::LocalClock& clock) {
  ep0_ = &ep0;
  control_ = &control;
  bulk_ = bulk;
  clock_ = &clock;
  // The hardware endpoints are the ones the configuration descriptor names.
  const tp::Result<BulkEndpoints> endpoints = bulk_endpoints(control.params());
  if (!endpoints) return false;
  bulk_ep_ = *endpoints;
  configure_alternate(pin_of(Signal::kUsbDm));
  configure_alternate(pin_of(Signal::kUsbDp));
  rcc::Registers& r = rcc::regs();
  r.AHB2ENR = r.AHB2ENR | rcc::kAhb2OtgFs;
  (void)r.AHB2ENR;

  // Core soft reset once the AHB master is idle (RM0090 §34.17.1).
  if (!wait_bits(otg::GRSTCTL(), otg::kGrstAhbidl, otg::kGrstAhbidl)) return false;
  otg::GRSTCTL() = otg::kGrstCsrst;
  if (!wait_bits(otg::GRSTCTL(), otg::kGrstCsrst, 0)) return false;
  if (!wait_bits(otg::GRSTCTL(), otg::kGrstAhbidl, otg::kGrstAhbidl)) return false;

  // No interrupt line (polled), the full-speed transceiver, turnaround for the 168 MHz
  // AHB, device mode forced: it takes effect within 25 ms.
  otg::GAHBCFG() = 0;
  otg::GUSBCFG() = otg::kGusbPhysel | field(otg::kTrdtAhbAbove32MHz, otg::kGusbTrdt) | otg::kGusbForceDevice;
  wait_ms(25);
  if ((otg::GINTSTS() & otg::kGintCmod) != 0) return false;

  // Transceiver on, VBUS sensing off; disconnected while the endpoints are set up.
  otg::GCCFG() = otg::kGccfgPwrdwn | otg::kGccfgNovbussens;
  otg::PCGCCTL() = 0;
  otg::DCTL() = otg::kDctlSdis;
  otg::DCFG() = field(otg::kDspdFullSpeed, otg::kDcfgDspd);

  otg::GRXFSIZ() = kFifoPlan.rx_words;
  otg::DIEPTXF0() = field(kFifoPlan.tx0_words, 16) | kFifoPlan.tx0_start;
  otg::DIEPTXF(bulk_ep_.in) = field(kFifoPlan.bulk_in_words, 16) | kFifoPlan.bulk_in_start;
  flush_tx(kAllTxFifos);
  flush_rx();

  otg::DIEPMSK() = otg::kEpXfrc | otg::kEpToc;
  otg::DOEPMSK() = otg::kEpXfrc | otg::kEpStup;
  otg::DAINTMSK() = 0;
  for (unsigned ep = 0; ep < kOtgEndpoints; ++ep) {
    otg::DIEPINT(ep) = 0xFF;
    otg::DOEPINT(ep) = 0xFF;
  }
  otg::GINTSTS() = 0xFFFFFFFFu;  // every status bit is write-1-to-clear
  otg::GINTMSK() = otg::kGintUsbrst | otg::kGintEnumdne | otg::kGintUsbsusp | otg::kGintWkupint |
                   otg::kGintRxflvl | otg::kGintIepint | otg::kGintOepint;
  running_ = true;
  otg::DCTL() = otg::DCTL() & ~otg::kDctlSdis;  // D+ pull-up: the host sees the device
  return true;
}

void UsbOtgFs::wait_ms(uint32_t ms) const {
  const uint64_t ticks = static_cast<uint64_t>(clock_->tick_hz()) * ms / 1000u;
  const fw::Tick start = clock_->now();
  for (uint32_t i = 0; i < 50'000'000u && clock_->now() - start < ticks; ++i) {
  }
}

void UsbOtgFs::disconnect() {
  if (running_) otg::DCTL() = otg::DCTL() | otg::kDctlSdis;
}

void UsbOtgFs::poll() {
  if (!running_) return;
  const uint32_t status = otg::GINTSTS();
  if ((status & otg::kGintUsbrst) != 0) {
    otg::GINTSTS() = otg::kGintUsbrst;
    on_bus_reset();
  }
  if ((status & otg::kGintEnumdne) != 0) {
    otg::GINTSTS() = otg::kGintEnumdne;
    on_enumeration_done();
  }
  if ((status & otg::kGintUsbsusp) != 0) {
    otg::GINTSTS() = otg::kGintUsbsusp;
    suspended_ = true;
  }
  if ((status & otg::kGintWkupint) != 0) {
    otg::GINTSTS() = otg::kGintWkupint;
    suspended_ = false;
  }
  // Packets first, then the endpoint events they complete; IN before OUT, so that the
  // status stage of a transfer is done before the SETUP of the next one is handled.
  for (unsigned i = 0; i < 2u * kFifoPlan.rx_words && (otg::GINTSTS() & otg::kGintRxflvl) != 0; ++i) on_receive_fifo();
  on_in_endpoints();
  on_out_endpoints();
}

void UsbOtgFs::on_bus_reset() {
  suspended_ = false;
  otg::DCTL() = otg::DCTL() & ~otg::kDctlRwusig;
  do_set_configured(false);
  flush_tx(kAllTxFifos);
  for (unsigned ep = 0; ep < kOtgEndpoints; ++ep) {
    otg::DIEPINT(ep) = 0xFF;
    otg::DOEPINT(ep) = 0xFF;
  }
  otg::DAINTMSK() = otg::daint_in(0) | otg::daint_out(0);
  otg::DCFG() = otg::DCFG() & ~mask(7, otg::kDcfgDad);
  ep0_out_ready_ = false;
  ep0_->reset();
  control_->bus_reset();
  arm_ep0_out(false);
}

void UsbOtgFs::on_enumeration_done() {
  // Full speed is the only speed: EP0 takes 64-byte packets (MPSIZ 0).
  otg::DIEPCTL(0) = otg::DIEPCTL(0) & ~mask(2, otg::kEpMpsiz);
  otg::DCTL() = otg::DCTL() | otg::kDctlCginak;
}

void UsbOtgFs::on_receive_fifo() {
  const uint32_t entry = otg::GRXSTSP();
  const unsigned ep = (entry >> otg::kRxEpnum) & 0xFu;
  const size_t count = (entry >> otg::kRxBcnt) & 0x7FFu;
  switch ((entry >> otg::kRxPktsts) & 0xFu) {
    case otg::kPktSetupData:
      read_fifo(setup_, sizeof(setup_), count);
      break;
    case otg::kPktOutData:
      if (ep == 0) {
        // Straight into the control transfer's buffer; handled at its transfer-complete.
        size_t room = 0;
        uint8_t* into = ep0_->out_target(&room);
        read_fifo(into, count <= room ? room : 0, count);
        ep0_out_size_ = static_cast<uint16_t>(count);
        ep0_out_ready_ = true;
      } else {
        uint8_t packet[kPacket];
        read_fifo(packet, sizeof(packet), count);
        const size_t n = count < sizeof(packet) ? count : sizeof(packet);
        if (ep == bulk_ep_.out && configured_) bulk_->on_bulk_packet(tp::ByteView{packet, n});
      }
      break;
    default:
      break;  // OUT/SETUP transfer complete, global OUT NAK: status only, no data
  }
}

void UsbOtgFs::on_in_endpoints() {
  const uint32_t pending = otg::DAINT() & otg::DAINTMSK();
  if ((pending & otg::daint_in(0)) != 0) {
    const uint32_t events = otg::DIEPINT(0);
    otg::DIEPINT(0) = events;
    if ((events & otg::kEpXfrc) != 0) act(ep0_->on_in_complete());
  }
  if ((pending & otg::daint_in(bulk_ep_.in)) != 0) {
    const uint32_t events = otg::DIEPINT(bulk_ep_.in);
    otg::DIEPINT(bulk_ep_.in) = events;
    if ((events & otg::kEpXfrc) != 0) {
      if (zlp_pending_) {
        zlp_pending_ = false;
        load_in(bulk_ep_.in, tp::ByteView{});  // the transfer ended on a packet boundary
      } else {
        bulk_in_busy_ = false;
      }
    }
  }
}

void UsbOtgFs::on_out_endpoints() {
  const uint32_t pending = otg::DAINT() & otg::DAINTMSK();
  if ((pending & otg::daint_out(0)) != 0) {
    const uint32_t events = otg::DOEPINT(0);
    otg::DOEPINT(0) = events;
    if ((events & otg::kEpXfrc) != 0 && ep0_out_ready_) {
      ep0_out_ready_ = false;
      act(ep0_->on_out_received(ep0_out_size_));
    }
    if ((events & otg::kEpStup) != 0) act(ep0_->on_setup(setup_));
  }
  if ((pending & otg::daint_out(bulk_ep_.out)) != 0) {
    const uint32_t events = otg::DOEPINT(bulk_ep_.out);
    otg::DOEPINT(bulk_ep_.out) = events;
    if ((events & otg::kEpXfrc) != 0 && configured_) arm_bulk_out();
  }
}

void UsbOtgFs::act(Action action) {
  switch (action) {
    case Action::kSendPacket:
      load_in(0, ep0_->in_packet());
      break;
    case Action::kSendStatus:
      load_in(0, tp::ByteView{});
      break;
    case Action::kReceivePacket:
    case Action::kReceiveStatus:
      arm_ep0_out(true);
      break;
    case Action::kStall:
      // Both directions until the next SETUP, which clears the stall in hardware.
      otg::DIEPCTL(0) = otg::DIEPCTL(0) | otg::kEpStall;
      otg::DOEPCTL(0) = otg::DOEPCTL(0) | otg::kEpStall;
      arm_ep0_out(false);
      break;
    case Action::kNone:
      arm_ep0_out(false);
      break;
  }
}

void UsbOtgFs::arm_ep0_out(bool enable) {
  // Up to three back-to-back SETUPs are always taken; data and status packets only while
  // the endpoint is enabled.
  otg::DOEPTSIZ(0) = field(3, otg::kTsizStupcnt) | field(1, otg::kTsizPktcnt) | field(kPacket, otg::kTsizXfrsiz);
  if (enable) otg::DOEPCTL(0) = otg::DOEPCTL(0) | otg::kEpEpena | otg::kEpCnak;
}

void UsbOtgFs::arm_bulk_out() {
  otg::DOEPTSIZ(bulk_ep_.out) = field(1, otg::kTsizPktcnt) | field(kPacket, otg::kTsizXfrsiz);
  otg::DOEPCTL(bulk_ep_.out) = otg::DOEPCTL(bulk_ep_.out) | otg::kEpEpena | otg::kEpCnak;
}

void UsbOtgFs::load_in(unsigned ep, tp::ByteView data) {
  const InTransfer t = in_transfer(data.size);
  otg::DIEPTSIZ(ep) = field(t.packets, otg::kTsizPktcnt) | field(static_cast<uint32_t>(data.size), otg::kTsizXfrsiz);
  otg::DIEPCTL(ep) = otg::DIEPCTL(ep) | otg::kEpEpena | otg::kEpCnak;
  for (size_t i = 0; i < t.words; ++i) otg::FIFO(ep) = fifo_word(data, i);
}

void UsbOtgFs::do_set_address(uint8_t address) {
  otg::DCFG() = (otg::DCFG() & ~mask(7, otg::kDcfgDad)) | field(address, otg::kDcfgDad);
}

void UsbOtgFs::do_set_configured(bool configured) {
  const uint32_t bulk_events = otg::daint_in(bulk_ep_.in) | otg::daint_out(bulk_ep_.out);
  configured_ = false;
  bulk_in_busy_ = zlp_pending_ = false;
  if (bulk_ == nullptr) return;  // the bootloader's configuration has no bulk endpoints
  otg::DAINTMSK() = otg::DAINTMSK() & ~bulk_events;
  disable_in(bulk_ep_.in);
  disable_out(bulk_ep_.out);
  if (!configured) return;
  const uint32_t bulk = field(kPacket, otg::kEpMpsiz) | field(otg::kEpTypeBulk, otg::kEpType) | otg::kEpUsbaep |
                        otg::kEpSd0pid;
  otg::DIEPCTL(bulk_ep_.in) = bulk | field(bulk_ep_.in, otg::kEpTxfnum) | otg::kEpSnak;
  otg::DOEPCTL(bulk_ep_.out) = bulk;
  otg::DAINTMSK() = otg::DAINTMSK() | bulk_events;
  configured_ = true;
  arm_bulk_out();
}

void UsbOtgFs::do_set_endpoint_halt(uint8_t endpoint, bool halted) {
  const bool in = endpoint == (0x80u | bulk_ep_.in);
  if ((!in && endpoint != bulk_ep_.out) || !configured_) return;
  Reg& control = in ? otg::DIEPCTL(bulk_ep_.in) : otg::DOEPCTL(bulk_ep_.out);
  if (halted) {
    control = control | otg::kEpStall;
    return;
  }
  // Clearing a halt resets the data toggle (USB 2.0 §9.4.5).
  control = (control & ~otg::kEpStall) | otg::kEpSd0pid;
  if (!in && (control & otg::kEpEpena) == 0) arm_bulk_out();
}

tp::Status UsbOtgFs::do_send_bulk(tp::ByteView transfer) {
  if (!running_ || !configured_ || bulk_in_busy()) return tp::Error::kBusy;
  if (transfer.size == 0 || transfer.size > tp::kUsbBulkMaxTransfer) return tp::Error::kBadLength;
  if ((otg::DTXFSTS(bulk_ep_.in) & 0xFFFFu) < in_transfer(transfer.size).words) return tp::Error::kBusy;
  bulk_in_busy_ = true;
  zlp_pending_ = tp::usb_bulk_needs_zlp(transfer.size);
  load_in(bulk_ep_.in, transfer);
  return {};
}

}  // namespace tetrapulse::stm32f405
