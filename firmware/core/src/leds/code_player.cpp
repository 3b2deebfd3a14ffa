#include "tetrapulse/fw/leds/code_player.hpp"

namespace tetrapulse::fw {

void CodePlayer::play(const LedProgram& program) {
  program_ = program;
  if (!identifying_) dirty_ = true;
}

void CodePlayer::identify(const LedProgram& program, Tick until) {
  identify_program_ = program;
  identifying_ = true;
  identify_until_ = until;
  dirty_ = true;
}

void CodePlayer::stop_identify() {
  if (!identifying_) return;
  identifying_ = false;
  dirty_ = true;
}

void CodePlayer::advance(size_t m, Cursor& c) const {
  // The next bit whose duty differs from the one last scheduled: at most one code length
  // away, or never (a code of equal bits, or no code).
  const LedProgram& p = active();
  const uint32_t length = p.codes[m].length;
  for (uint32_t i = 1; i <= length; ++i) {
    if (p.duty(m, c.bit + i) != c.duty) {
      c.bit += i;
      return;
    }
  }
  c.done = true;
}

void CodePlayer::restart(Tick now, const ClockMapping& clock) {
  // Every marker goes to the level of the bit playing a lead time from now, then follows
  // its code from there.
  leds_.cancel();
  const LedProgram& p = active();
  const Tick at = now + leds_.lead_ticks() + 1;
  const int64_t rig = clock.to_rig(at);
  const int64_t bit = protocol::bit_number(p.timebase, rig);
  for (uint8_t m = 0; m < kLedCount; ++m) {
    Cursor& c = cursors_[m];
    c = Cursor{};
    c.bit = bit;
    c.duty = p.duty(m, bit);
    if (leds_.schedule(m, c.duty, at)) {
      log_.append(rig, at, m, c.duty);
    } else {
      leds_.set_now(m, c.duty);
    }
    advance(m, c);
  }
}

void CodePlayer::service(Tick now, const ClockMapping& clock, uint32_t clock_generation) {
  if (identifying_ && identify_until_ != 0 && now >= identify_until_) {
    identifying_ = false;
    dirty_ = true;
  }
  if (clock_generation != generation_ || !started_) {
    generation_ = clock_generation;
    started_ = true;
    dirty_ = true;
  }
  if (dirty_) {
    dirty_ = false;
    restart(now, clock);
  }
  const LedProgram& p = active();
  const Tick earliest = now + leds_.lead_ticks();
  const int64_t horizon = clock.to_rig(now) + kHorizonNs;
  const size_t depth = leds_.queue_depth();
  for (uint8_t m = 0; m < kLedCount; ++m) {
    Cursor& c = cursors_[m];
    while (!c.done && leds_.pending(m) < depth) {
      const int64_t rig = protocol::bit_start(p.timebase, c.bit);
      if (rig > horizon) break;
      const Tick at = clock.to_local(rig);
      if (at < earliest) {
        // Too late for this edge: play the bit that is current at the earliest tick the
        // driver still takes, so the level is right again from there.
        ++late_;
        const Tick catch_up = earliest + 1;
        const int64_t bit = protocol::bit_number(p.timebase, clock.to_rig(catch_up));
        const uint16_t duty = p.duty(m, bit);
        if (duty != c.duty && leds_.schedule(m, duty, catch_up)) {
          log_.append(clock.to_rig(catch_up), catch_up, m, duty);
          c.duty = duty;
        }
        c.bit = bit;
        advance(m, c);
        continue;
      }
      const uint16_t duty = p.duty(m, c.bit);
      if (!leds_.schedule(m, duty, at)) break;
      log_.append(rig, at, m, duty);
      c.duty = duty;
      advance(m, c);
    }
  }
}

}  // namespace tetrapulse::fw
