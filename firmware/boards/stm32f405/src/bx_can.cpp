#include "tetrapulse/stm32f405/bx_can.hpp"

#include "tetrapulse/stm32f405/gpio_setup.hpp"
#include "tetrapulse/stm32f405/interrupt_handlers.hpp"
#include "tetrapulse/stm32f405/pinout.hpp"
#include "tetrapulse/stm32f405/registers/can.hpp"
#include "tetrapulse/stm32f405/registers/core.hpp"
#include "tetrapulse/stm32f405/registers/rcc.hpp"

namespace tetrapulse::stm32f405 {
namespace {

namespace tp = protocol;
constexpr uint32_t kModePolls = 1'000'000;  // INAK follows INRQ within 11 recessive bits
constexpr uint8_t kRxPriority = 1;
constexpr uint8_t kTxPriority = 2;
constexpr unsigned kBankAddressed = 0;
constexpr unsigned kBankBroadcast = 1;

bool wait_inak(bool set) {
  can::Registers& c = can::can1();
  for (uint32_t i = 0; i < kModePolls; ++i) {
    if (((c.MSR & can::kMsrInak) != 0) == set) return true;
  }
  return false;
}

// Bit timing with 8..16 time quanta per bit and the sample point near 87.5 %.
bool bit_timing(uint32_t apb1_hz, uint32_t bitrate, uint32_t* btr) {
  for (uint32_t quanta = 16; quanta >= 8; --quanta) {
    const uint32_t per_quantum = bitrate * quanta;
    if (apb1_hz % per_quantum != 0) continue;
    const uint32_t prescaler = apb1_hz / per_quantum;
    if (prescaler == 0 || prescaler > 1024) continue;
    const uint32_t seg2 = (quanta + 4) / 8;  // >= 1, about 1/8 of the bit
    const uint32_t seg1 = quanta - 1 - seg2;
    *btr = field(prescaler - 1, can::kBtrBrp) | field(seg1 - 1, can::kBtrTs1) |
           field(seg2 - 1, can::kBtrTs2) | field(0, can::kBtrSjw);
    return true;
  }
  return false;
}

uint32_t filter_word(uint32_t id) { return (id << can::kIdExtShift) | can::kIdIde; }

}  // namespace

BxCan& bx_can() {
  static BxCan controller;
  return controller;
}

bool BxCan::start(uint32_t apb1_hz, uint32_t bitrate, LocalTimer& clock) {
  clock_ = &clock;
  uint32_t btr = 0;
  if (!bit_timing(apb1_hz, bitrate, &btr)) return false;
  rcc::Registers& r = rcc::regs();
  r.APB1ENR = r.APB1ENR | rcc::kApb1Can1;
  (void)r.APB1ENR;
  configure_alternate(pin_of(Signal::kCanRx), gpio::kPullUp);
  configure_alternate(pin_of(Signal::kCanTx));

  can::Registers& c = can::can1();
  c.MCR = can::kMcrInrq;  // leaves sleep, enters initialisation
  if (!wait_inak(true)) return false;
  c.MCR = can::kMcrInrq | can::kMcrTxfp | can::kMcrAbom;
  c.BTR = btr;
  do_set_filters(tp::can_node_filters(tp::kCanFirstBoardNode));
  c.IER = can::kIerFmpie0 | bit(0) /* TMEIE */ | can::kIerErrie | can::kIerBofie | can::kIerLecie;
  c.MCR = can::kMcrTxfp | can::kMcrAbom;
  if (!wait_inak(false)) return false;
  nvic::enable(nvic::kCan1Rx0, kRxPriority);
  nvic::enable(nvic::kCan1Tx, kTxPriority);
  nvic::enable(nvic::kCan1Sce, kTxPriority);
  running_ = true;
  return true;
}

void BxCan::do_set_filters(const tp::CanNodeFilters& filters) {
  can::Registers& c = can::can1();
  c.FMR = c.FMR | can::kFmrFinit;
  const uint32_t banks = bit(kBankAddressed) | bit(kBankBroadcast);
  c.FA1R = c.FA1R & ~banks;
  c.FM1R = c.FM1R & ~banks;    // mask mode
  c.FS1R = c.FS1R | banks;     // one 32-bit filter per bank
  c.FFA1R = c.FFA1R & ~banks;  // both to FIFO 0
  // The masks also compare IDE (must be 1) and RTR (must be 0): standard and remote
  // frames never match.
  const uint32_t flag_mask = can::kIdIde | can::kIdRtr;
  c.FB[kBankAddressed].FR1 = filter_word(filters.addressed.id);
  c.FB[kBankAddressed].FR2 = (filters.addressed.mask << can::kIdExtShift) | flag_mask;
  c.FB[kBankBroadcast].FR1 = filter_word(filters.broadcast.id);
  c.FB[kBankBroadcast].FR2 = (filters.broadcast.mask << can::kIdExtShift) | flag_mask;
  c.FA1R = c.FA1R | banks;
  c.FMR = c.FMR & ~can::kFmrFinit;
}

tp::Status BxCan::do_send(const tp::CanFrame& frame) {
  if (!running_) return tp::Error::kBusy;
  InterruptLock lock;
  if (tx_count_ == sizeof(tx_) / sizeof(tx_[0])) return tp::Error::kBusy;
  tx_[(tx_head_ + tx_count_) % (sizeof(tx_) / sizeof(tx_[0]))] = frame;
  ++tx_count_;
  fill_mailboxes();
  return {};
}

void BxCan::fill_mailboxes() {
  can::Registers& c = can::can1();
  constexpr size_t kSlots = sizeof(tx_) / sizeof(tx_[0]);
  while (tx_count_ != 0 && (c.TSR & can::kTsrTmeAll) != 0) {
    const unsigned box = (c.TSR >> can::kTsrCode) & 3u;
    const tp::CanFrame& f = tx_[tx_head_];
    can::TxMailbox& m = c.TX[box];
    uint32_t lo = 0, hi = 0;
    for (unsigned i = 0; i < 4 && i < f.size; ++i) lo |= static_cast<uint32_t>(f.data[i]) << (8 * i);
    for (unsigned i = 4; i < 8 && i < f.size; ++i) hi |= static_cast<uint32_t>(f.data[i]) << (8 * (i - 4));
    m.TDLR = lo;
    m.TDHR = hi;
    m.TDTR = f.size;
    m.TIR = (f.id << can::kIdExtShift) | can::kIdIde | can::kIdTxrq;
    tx_head_ = (tx_head_ + 1) % kSlots;
    --tx_count_;
  }
}

void BxCan::on_receive_interrupt() {
  const fw::Tick now = clock_->now();
  can::Registers& c = can::can1();
  while ((c.RF0R & can::kRfFmp) != 0) {
    const can::RxFifo& box = c.RX[0];
    ReceivedFrame r;
    r.rx = now;
    const uint32_t rir = box.RIR;
    const uint32_t lo = box.RDLR;
    const uint32_t hi = box.RDHR;
    uint32_t dlc = box.RDTR & 0xFu;
    if (dlc > 8) dlc = 8;
    r.frame.id = rir >> can::kIdExtShift;
    r.frame.size = static_cast<uint8_t>(dlc);
    for (unsigned i = 0; i < 4; ++i) r.frame.data[i] = static_cast<uint8_t>(lo >> (8 * i));
    for (unsigned i = 0; i < 4; ++i) r.frame.data[4 + i] = static_cast<uint8_t>(hi >> (8 * i));
    c.RF0R = can::kRfRfom;  // release the FIFO slot
    const bool ours = (rir & can::kIdIde) != 0 && (rir & can::kIdRtr) == 0;
    if (ours && !rx_.push(r) && errors_ != UINT16_MAX) errors_ = errors_ + 1;
  }
  if ((c.RF0R & can::kRfFovr) != 0) {
    c.RF0R = can::kRfFovr;
    if (errors_ != UINT16_MAX) errors_ = errors_ + 1;
  }
}

void BxCan::on_transmit_interrupt() {
  can::Registers& c = can::can1();
  c.TSR = bit(0) | bit(8) | bit(16);  // RQCP0..2: write 1 to clear
  fill_mailboxes();
}

void BxCan::on_status_interrupt() {
  can::Registers& c = can::can1();
  const uint32_t esr = c.ESR;
  if (((esr >> can::kEsrLec) & 7u) != 0 && errors_ != UINT16_MAX) errors_ = errors_ + 1;
  c.ESR = 0;  // LEC back to "no error" (software may write it)
  c.MSR = bit(2);  // ERRI: write 1 to clear
}

bool BxCan::do_bus_off() const { return (can::can1().ESR & can::kEsrBoff) != 0; }

}  // namespace tetrapulse::stm32f405

extern "C" void CAN1_RX0_IRQHandler() { tetrapulse::stm32f405::bx_can().on_receive_interrupt(); }
extern "C" void CAN1_TX_IRQHandler() { tetrapulse::stm32f405::bx_can().on_transmit_interrupt(); }
extern "C" void CAN1_SCE_IRQHandler() { tetrapulse::stm32f405::bx_can().on_status_interrupt(); }
