#pragma once
// USB on-the-go full-speed core in device mode (RM0090 §34.16), at 0x50000000.
// Offsets rather than one struct: the block spans 0x20000 bytes with sparse registers.
#include "tetrapulse/stm32f405/registers/mmio.hpp"

namespace tetrapulse::stm32f405::otg {

constexpr uintptr_t kBase = 0x50000000;
inline Reg& at(uintptr_t offset) { return *reinterpret_cast<Reg*>(kBase + offset); }

// Global registers
inline Reg& GOTGCTL() { return at(0x000); }
inline Reg& GAHBCFG() { return at(0x008); }
inline Reg& GUSBCFG() { return at(0x00C); }
inline Reg& GRSTCTL() { return at(0x010); }
inline Reg& GINTSTS() { return at(0x014); }
inline Reg& GINTMSK() { return at(0x018); }
inline Reg& GRXSTSP() { return at(0x020); }
inline Reg& GRXFSIZ() { return at(0x024); }
inline Reg& DIEPTXF0() { return at(0x028); }  // EP0 TX FIFO: start word 15..0, depth 31..16
inline Reg& GCCFG() { return at(0x038); }
inline Reg& DIEPTXF(unsigned ep) { return at(0x104 + 4 * (ep - 1)); }  // ep 1..3
// Device registers
inline Reg& DCFG() { return at(0x800); }
inline Reg& DCTL() { return at(0x804); }
inline Reg& DSTS() { return at(0x808); }
inline Reg& DIEPMSK() { return at(0x810); }
inline Reg& DOEPMSK() { return at(0x814); }
inline Reg& DAINT() { return at(0x818); }
inline Reg& DAINTMSK() { return at(0x81C); }
inline Reg& DIEPEMPMSK() { return at(0x834); }
inline Reg& DIEPCTL(unsigned ep) { return at(0x900 + 0x20 * ep); }
inline Reg& DIEPINT(unsigned ep) { return at(0x908 + 0x20 * ep); }
inline Reg& DIEPTSIZ(unsigned ep) { return at(0x910 + 0x20 * ep); }
inline Reg& DTXFSTS(unsigned ep) { return at(0x918 + 0x20 * ep); }
inline Reg& DOEPCTL(unsigned ep) { return at(0xB00 + 0x20 * ep); }
inline Reg& DOEPINT(unsigned ep) { return at(0xB08 + 0x20 * ep); }
inline Reg& DOEPTSIZ(unsigned ep) { return at(0xB10 + 0x20 * ep); }
inline Reg& PCGCCTL() { return at(0xE00); }
inline Reg& FIFO(unsigned ep) { return at(0x1000 * (ep + 1)); }

// GAHBCFG
constexpr uint32_t kGahbGint = bit(0);
// GUSBCFG
constexpr uint32_t kGusbPhysel = bit(6);
constexpr unsigned kGusbTrdt = 10;            // 4 bits: turnaround time
constexpr uint32_t kGusbForceDevice = bit(30);
// GRSTCTL
constexpr uint32_t kGrstCsrst = bit(0);
constexpr uint32_t kGrstRxfflsh = bit(4);
constexpr uint32_t kGrstTxfflsh = bit(5);
constexpr unsigned kGrstTxfnum = 6;           // 5 bits; 0x10 = all
constexpr uint32_t kGrstAhbidl = bit(31);
// GINTSTS / GINTMSK
constexpr uint32_t kGintRxflvl = bit(4);
constexpr uint32_t kGintUsbsusp = bit(11);
constexpr uint32_t kGintUsbrst = bit(12);
constexpr uint32_t kGintEnumdne = bit(13);
constexpr uint32_t kGintIepint = bit(18);
constexpr uint32_t kGintOepint = bit(19);
constexpr uint32_t kGintWkupint = bit(31);
// GRXSTSP (device)
constexpr unsigned kRxEpnum = 0;              // 4 bits
constexpr unsigned kRxBcnt = 4;               // 11 bits
constexpr unsigned kRxPktsts = 17;            // 4 bits
constexpr uint32_t kPktOutData = 2;
constexpr uint32_t kPktOutDone = 3;
constexpr uint32_t kPktSetupDone = 4;
constexpr uint32_t kPktSetupData = 6;
// GCCFG
constexpr uint32_t kGccfgPwrdwn = bit(16);    // transceiver on
constexpr uint32_t kGccfgVbusbsen = bit(19);
constexpr uint32_t kGccfgNovbussens = bit(21);
// DCFG
constexpr unsigned kDcfgDspd = 0;             // 2 bits: 3 = full speed (internal PHY)
constexpr unsigned kDcfgDad = 4;              // 7 bits: device address
// DCTL
constexpr uint32_t kDctlSdis = bit(1);        // soft disconnect
constexpr uint32_t kDctlCginak = bit(8);
constexpr uint32_t kDctlCgonak = bit(10);
// DIEPCTL / DOEPCTL
constexpr unsigned kEpMpsiz = 0;              // EP0: 2 bits (0 = 64 bytes); others: 11 bits
constexpr uint32_t kEpUsbaep = bit(15);
constexpr unsigned kEpType = 18;              // 2 bits: 2 = bulk
constexpr uint32_t kEpStall = bit(21);
constexpr unsigned kEpTxfnum = 22;            // 4 bits (IN)
constexpr uint32_t kEpCnak = bit(26);
constexpr uint32_t kEpSnak = bit(27);
constexpr uint32_t kEpSd0pid = bit(28);
constexpr uint32_t kEpEpdis = bit(30);
constexpr uint32_t kEpEpena = bit(31);
// DIEPINT / DOEPINT
constexpr uint32_t kEpXfrc = bit(0);
constexpr uint32_t kEpStup = bit(3);          // OUT: setup phase done
constexpr uint32_t kEpTxfe = bit(7);          // IN: TX FIFO empty
// DIEPTSIZ / DOEPTSIZ
constexpr unsigned kTsizXfrsiz = 0;           // 19 bits (EP0: 7)
constexpr unsigned kTsizPktcnt = 19;          // 10 bits (EP0: IN 2 bits, OUT 1 bit)
constexpr unsigned kTsizStupcnt = 29;         // EP0 OUT: 2 bits

}  // namespace tetrapulse::stm32f405::otg
