#include "tetrapulse/localizer/frequency_identifier.hpp"

#include <algorithm>
#include <cmath>
#include <limits>


namespace tetrapulse {
namespace {

// A code's lit board time before x, for any real board time x (ns).
class CodeWave {
 public:
  CodeWave(const Code& code, double bit_period_ns) : code_(code), T_(bit_period_ns) {
    prefix_.push_back(0);
    for (uint32_t i = 0; i < code.length; ++i) prefix_.push_back(prefix_.back() + (code.bit(i) ? T_ : 0));
    period_ = T_ * code.length;
  }
  double period() const { return period_; }
  double lit_before(double x) const {
    const double cycles = std::floor(x / period_);
    const double r = x - cycles * period_;
    const auto bit = std::min<size_t>(static_cast<size_t>(r / T_), code_.length - 1);
    const double into = code_.bit(static_cast<uint32_t>(bit)) ? r - static_cast<double>(bit) * T_ : 0.0;
    return cycles * prefix_.back() + prefix_[bit] + into;
  }

 private:
  Code code_;
  double T_;
  double period_ = 0;
  std::vector<double> prefix_;
};

struct Fit {
  double rss = std::numeric_limits<double>::infinity();
  double swing = 0;  // b
  double origin = 0;
  double rate = 1;
};

// Samples relative to the newest one's start, as doubles.
struct Window {
  std::vector<double> start, exposure, intensity;
  double mean = 0, tss = 0, peak = 0;
};

// Least squares of intensity = a + b g over the window, b > 0.
Fit fit_template(const CodeWave& wave, const Window& w, double origin, double rate) {
  const size_t n = w.start.size();
  double sg = 0, sgg = 0, sgi = 0;
  for (size_t k = 0; k < n; ++k) {
    const double t0 = origin + rate * w.start[k];
    const double g = (wave.lit_before(t0 + rate * w.exposure[k]) - wave.lit_before(t0)) / (rate * w.exposure[k]);
    sg += g;
    sgg += g * g;
    sgi += g * (w.intensity[k] - w.mean);
  }
  Fit f;
  f.origin = origin;
  f.rate = rate;
  const double var = sgg - sg * sg / static_cast<double>(n);
  if (var <= 1e-12 || sgi <= 0) {
    f.rss = w.tss;  // explains nothing (or only with the polarity reversed)
    return f;
  }
  f.swing = sgi / var;
  f.rss = std::max(0.0, w.tss - sgi * sgi / var);
  return f;
}

// Best origin (and rate) of one code: a grid, then golden-section refinement of the origin.
Fit best_fit(const CodeWave& wave, const Window& w, const std::vector<double>& rates, double bit_period,
             int phase_steps, const double* known_origin) {
  const double exposure = *std::min_element(w.exposure.begin(), w.exposure.end());
  if (known_origin != nullptr) return fit_template(wave, w, *known_origin, 1.0);
  Fit best;
  // A template changes over an exposure's length at its edges, so a grid finer
  // than a quarter exposure finds nothing the refinement below does not.
  const double step = std::max(bit_period / phase_steps, std::min(exposure / 4, wave.period() / 16));
  const int points = static_cast<int>(std::ceil(wave.period() / step));
  for (double rate : rates) {
    for (int g = 0; g < points; ++g) {
      const Fit f = fit_template(wave, w, g * step, rate);
      if (f.rss < best.rss) best = f;
    }
  }
  double lo = best.origin - step, hi = best.origin + step;
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < 12; ++i) {
    const double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
    const Fit f1 = fit_template(wave, w, x1, best.rate), f2 = fit_template(wave, w, x2, best.rate);
    if (f1.rss < best.rss) best = f1;
    if (f2.rss < best.rss) best = f2;
    if (f1.rss < f2.rss) {
      hi = x2;
    } else {
      lo = x1;
    }
  }
  return best;
}

bool same_code(const Code& a, const Code& b, bool any_rotation) {
  if (a.length != b.length) return false;
  for (uint32_t s = 0; s < (any_rotation ? a.length : 1u); ++s) {
    bool equal = true;
    for (uint32_t i = 0; i < a.length && equal; ++i) equal = a.bit(i) == b.bit(i + s);
    if (equal) return true;
  }
  return false;
}

}  // namespace

std::vector<RigCode> rig_codes(const TargetsFile& targets) {
  std::vector<RigCode> out;
  if (targets.modulation.kind == ModulationKind::kConstant) return out;
  const bool free_running = !targets.timebase.synchronized;
  for (size_t t = 0; t < targets.targets.size(); ++t) {
    for (size_t m = 0; m < targets.targets[t].markers.size(); ++m) {
      const std::optional<Code>& code = targets.targets[t].markers[m].code;
      if (!code || code->length == 0) continue;
      auto same = [&](const RigCode& r) { return same_code(r.code, *code, free_running); };
      auto it = std::find_if(out.begin(), out.end(), same);
      if (it == out.end()) {
        RigCode r;
        r.code = *code;
        r.frequency = protocol::is_square_wave(*code);
        out.push_back(r);
        it = out.end() - 1;
      }
      it->markers.emplace_back(t, m);
    }
  }
  return out;
}

