#include "tetrapulse/stm32f405/local_timer.hpp"

#include "tetrapulse/stm32f405/gpio_setup.hpp"
#include "tetrapulse/stm32f405/interrupt_handlers.hpp"
#include "tetrapulse/stm32f405/pinout.hpp"
#include "tetrapulse/stm32f405/registers/core.hpp"
#include "tetrapulse/stm32f405/registers/rcc.hpp"
#include "tetrapulse/stm32f405/registers/timer.hpp"

namespace tetrapulse::stm32f405 {
namespace {

constexpr unsigned kCompareChannel = 0;  // CH1
constexpr unsigned kCaptureChannel = 1;  // CH2
constexpr uint32_t kCaptureFilter = 3;   // ICxF = 0011: 8 samples at f_CK_INT, rejects < 100 ns glitches
constexpr uint8_t kIrqPriority = 1;      // above the links: overflow counting must not lag

}  // namespace

LocalTimer& local_timer() {
  static LocalTimer timer;
  return timer;
}

void LocalTimer::start(uint32_t timer_clock_hz) {
  const uint32_t divider = (timer_clock_hz + kMaxTickHz - 1) / kMaxTickHz;
  tick_hz_ = timer_clock_hz / divider;
  rcc::Registers& r = rcc::regs();
  r.APB1ENR = r.APB1ENR | rcc::kApb1Tim2;
  (void)r.APB1ENR;  // the enable takes effect before the timer is touched (RM0090 §7.3)
  tim::Registers& t = tim::tim2();
  t.CR1 = 0;
  t.PSC = divider - 1;
  t.ARR = 0xFFFFFFFFu;
  t.CR2 = field(tim::kMmsComparePulse, tim::kCr2Mms);
  t.CCMR1 = field(tim::kCcsOutput | field(tim::kOcFrozen, tim::kOcMode), tim::ccmr_shift(kCompareChannel));
  t.EGR = tim::kEgrUg;  // load PSC and ARR now
  t.SR = 0;
  t.CNT = 0;
  high_ = 0;
  t.DIER = tim::kUif;
  t.CR1 = tim::kCr1Cen;
  nvic::enable(nvic::kTim2, kIrqPriority);
}

uint64_t LocalTimer::read() const {
  const tim::Registers& t = tim::tim2();
  InterruptLock lock;
  uint32_t high = high_;
  const uint32_t low = t.CNT;
  // An overflow that happened but whose interrupt has not run yet (we hold it off):
  // a small counter value after the flag means the wrap came first.
  if ((t.SR & tim::kUif) != 0 && low < 0x80000000u) ++high;
  return (static_cast<uint64_t>(high) << 32) | low;
}

uint64_t LocalTimer::extend_past(uint32_t counter_value) const {
  const uint64_t n = read();
  return n - static_cast<uint32_t>(static_cast<uint32_t>(n) - counter_value);
}

void LocalTimer::enable_capture(bool falling, CaptureCallback callback, void* context) {
  {
    InterruptLock lock;
    capture_ = callback;
    capture_context_ = context;
  }
  configure_alternate(pin_of(Signal::kSyncInput), gpio::kPullDown);
  tim::Registers& t = tim::tim2();
  const unsigned shift = tim::ccmr_shift(kCaptureChannel);
  t.CCER = t.CCER & ~(tim::ccer_enable(kCaptureChannel) | tim::ccer_polarity(kCaptureChannel));
  t.CCMR1 = (t.CCMR1 & ~(0xFFu << shift)) |
            (field(tim::kCcsInputTi | field(kCaptureFilter, tim::kIcFilter), shift));
  t.CCER = t.CCER | tim::ccer_enable(kCaptureChannel) |
           (falling ? tim::ccer_polarity(kCaptureChannel) : 0);
  t.SR = ~(tim::kCc2if | tim::kCc2of);
  t.DIER = t.DIER | tim::kCc2if;
}

void LocalTimer::disable_capture() {
  tim::Registers& t = tim::tim2();
  t.DIER = t.DIER & ~tim::kCc2if;
  t.CCER = t.CCER & ~tim::ccer_enable(kCaptureChannel);
}

bool LocalTimer::arm_compare(uint64_t at) {
  tim::Registers& t = tim::tim2();
  InterruptLock lock;
  t.CCR[kCompareChannel] = static_cast<uint32_t>(at);
  // Checked after writing: a counter already at or past `at` matches only after a wrap.
  return static_cast<int64_t>(at - read()) > 0;
}

void LocalTimer::on_interrupt() {
  tim::Registers& t = tim::tim2();
  const uint32_t sr = t.SR;
  const uint32_t enabled = t.DIER;
  if ((sr & tim::kUif) != 0) {
    t.SR = ~tim::kUif;
    high_ = high_ + 1;
  }
  if ((sr & tim::kCc2if & enabled) != 0) {
    const uint32_t captured = t.CCR[kCaptureChannel];  // reading clears CC2IF
    t.SR = ~tim::kCc2of;
    if (capture_ != nullptr) capture_(capture_context_, extend_past(captured));
  }
}

}  // namespace tetrapulse::stm32f405

extern "C" void TIM2_IRQHandler() { tetrapulse::stm32f405::local_timer().on_interrupt(); }
