#include "tetrapulse/ros2/status_diagnostics.hpp"

#include <fmt/format.h>

namespace tetrapulse::ros2 {

namespace {

void add_durations(const char* what, const DurationStats& d, DiagnosticEntry* e) {
  const auto ms = [](int64_t ns) { return fmt::format("{:.3f}", double(ns) * 1e-6); };
  e->values.emplace_back(fmt::format("{}_last_ms", what), ms(d.last_ns));
  e->values.emplace_back(fmt::format("{}_mean_ms", what), ms(d.mean_ns()));
  e->values.emplace_back(fmt::format("{}_max_ms", what), ms(d.max_ns));
}

uint8_t board_level(BoardSyncState s) {
  switch (s) {
    case BoardSyncState::kSynchronized:
    case BoardSyncState::kFreeRunning:
      return kDiagnosticOk;
    case BoardSyncState::kLost:
      return kDiagnosticError;
    case BoardSyncState::kAcquiring:
    case BoardSyncState::kUnknown:
      break;
  }
  return kDiagnosticWarn;
}

}  // namespace

void DurationStats::add(int64_t ns) {
  ++count;
  last_ns = ns;
  max_ns = count == 1 ? ns : std::max(max_ns, ns);
  total_ns += ns;
}

const char* board_sync_state_name(BoardSyncState state) {
  switch (state) {
    case BoardSyncState::kSynchronized: return "synchronized";
    case BoardSyncState::kAcquiring: return "acquiring";
    case BoardSyncState::kFreeRunning: return "free-running";
    case BoardSyncState::kLost: return "lost";
    case BoardSyncState::kUnknown: break;
  }
  return "unknown";
}

std::vector<DiagnosticEntry> status_diagnostics(const LocalizerStatus& status, const std::string& node_name,
                                                const std::string& camera_frame, uint64_t dropped_in_window) {
  std::vector<DiagnosticEntry> out;
  DiagnosticEntry loc;
  loc.name = node_name + ": localizer";
  loc.hardware_id = camera_frame;
  std::string ids;
  for (int id : status.targets_with_pose) ids += (ids.empty() ? "" : " ") + std::to_string(id);
  loc.level = (dropped_in_window > 0 || status.targets_with_pose.empty()) ? kDiagnosticWarn : kDiagnosticOk;
  loc.message = fmt::format("{} target{} with a pose, {} frames, {} dropped", status.targets_with_pose.size(),
                            status.targets_with_pose.size() == 1 ? "" : "s", status.frames_matched,
                            status.frames_dropped);
  loc.values.emplace_back("frames_matched", std::to_string(status.frames_matched));
  loc.values.emplace_back("frames_dropped", std::to_string(status.frames_dropped));
  loc.values.emplace_back("targets_with_pose", ids);
  if (const auto& l = status.live) {
    loc.values.emplace_back("frames_localized", std::to_string(l->frames_localized));
    loc.values.emplace_back("queue_drops", std::to_string(l->queue_drops));
    loc.values.emplace_back("bad_buffers", std::to_string(l->bad_buffers));
    loc.values.emplace_back("exposures_without_frame", std::to_string(l->exposures_without_frame));
    loc.values.emplace_back("frames_without_exposure", std::to_string(l->frames_without_exposure));
  }
  if (status.processing) add_durations("processing", *status.processing, &loc);
  if (status.latency) add_durations("latency", *status.latency, &loc);
  out.push_back(std::move(loc));

  for (const BoardSync& b : status.boards) {
    DiagnosticEntry e;
    e.name = node_name + ": board " + b.board;
    e.hardware_id = b.board;
    e.level = board_level(b.state);
    e.message = board_sync_state_name(b.state);
    if (b.target_id >= 0) e.values.emplace_back("target", std::to_string(b.target_id));
    e.values.emplace_back("sync_state", board_sync_state_name(b.state));
    if (b.offset_ns) e.values.emplace_back("offset_ns", std::to_string(*b.offset_ns));
    if (b.rate_ppm) e.values.emplace_back("rate_ppm", fmt::format("{:.3f}", *b.rate_ppm));
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace tetrapulse::ros2
