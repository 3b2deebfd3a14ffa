#pragma once
// Board hardware models (wire values in Info and the firmware image header; append only).
#include <cstdint>

namespace tetrapulse::protocol {

enum class HwModel : uint16_t {
  kStm32f405Reference = 1,  // the reference board, STM32F405
  kLinuxBoard = 2,          // a Linux computer acting as a board (libgpiod, SocketCAN, FunctionFS)
  kSimulatedBoard = 3,      // the virtual rig's board
};

constexpr bool is_known(HwModel m) {
  return m == HwModel::kStm32f405Reference || m == HwModel::kLinuxBoard || m == HwModel::kSimulatedBoard;
}

}  // namespace tetrapulse::protocol
