#include "code_reading.hpp"

namespace tetrapulse::localizer_internal {
namespace {

const TrackBits& no_bits() {
  static const TrackBits unknown = [] {
    TrackBits b;
    b.fill(ReadBit::kUnknown);
    return b;
  }();
  return unknown;
}

}  // namespace

CodeReading::CodeReading(const TargetsFile& targets, const BitReading& reading,
                         const FrequencyIdentifierOptions& frequency, int samples, bool frequency_coded)
    : targets_(targets),
      reading_(reading),
      frequency_options_(frequency),
      samples_(samples),
      coded_(targets.modulation.kind != ModulationKind::kConstant),
      frequency_coded_(frequency_coded) {}

size_t CodeReading::first_of_newest(const BlobTrack& track, int samples) {
  const size_t n = track.history().size();
  return n > size_t(samples) ? n - size_t(samples) : 0;
}

void CodeReading::update(const BlobTracker& tracker, int64_t frame) {
  for (auto it = bits_.begin(); it != bits_.end();) it = tracker.find(it->first) ? std::next(it) : bits_.erase(it);
  if (coded_) {
    for (const BlobTrack& track : tracker.tracks())
      bits_[track.id()].update(track.history(), targets_.modulation, reading_, first_of_newest(track, samples_));
  }
  if (!frequency_coded_) return;
  for (auto it = frequencies_.begin(); it != frequencies_.end();)
    it = tracker.find(it->first) ? std::next(it) : frequencies_.erase(it);
  for (const BlobTrack& track : tracker.tracks()) {
    const TrackSample& newest = track.history().newest();
    if (newest.frame != frame) continue;
    frequencies_.try_emplace(track.id(), targets_, frequency_options_).first->second.push(newest);
  }
}

const TrackBits& CodeReading::bits(int64_t track_id) const {
  const auto it = bits_.find(track_id);
  return it != bits_.end() ? it->second.bits() : no_bits();
}

const FrequencyDecision* CodeReading::frequency_decision(int64_t track_id) {
  const auto it = frequencies_.find(track_id);
  return it != frequencies_.end() ? &it->second.decision() : nullptr;
}

int CodeReading::frequency_code(int64_t track_id) {
  const FrequencyDecision* d = frequency_decision(track_id);
  return d && d->kind == FrequencyDecision::Kind::kFrequency ? d->code : -1;
}

}  // namespace tetrapulse::localizer_internal
