#include "tetrapulse/fw/sync/gpio_edge_numberer.hpp"

#include "tetrapulse/fw/sync/fixed_point.hpp"

namespace tetrapulse::fw {

void GpioEdgeNumberer::configure(const protocol::Config& config, Tick now) {
  epoch_ns_ = config.gpio_edge_epoch_ns;
  period_ns_ = config.gpio_edge_period_ns;
  numbering_ = config.gpio_edge_numbering;
  started_ = now;
  have_last_ = false;
  counting_ = false;
}

void GpioEdgeNumberer::set_coarse_time(Tick local, int64_t rig_ns) {
  have_coarse_ = true;
  coarse_local_ = local;
  coarse_rig_ = rig_ns;
}

int64_t GpioEdgeNumberer::nominal_ns(Tick from, Tick to) const {
  return nominal_.to_rig(to) - nominal_.to_rig(from);
}

int64_t GpioEdgeNumberer::edge_time(int64_t k) const { return epoch_ns_ + k * period_ns_; }

int64_t GpioEdgeNumberer::nearest_k(int64_t rig_ns) const { return div_round(rig_ns - epoch_ns_, period_ns_); }

NumberedEdge GpioEdgeNumberer::number(Tick local, const ClockServo& servo) {
  NumberedEdge out;
  const int64_t gap = have_last_ ? nominal_ns(last_local_, local) : nominal_ns(started_, local);
  if (have_last_ && gap < period_ns_ / 2) {
    out.verdict = EdgeVerdict::kSpurious;
    return out;
  }
  const bool counting = numbering_ == protocol::GpioEdgeNumbering::kCountAfterGap;
  int64_t k = 0;
  if (servo.acquired()) {
    // Our own disciplined clock numbers the edge: a missed edge skips a number.
    k = nearest_k(servo.to_rig(local));
    if (counting && gap >= kCountRestartGapPeriods * period_ns_) {
      k = 0;
      out.restart = true;
    } else if (have_last_ && k <= last_k_) {
      out.verdict = EdgeVerdict::kSpurious;
      return out;
    }
  } else if (counting) {
    if (gap >= 2 * period_ns_) {
      k = 0;
      out.restart = true;
      counting_ = true;
    } else if (counting_ && have_last_) {
      k = last_k_ + div_round(gap, period_ns_);
    } else {
      last_local_ = local;  // still waiting for the gap that starts the count
      have_last_ = true;
      return out;
    }
  } else {
    if (!have_coarse_) return out;
    k = nearest_k(coarse_rig_ + nominal_ns(coarse_local_, local));
  }
  have_last_ = true;
  last_local_ = local;
  last_k_ = k;
  out.verdict = EdgeVerdict::kNumbered;
  out.rig_ns = edge_time(k);
  return out;
}

}  // namespace tetrapulse::fw