std::vector<std::array<int, 4>> frequency_code_of(const TargetsFile& targets, const std::vector<RigCode>& codes) {
  std::vector<std::array<int, 4>> out(targets.targets.size(), std::array<int, 4>{-1, -1, -1, -1});
  for (size_t c = 0; c < codes.size(); ++c)
    if (codes[c].frequency)
      for (const auto& [t, m] : codes[c].markers)
        if (t < out.size() && m < 4) out[t][m] = int(c);
  return out;
}

FrequencyIdentifier::FrequencyIdentifier(const TargetsFile& targets, FrequencyIdentifierOptions options)
    : options_(options), timebase_(targets.timebase), codes_(rig_codes(targets)) {}

void FrequencyIdentifier::push(const FrequencySample& sample) {
  if (sample.exposure_ns <= 0 || !std::isfinite(sample.intensity)) return;
  if (!samples_.empty() && sample.start_ns <= samples_.back().start_ns) return;
  samples_.push_back(sample);
  while (samples_.size() > options_.max_samples) samples_.pop_front();
  stale_ = true;
}

void FrequencyIdentifier::push(const TrackSample& sample) {
  if (sample.measured) {
    push(FrequencySample{sample.timestamp_ns, sample.exposure_ns, sample.intensity});
  } else if (!sample.detected && options_.absent_is_dark) {
    push(FrequencySample{sample.timestamp_ns, sample.exposure_ns, 0.0});
  }
}

void FrequencyIdentifier::reset() {
  samples_.clear();
  stale_ = true;
}

const FrequencyDecision& FrequencyIdentifier::decision() {
  if (stale_) decide();
  stale_ = false;
  return decision_;
}

void FrequencyIdentifier::decide() {
  decision_ = FrequencyDecision{};
  unexplained_.assign(codes_.size(), 1.0);
  const size_t n = samples_.size();
  decision_.samples = n;
  if (n < std::max<size_t>(options_.min_samples, 4) || codes_.empty() || timebase_.bit_period_ns <= 0) return;

  Window w;
  const int64_t reference = samples_.back().start_ns;
  for (const FrequencySample& s : samples_) {
    w.start.push_back(static_cast<double>(s.start_ns - reference));
    w.exposure.push_back(static_cast<double>(s.exposure_ns));
    w.intensity.push_back(s.intensity);
    w.mean += s.intensity;
    w.peak = std::max(w.peak, s.intensity);
  }
  w.mean /= static_cast<double>(n);
  for (double i : w.intensity) w.tss += (i - w.mean) * (i - w.mean);
  if (w.tss <= 0) return;

  // Three rates when 200 ppm slips the code by more than half a grid step over the window.
  const double T = static_cast<double>(timebase_.bit_period_ns);
  const double span = -w.start.front() + w.exposure.back();
  std::vector<double> rates{1.0};
  if (span * options_.clock_ppm * 1e-6 > 0.5 * T / options_.phase_steps) {
    rates = {1.0 - options_.clock_ppm * 1e-6, 1.0, 1.0 + options_.clock_ppm * 1e-6};
  }
  std::vector<Fit> fits(codes_.size());
  for (size_t c = 0; c < codes_.size(); ++c) {
    const CodeWave wave(codes_[c].code, T);
    if (timebase_.synchronized) {
      // Board time at the reference is rig time minus the epoch, taken modulo the period in integers.
      const int64_t period = timebase_.bit_period_ns * codes_[c].code.length;
      const double origin = static_cast<double>(((reference - timebase_.epoch_ns) % period + period) % period);
      fits[c] = best_fit(wave, w, rates, T, options_.phase_steps, &origin);
    } else {
      fits[c] = best_fit(wave, w, rates, T, options_.phase_steps, nullptr);
    }
    unexplained_[c] = fits[c].rss / w.tss;
  }
  size_t best = 0;
  for (size_t c = 1; c < codes_.size(); ++c) {
    if (fits[c].rss < fits[best].rss) best = c;
  }
  double rival = w.tss;  // no rival: the constant explains nothing either
  for (size_t c = 0; c < codes_.size(); ++c) {
    if (c != best) rival = std::min(rival, fits[c].rss);
  }
  const Fit& f = fits[best];
  const double sigma2 = std::max(f.rss / static_cast<double>(n - 3), std::pow(options_.noise_floor * f.swing, 2));
  decision_.code = static_cast<int>(best);
  decision_.fit = 1.0 - f.rss / w.tss;
  decision_.evidence = sigma2 > 0 ? (rival - f.rss) / (2.0 * sigma2) : 0.0;
  decision_.reference_ns = reference;
  decision_.origin_ns = f.origin;
  decision_.rate = f.rate;
  const bool modulated = f.swing >= options_.min_modulation * w.peak;
  if (decision_.fit >= options_.min_fit && modulated && decision_.evidence >= options_.min_evidence) {
    decision_.kind = codes_[best].frequency ? FrequencyDecision::Kind::kFrequency : FrequencyDecision::Kind::kBinary;
  }
}

}  // namespace tetrapulse
