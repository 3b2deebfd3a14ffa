#pragma once
// bxCAN (RM0090 §32.9); CAN1 at 0x40006400 on APB1 (42 MHz).
#include "tetrapulse/stm32f405/registers/mmio.hpp"

namespace tetrapulse::stm32f405::can {

struct TxMailbox {
  Reg TIR;   // identifier: extended id in bits 31..3, IDE bit 2, RTR bit 1, TXRQ bit 0
  Reg TDTR;  // DLC bits 3..0
  Reg TDLR;  // data bytes 0..3 (byte 0 in bits 7..0)
  Reg TDHR;  // data bytes 4..7
};
struct RxFifo {
  Reg RIR;   // as TIR
  Reg RDTR;  // DLC bits 3..0, FMI bits 15..8, TIME bits 31..16
  Reg RDLR;
  Reg RDHR;
};
struct FilterBank {
  Reg FR1;  // 32-bit mask mode: identifier
  Reg FR2;  //                   mask
};

struct Registers {
  Reg MCR;                // 0x000
  Reg MSR;                // 0x004
  Reg TSR;                // 0x008
  Reg RF0R;               // 0x00C
  Reg RF1R;               // 0x010
  Reg IER;                // 0x014
  Reg ESR;                // 0x018
  Reg BTR;                // 0x01C
  Reg reserved0[88];      // 0x020..0x17F
  TxMailbox TX[3];        // 0x180
  RxFifo RX[2];           // 0x1B0
  Reg reserved1[12];      // 0x1D0..0x1FF
  Reg FMR;                // 0x200
  Reg FM1R;               // 0x204: 0 mask mode, 1 list mode
  Reg reserved2;
  Reg FS1R;               // 0x20C: 1 = single 32-bit scale
  Reg reserved3;
  Reg FFA1R;              // 0x214: FIFO assignment
  Reg reserved4;
  Reg FA1R;               // 0x21C: filter active
  Reg reserved5[8];       // 0x220..0x23F
  FilterBank FB[28];      // 0x240
};
static_assert(offsetof(Registers, TX) == 0x180);
static_assert(offsetof(Registers, RX) == 0x1B0);
static_assert(offsetof(Registers, FMR) == 0x200);
static_assert(offsetof(Registers, FA1R) == 0x21C);
static_assert(offsetof(Registers, FB) == 0x240);

constexpr uintptr_t kCan1 = 0x40006400;
inline Registers& can1() { return block<Registers>(kCan1); }

// MCR
constexpr uint32_t kMcrInrq = bit(0);
constexpr uint32_t kMcrSleep = bit(1);
constexpr uint32_t kMcrTxfp = bit(2);   // transmit in request order (SPEC §4.3)
constexpr uint32_t kMcrAbom = bit(6);   // leave bus-off automatically
constexpr uint32_t kMcrReset = bit(15);
constexpr uint32_t kMcrDbf = bit(16);   // freeze during debug
// MSR
constexpr uint32_t kMsrInak = bit(0);
constexpr uint32_t kMsrSlak = bit(1);
// TSR
constexpr uint32_t kTsrTme0 = bit(26);
constexpr unsigned kTsrCode = 24;       // 2 bits: next free mailbox
constexpr uint32_t kTsrTmeAll = bit(26) | bit(27) | bit(28);
// RFxR
constexpr uint32_t kRfFmp = mask(2, 0);
constexpr uint32_t kRfFovr = bit(4);
constexpr uint32_t kRfRfom = bit(5);
// IER
constexpr uint32_t kIerFmpie0 = bit(1);
constexpr uint32_t kIerFmpie1 = bit(4);
constexpr uint32_t kIerErrie = bit(15);
constexpr uint32_t kIerBofie = bit(10);
constexpr uint32_t kIerLecie = bit(11);
// ESR
constexpr uint32_t kEsrBoff = bit(2);
constexpr unsigned kEsrLec = 4;         // 3 bits: last error code
constexpr unsigned kEsrTec = 16;
constexpr unsigned kEsrRec = 24;
// BTR: bit time = (1 + TS1 + 1 + TS2 + 1) quanta of (BRP + 1) APB1 clocks
constexpr unsigned kBtrBrp = 0;
constexpr unsigned kBtrTs1 = 16;
constexpr unsigned kBtrTs2 = 20;
constexpr unsigned kBtrSjw = 24;
// Identifier registers
constexpr uint32_t kIdTxrq = bit(0);
constexpr uint32_t kIdRtr = bit(1);
constexpr uint32_t kIdIde = bit(2);
constexpr unsigned kIdExtShift = 3;
// FMR
constexpr uint32_t kFmrFinit = bit(0);

}  // namespace tetrapulse::stm32f405::can
