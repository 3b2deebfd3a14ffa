#include "tetrapulse/stm32f405/led_timer.hpp"

#include "tetrapulse/stm32f405/gpio_setup.hpp"
#include "tetrapulse/stm32f405/interrupt_handlers.hpp"
#include "tetrapulse/stm32f405/pinout.hpp"
#include "tetrapulse/stm32f405/registers/core.hpp"
#include "tetrapulse/stm32f405/registers/rcc.hpp"
#include "tetrapulse/stm32f405/registers/timer.hpp"

namespace tetrapulse::stm32f405 {
namespace {

constexpr uint8_t kIrqPriority = 0;        // the highest: preloads are written right after a UEV
constexpr uint32_t kLeadUs = 20;           // interrupt entry and arming, with room to spare
constexpr uint16_t kFullScaleMa = 350;     // the reference board's LED drivers (hardware/ notes)
constexpr Signal kLedPins[fw::kLedCount] = {Signal::kLed0, Signal::kLed1, Signal::kLed2, Signal::kLed3};

}  // namespace

LedTimer& led_timer() {
  static LedTimer leds;
  return leds;
}

void LedTimer::start(uint32_t apb2_timer_hz, LocalTimer& clock) {
  clock_ = &clock;
  period_ = apb2_timer_hz / kPwmHz;
  lead_ticks_ = static_cast<uint32_t>(static_cast<uint64_t>(clock.tick_hz()) * kLeadUs / 1'000'000);
  // Periodic UEVs come every (RCR + 1) PWM periods; a margin of one period covers the
  // trigger's resynchronisation and the two clocks' phase.
  const uint64_t spacing_ns = static_cast<uint64_t>(tim::kRcrMax) * 1'000'000'000ull / kPwmHz;
  uev_spacing_ticks_ = static_cast<uint32_t>(spacing_ns * clock.tick_hz() / 1'000'000'000ull);

  rcc::Registers& r = rcc::regs();
  r.APB2ENR = r.APB2ENR | rcc::kApb2Tim8;
  (void)r.APB2ENR;
  for (Signal s : kLedPins) configure_alternate(pin_of(s));

  tim::Registers& t = tim::tim8();
  t.CR1 = tim::kCr1Arpe;
  t.PSC = 0;
  t.ARR = period_ - 1;
  t.RCR = tim::kRcrMax;
  const uint32_t pwm = tim::kCcsOutput | tim::kOcPreload | field(tim::kOcPwm1, tim::kOcMode);
  t.CCMR1 = field(pwm, tim::ccmr_shift(0)) | field(pwm, tim::ccmr_shift(1));
  t.CCMR2 = field(pwm, tim::ccmr_shift(2)) | field(pwm, tim::ccmr_shift(3));
  for (unsigned ch = 0; ch < fw::kLedCount; ++ch) t.CCR[ch] = 0;
  t.CCER = tim::ccer_enable(0) | tim::ccer_enable(1) | tim::ccer_enable(2) | tim::ccer_enable(3);
  t.BDTR = tim::kBdtrMoe;
  t.SMCR = field(tim::kTsItr1, tim::kSmcrTs) | field(tim::kSmsReset, tim::kSmcrSms);
  t.EGR = tim::kEgrUg;
  t.SR = 0;
  t.DIER = tim::kUif;
  t.CR1 = tim::kCr1Arpe | tim::kCr1Cen;
  last_uev_ = clock.now();
  nvic::enable(nvic::kTim8Up, kIrqPriority);
}

uint32_t LedTimer::compare_value(uint16_t duty) const {
  // PWM mode 1 is high while CNT < CCR: 0 is always off, `period_` always on.
  return static_cast<uint32_t>((static_cast<uint64_t>(duty) * period_ + fw::kDutyFull / 2) / fw::kDutyFull);
}

void LedTimer::write_now(uint8_t index, uint16_t duty) {
  // Every preload back to what shows (nothing armed may leak out), this one to its new
  // duty, then a software UEV moves the preloads out. The caller re-arms.
  tim::Registers& t = tim::tim8();
  duty_[index] = duty;
  for (uint8_t m = 0; m < fw::kLedCount; ++m) t.CCR[m] = compare_value(duty_[m]);
  t.EGR = tim::kEgrUg;
  armed_ = 0;
}

protocol::Status LedTimer::do_schedule(uint8_t index, uint16_t duty, fw::Tick at) {
  if (index >= fw::kLedCount) return protocol::Error::kBadValue;
  InterruptLock lock;
  Queue& q = queues_[index];
  if (q.count == kQueueDepth) return protocol::Error::kBusy;
  if (static_cast<int64_t>(at - clock_->now()) < static_cast<int64_t>(lead_ticks_)) {
    return protocol::Error::kInvalidState;
  }
  q.items[(q.head + q.count) % kQueueDepth] = Change{at, duty};
  ++q.count;
  if (armed_ == 0 || static_cast<int64_t>(at - armed_) < 0) arm_next();
  return {};
}

size_t LedTimer::do_pending(uint8_t index) const {
  if (index >= fw::kLedCount) return 0;
  InterruptLock lock;
  return queues_[index].count;
}

void LedTimer::do_cancel() {
  InterruptLock lock;
  tim::Registers& t = tim::tim8();
  for (uint8_t m = 0; m < fw::kLedCount; ++m) {
    queues_[m].count = 0;
    t.CCR[m] = compare_value(duty_[m]);  // preload back to what shows
  }
  armed_ = 0;
}

void LedTimer::do_set_now(uint8_t index, uint16_t duty) {
  if (index >= fw::kLedCount) return;
  InterruptLock lock;
  write_now(index, duty);
  arm_next();
}

uint16_t LedTimer::do_full_scale_ma() const { return kFullScaleMa; }

void LedTimer::arm_next() {
  tim::Registers& t = tim::tim8();
  // Whatever was preloaded for a later tick goes back to the shown duty first.
  for (uint8_t m = 0; m < fw::kLedCount; ++m) t.CCR[m] = compare_value(duty_[m]);
  armed_ = 0;
  bool any = false;
  fw::Tick next = 0;
  for (const Queue& q : queues_) {
    if (q.count == 0) continue;
    const fw::Tick at = q.items[q.head].at;
    if (!any || static_cast<int64_t>(at - next) < 0) next = at;
    any = true;
  }
  if (!any) return;
  // A periodic UEV before `next` would apply the preload early: wait for it instead;
  // its interrupt arms the change.
  if (static_cast<int64_t>(next - (last_uev_ + uev_spacing_ticks_)) >= 0) return;
  for (uint8_t m = 0; m < fw::kLedCount; ++m) {
    const Queue& q = queues_[m];
    if (q.count != 0 && q.items[q.head].at == next) t.CCR[m] = compare_value(q.items[q.head].duty);
  }
  armed_ = next;
  if (!clock_->arm_compare(next)) {
    // Too late for the trigger: apply now, late.
    for (uint8_t m = 0; m < fw::kLedCount; ++m) t.CCR[m] = compare_value(duty_[m]);
    armed_ = 0;
  }
}

void LedTimer::pop_applied(fw::Tick at) {
  for (uint8_t m = 0; m < fw::kLedCount; ++m) {
    Queue& q = queues_[m];
    if (q.count != 0 && q.items[q.head].at == at) {
      duty_[m] = q.items[q.head].duty;
      q.head = (q.head + 1) % kQueueDepth;
      --q.count;
    }
  }
}

void LedTimer::on_update_event() {
  tim::Registers& t = tim::tim8();
  t.SR = ~tim::kUif;
  const fw::Tick now = clock_->now();
  last_uev_ = now;
  if (armed_ != 0 && static_cast<int64_t>(now - armed_) >= 0) pop_applied(armed_);
  arm_next();
}

void LedTimer::apply_overdue() {
  InterruptLock lock;
  const fw::Tick now = clock_->now();
  bool changed = false;
  for (uint8_t m = 0; m < fw::kLedCount; ++m) {
    Queue& q = queues_[m];
    // Overdue: its tick is a lead time past and no UEV took it (the interrupt would have).
    while (q.count != 0 && static_cast<int64_t>(now - q.items[q.head].at) > static_cast<int64_t>(lead_ticks_)) {
      write_now(m, q.items[q.head].duty);
      q.head = (q.head + 1) % kQueueDepth;
      --q.count;
      ++late_;
      changed = true;
    }
  }
  if (changed) arm_next();
}

}  // namespace tetrapulse::stm32f405

extern "C" void TIM8_UP_TIM13_IRQHandler() { tetrapulse::stm32f405::led_timer().on_update_event(); }
