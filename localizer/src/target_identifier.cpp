#include "tetrapulse/localizer/target_identifier.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "identification_hypothesis.hpp"
#include "track_neighbours.hpp"
#include "tetrapulse/localizer/frequency_identifier.hpp"
#include "tetrapulse/localizer/p3p.hpp"
#include "tetrapulse/localizer/target_appearance.hpp"
#include "tetrapulse/localizer/p4p.hpp"
#include "tetrapulse/localizer/pose_refinement.hpp"

namespace tetrapulse {

namespace {

// A known-order P4P pose (three markers exact, the fourth's error shared out)
// that misses the geometry bound by this factor does not refine to within it:
// not refined (most hypotheses of weak codes are such).
constexpr double kMaxUnrefinedRms = 2.0;

int64_t gcd(int64_t a, int64_t b) { return b == 0 ? a : gcd(b, a % b); }

// Whether the geometry check sees two targets alike: marker positions and size.
bool same_markers(const Target& a, const Target& b) {
  if (a.marker_diameter_m != b.marker_diameter_m) return false;
  for (size_t m = 0; m < 4; ++m)
    if (a.markers[m].position_m != b.markers[m].position_m) return false;
  return true;
}

constexpr uint64_t kNoSharedKey = ~uint64_t(0);

}  // namespace

TargetIdentifier::TargetIdentifier(const CameraModel& camera, const TargetsFile& targets,
                                   IdentificationOptions options)
    : camera_(camera),
      targets_(targets),
      options_(options),
      neighbours_(std::make_unique<localizer_internal::TrackNeighbours>()) {
  coded_ = targets.modulation.kind != ModulationKind::kConstant;
  free_running_ = coded_ && !targets.timebase.synchronized;
  frequency_of_ = frequency_code_of(targets, rig_codes(targets));
  look_of_ = rig_looks(BlobExtractorConfig{}, targets).look_of;
  for (size_t ti = 0; ti < targets.targets.size(); ++ti) {
    const Target& t = targets.targets[ti];
    std::array<int, 4> of{-1, -1, -1, -1};
    double extent = 0;
    for (size_t m = 0; m < 4; ++m) {
      for (size_t k = 0; k < 4; ++k)
        extent = std::max(extent, (t.markers[m].position_m - t.markers[k].position_m).norm());
      if (!coded_ || !t.markers[m].code || frequency_of_[ti][m] >= 0) continue;
      const auto it = std::find(codes_.begin(), codes_.end(), *t.markers[m].code);
      of[m] = int(it - codes_.begin());
      if (it == codes_.end()) codes_.push_back(*t.markers[m].code);
    }
    code_of_.push_back(of);
    bool same = coded_ && (of[0] >= 0 || frequency_of_[ti][0] >= 0);
    for (size_t m = 1; m < 4; ++m)
      same = same && of[m] == of[0] && frequency_of_[ti][m] == frequency_of_[ti][0] && look_of_[ti][m] == look_of_[ti][0];
    interchangeable_.push_back(same);
    extent_ratio_.push_back(t.marker_diameter_m > 0 ? extent / (t.marker_diameter_m / 2) : 1e9);
    // The first target with the same markers (positions, size) names the class.
    size_t first = 0;
    while (first < ti && !same_markers(targets.targets[first], t)) ++first;
    geometry_class_.push_back(first == ti ? uint32_t(ti) : geometry_class_[first]);
  }
}

TargetIdentifier::~TargetIdentifier() = default;
TargetIdentifier::TargetIdentifier(TargetIdentifier&&) noexcept = default;

Identification TargetIdentifier::identification_of(const Hypothesis& h, const std::array<int64_t, 4>& track_ids) const {
  Identification id;
  id.target = h.target;
  id.track_of = track_ids;
  id.pose = h.pose;
  id.rms_px = h.rms_px;
  id.codes = h.codes;
  id.clock = CodeClock::from(targets_.timebase);
  if (free_running_) id.clock.origin_ns = phase_origin(0, targets_.timebase.bit_period_ns, options_.phase_steps, h.phase);
  return id;
}

bool TargetIdentifier::has_binary_codes(size_t target) const {
  for (int c : code_of_[target])
    if (c >= 0) return true;
  return false;
}

double TargetIdentifier::allowed_errors(int counted) const {
  return std::floor(double(counted) / double(std::max(options_.bits_per_error, 1)));
}

void TargetIdentifier::score_tracks(const std::vector<CandidateTrack>& tracks) {
  track_codes_.resize(tracks.size());
  const int64_t T = targets_.timebase.bit_period_ns;
  for (size_t i = 0; i < tracks.size(); ++i) {
    TrackCodes& tc = track_codes_[i];
    const auto& history = tracks[i].track->history();
    tc.from = history.size() > size_t(options_.max_samples) ? history.size() - size_t(options_.max_samples) : 0;
    tc.best_cost.assign(codes_.size(), 0.0);
    if (free_running_) {
      tc.phases.resize(codes_.size());
      for (size_t c = 0; c < codes_.size(); ++c) {
        match_code_phases(history, *tracks[i].bits, tc.from, 0, T, options_.phase_steps, codes_[c], &tc.phases[c]);
        double best = std::numeric_limits<double>::infinity();
        for (const CodeMatch& m : tc.phases[c]) best = std::min(best, m.cost());
        tc.best_cost[c] = best;
      }
    } else {
      tc.matches.resize(codes_.size());
      const CodeClock clock = CodeClock::from(targets_.timebase);
      for (size_t c = 0; c < codes_.size(); ++c) {
        tc.matches[c] = match_code(history, *tracks[i].bits, tc.from, clock, codes_[c]);
        tc.best_cost[c] = tc.matches[c].cost();
      }
    }
  }
}

void TargetIdentifier::score_codes(Hypothesis* h) const {
  const std::array<int, 4>& code = code_of_[h->target];
  if (!coded_) return;
  if (!free_running_) {
    h->codes = CodeMatch{};
    for (int m = 0; m < 4; ++m)
      if (code[size_t(m)] >= 0 && h->track[size_t(m)] >= 0)
        h->codes += track_codes_[size_t(h->track[size_t(m)])].matches[size_t(code[size_t(m)])];
    h->cost = h->codes.cost();
    return;
  }
  // One clock for the target's board: the phase that explains all four tracks best.
  // Phases repeat with the least common multiple of the code lengths.
  int64_t period = 1;
  for (int c : code)
    if (c >= 0) period = period / gcd(period, codes_[size_t(c)].length) * codes_[size_t(c)].length;
  const int phases = int(std::min<int64_t>(period, 4096)) * options_.phase_steps;
  std::vector<double> cost(size_t(phases), 0.0);
  for (int g = 0; g < phases; ++g)
    for (int m = 0; m < 4; ++m) {
      if (code[size_t(m)] < 0 || h->track[size_t(m)] < 0) continue;
      const auto& table = track_codes_[size_t(h->track[size_t(m)])].phases[size_t(code[size_t(m)])];
      cost[size_t(g)] += table[size_t(g) % table.size()].cost();
    }
  const double best = *std::min_element(cost.begin(), cost.end());
  // The middle of the run of best phases (cyclic) that contains the first best one:
  // the bits only bound the phase, and its middle keeps clear of both ends.
  int first = int(std::min_element(cost.begin(), cost.end()) - cost.begin());
  int begin = first, length = 1;
  while (length < phases && cost[size_t((begin - 1 + phases) % phases)] == best) begin = (begin - 1 + phases) % phases, ++length;
  while (length < phases && cost[size_t((first + 1) % phases)] == best) first = (first + 1) % phases, ++length;
  h->phase = (begin + length / 2) % phases;
  h->cost = best;
  h->shifted_cost = std::numeric_limits<double>::infinity();
  for (int g = 0; g < phases; ++g) {
    const int after_begin = (g - begin + phases) % phases;  // 0 .. phases - 1
    const int outside = after_begin - (length - 1);          // > 0: past the run's end
    if (outside > options_.phase_steps && phases - after_begin > options_.phase_steps) {
      h->shifted_cost = std::min(h->shifted_cost, cost[size_t(g)]);
    }
  }
  h->codes = CodeMatch{};
  for (int m = 0; m < 4; ++m) {
    if (code[size_t(m)] < 0 || h->track[size_t(m)] < 0) continue;
    const auto& table = track_codes_[size_t(h->track[size_t(m)])].phases[size_t(code[size_t(m)])];
    h->codes += table[size_t(h->phase) % table.size()];
  }
  h->cost = std::min(h->cost, h->codes.cost());
}

bool TargetIdentifier::may_be(const CandidateTrack& track, size_t i, size_t t, size_t m) const {
  if (track.look != look_of_[t][m]) return false;
  // A frequency code's marker takes exactly its tracks; a binary one none of them.
  const int frequency = frequency_of_[t][m];
  if (frequency >= 0 ? track.frequency_code != frequency : track.frequency_code >= 0) return false;
  const int code = code_of_[t][m];
  if (code < 0) return true;
  const TrackCodes& tc = track_codes_[i];
  const int counted = free_running_ ? 0 : tc.matches[size_t(code)].counted;
  return tc.best_cost[size_t(code)] <= allowed_errors(counted) + options_.code_margin;
}

bool TargetIdentifier::holds(const std::vector<CandidateTrack>& tracks, size_t i) {
  const bool ok = geometry(tracks, &hypotheses_[i]);
  // The other assignments of a set of tracks join the hypotheses (not sorted in:
  // same cost); references into hypotheses_ end here.
  for (Hypothesis& o : assignments_) hypotheses_.push_back(o);
  assignments_.clear();
  return ok;
}

bool TargetIdentifier::unordered_geometry(const std::vector<CandidateTrack>& tracks, Hypothesis* h) {
  const Target& target = targets_.targets[h->target];
  Bearing4 x;
  Point4 X;
  int measured = 0;
  for (size_t i = 0; i < 4; ++i) {
    const CandidateTrack& c = tracks[size_t(h->track[i])];
    measured += c.measured;
    if (!bearing_of(tracks, size_t(h->track[i]), &x[i])) return false;
    X[i] = target.markers[i].position_m;
  }
  if (measured < 3) return false;
  P4POptions p4p;
  p4p.solver = options_.solver;
  p4p.camera = &camera_;
  const P4PIdentification found = identify_p4p(x, X, p4p);
  if (!found.in_pixels) return false;
  std::vector<Hypothesis> held;
  for (const P4PHypothesis& c : found.candidates) {
    if (!(c.error_px <= kMaxUnrefinedRms * options_.max_rms_px)) continue;
    Hypothesis g = *h;
    g.unordered = false;
    for (size_t i = 0; i < 4; ++i) g.track[size_t(c.marker_of[i])] = h->track[i];
    std::vector<MarkerObservation> observations;
    for (size_t m = 0; m < 4; ++m) observations.push_back({X[m], tracks[size_t(g.track[m])].pixel});
    g.pose = c.pose;
    g.rms_px = c.error_px;
    refine_geometry(observations, &g);
    if (!(g.rms_px <= options_.max_rms_px)) continue;
    g.geometry_state = 1;
    held.push_back(g);
  }
  if (held.empty()) return false;
  std::stable_sort(held.begin(), held.end(), [](const Hypothesis& a, const Hypothesis& b) { return a.rms_px < b.rms_px; });
  *h = held.front();
  assignments_.insert(assignments_.end(), held.begin() + 1, held.end());
  return true;
}

void TargetIdentifier::refine_geometry(const std::vector<MarkerObservation>& observations, Hypothesis* h) const {
  RefinementOptions refine;
  refine.max_iterations = 10;
  refine.sphere_centroid = false;
  if (const auto refined = refine_pose(camera_, observations, h->pose, refine); refined) {
    if (refined->rms_px < h->rms_px) h->pose = refined->pose, h->rms_px = refined->rms_px;
  }
}

uint64_t TargetIdentifier::shared_key(const Hypothesis& h, size_t track_count) const {
  // Class (16 bits) and the four tracks (12 bits each).
  const uint32_t cls = geometry_class_[h.target];
  if (track_count >= (1u << 12) || cls >= (1u << 16)) return kNoSharedKey;
  uint64_t key = cls;
  for (int k : h.track) {
    if (k < 0) return kNoSharedKey;
    key = (key << 12) | uint64_t(k);
  }
  return key;
}

bool TargetIdentifier::geometry(const std::vector<CandidateTrack>& tracks, Hypothesis* h) {
  if (h->geometry_state != 0) return h->geometry_state > 0;
  h->geometry_state = -1;
  if (h->unordered) return unordered_geometry(tracks, h);
  // Targets of one class fit a set of tracks alike: computed once per call.
  const uint64_t key = shared_key(*h, tracks.size());
  if (key != kNoSharedKey) {
    if (const auto it = shared_geometry_.find(key); it != shared_geometry_.end()) {
      h->geometry_state = it->second.state, h->pose = it->second.pose, h->rms_px = it->second.rms_px;
      return h->geometry_state > 0;
    }
  }
  h->geometry_state = ordered_geometry(tracks, h) ? 1 : -1;
  if (key != kNoSharedKey) shared_geometry_.emplace(key, SharedGeometry{h->geometry_state, h->pose, h->rms_px});
  return h->geometry_state > 0;
}

bool TargetIdentifier::ordered_geometry(const std::vector<CandidateTrack>& tracks, Hypothesis* h) {
  const Target& target = targets_.targets[h->target];
  Bearing4 x;
  Point4 X;
  std::vector<MarkerObservation> observations;
  int measured = 0;
  for (size_t m = 0; m < 4; ++m) measured += tracks[size_t(h->track[m])].measured;
  if (measured < 3) return false;
  for (size_t m = 0; m < 4; ++m) {
    const size_t k = size_t(h->track[m]);
    if (!bearing_of(tracks, k, &x[m])) return false;
    X[m] = target.markers[m].position_m;
    observations.push_back({X[m], tracks[k].pixel});
  }
  P4POptions p4p;
  p4p.solver = options_.solver;
  p4p.camera = &camera_;
  const double max_unrefined = kMaxUnrefinedRms * options_.max_rms_px;
  const auto solution = solve_p4p(x, X, p4p, max_unrefined);
  if (!solution) return false;
  h->pose = solution->pose;
  h->rms_px = solution->rms_error_px;
  if (!(h->rms_px <= max_unrefined)) return false;
  refine_geometry(observations, h);
  if (!(h->rms_px <= options_.max_rms_px)) return false;
  return coded_ || sizes_agree(tracks, *h);
}

bool TargetIdentifier::bearing_of(const std::vector<CandidateTrack>& tracks, size_t k, Eigen::Vector3d* x) {
  // Unprojecting is iterative under distortion: once per track and call.
  if (bearings_.size() != tracks.size()) bearings_.assign(tracks.size(), {0, Eigen::Vector3d::Zero()});
  auto& [state, bearing] = bearings_[k];
  if (state == 0) state = camera_.unproject(tracks[k].pixel, &bearing) ? 1 : -1;
  *x = bearing;
  return state > 0;
}

int TargetIdentifier::predict_fourth(const std::vector<CandidateTrack>& tracks, size_t t, const std::array<int, 3>& three,
                                     std::array<Eigen::Vector2d, 4>* fourth) const {
  const Target& target = targets_.targets[t];
  Bearing3 x;
  Point3x3 X;
  for (size_t m = 0; m < 3; ++m) {
    if (!camera_.unproject(tracks[size_t(three[m])].pixel, &x[m])) return 0;
    X[m] = target.markers[m].position_m;
  }
  PoseCandidates poses;
  const int n = solve_p3p(options_.solver, x, X, &poses);
  int found = 0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d p = poses[size_t(k)].apply(target.markers[3].position_m);
    if (p.z() > 0 && camera_.project(p, &(*fourth)[size_t(found)])) ++found;
  }
  return found;
}

bool TargetIdentifier::sizes_agree(const std::vector<CandidateTrack>& tracks, const Hypothesis& h) const {
  const Target& target = targets_.targets[h.target];
  const double R = target.marker_diameter_m / 2;
  std::vector<double> ratios;
  for (size_t m = 0; m < 4; ++m) {
    if (h.track[m] < 0) continue;
    const CandidateTrack& c = tracks[size_t(h.track[m])];
    if (!c.measured || !(c.radius_px > 0)) continue;
    // The sphere's image radius: its centre and a point R off it across the ray.
    const Eigen::Vector3d p = h.pose.apply(target.markers[m].position_m);
    Eigen::Vector3d across = p.cross(Eigen::Vector3d::UnitY());
    if (across.norm() < 1e-9 * p.norm()) across = p.cross(Eigen::Vector3d::UnitX());
    Eigen::Vector2d a, b;
    if (!camera_.project(p, &a) || !camera_.project(p + R * across.normalized(), &b)) continue;
    const double predicted = (b - a).norm();
    if (predicted >= options_.min_sized_radius_px) ratios.push_back(c.radius_px / predicted);
  }
  if (ratios.size() < 2) return true;
  std::sort(ratios.begin(), ratios.end());
  const double median = ratios.size() % 2 ? ratios[ratios.size() / 2]
                                          : 0.5 * (ratios[ratios.size() / 2 - 1] + ratios[ratios.size() / 2]);
  return median >= options_.min_size_ratio;
}

std::vector<Identification> TargetIdentifier::identify(const std::vector<CandidateTrack>& tracks,
                                                       const std::vector<bool>& wanted) {
  std::vector<Identification> out;
  last_hypotheses_ = 0;
  shared_geometry_.clear();
  bearings_.clear();
  if (tracks.size() < 3) return out;
  if (coded_) score_tracks(tracks);
  find_neighbours(tracks, wanted);
  enumerate(tracks, wanted);
  last_hypotheses_ = hypotheses_.size();
  {
    // By cost, ties in enumeration order; indices sort, each hypothesis moves once.
    std::vector<uint32_t> order(hypotheses_.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return hypotheses_[a].cost < hypotheses_[b].cost; });
    // With the capacity of the buffer it takes the place of: holds() appends the
    // other assignments of sets of tracks, and a buffer sized exactly would be
    // copied whole to take them.
    sorted_.clear();
    sorted_.reserve(std::max(order.size(), hypotheses_.capacity()));
    for (uint32_t i : order) sorted_.push_back(hypotheses_[i]);
    hypotheses_.swap(sorted_);
    sorted_count_ = hypotheses_.size();
  }

  std::vector<char> track_blocked(tracks.size(), 0), target_blocked(targets_.targets.size(), 0);
  const double margin = coded_ ? options_.code_margin : std::numeric_limits<double>::infinity();
  for (auto& [key, e] : geometry_evidence_) e.touched = false;
  for (size_t i = 0; i < hypotheses_.size(); ++i) {
    {
      const Hypothesis& h = hypotheses_[i];
      if (target_blocked[h.target]) continue;
      if (std::any_of(h.track.begin(), h.track.end(), [&](int k) { return track_blocked[size_t(k)]; })) continue;
      if (!codes_accept(h) || !holds(tracks, i)) continue;
    }
    const Hypothesis& h = hypotheses_[i];
    if (unweighed_rival(h)) {
      // A rival not weighed: wait, as for any rival too close to call.
      target_blocked[h.target] = 1;
      for (int k : h.track) track_blocked[size_t(k)] = 1;
      continue;
    }
    // Rivals: every other hypothesis touching this one's target or tracks that the
    // codes do not clearly reject and whose geometry is about as good. Codes tied,
    // the best geometry among them is the one whose rivals count.
    const bool code_ambiguous = h.shifted_cost < h.cost + margin;
    size_t chosen = i;
    std::vector<size_t> group;
    for (int walk = 0; walk < 8 && !code_ambiguous; ++walk) {
      group = rivals_of(tracks, chosen, margin);
      size_t best = chosen;
      for (size_t j : group)
        if (hypotheses_[j].rms_px < hypotheses_[best].rms_px) best = j;
      if (best == chosen) break;
      chosen = best;
    }
    const Hypothesis& best = hypotheses_[chosen];
    const bool chosen_free = chosen == i || (!target_blocked[best.target] &&
                                             std::none_of(best.track.begin(), best.track.end(),
                                                          [&](int k) { return track_blocked[size_t(k)]; }));
    for (const Hypothesis* b : {static_cast<const Hypothesis*>(&hypotheses_[i]), &best}) {
      target_blocked[b->target] = 1;
      for (int k : b->track) track_blocked[size_t(k)] = 1;
    }
    if (code_ambiguous || !chosen_free) continue;
    if (chosen != i && (best.shifted_cost < best.cost + margin || !codes_accept(best) || unweighed_rival(best))) continue;
    if (group.size() > 1) {
      // Too close to call in this frame: the residuals of the same hypotheses over
      // the frames they have lasted decide, or the wait goes on.
      const auto winner = geometry_winner(tracks, group);
      if (!winner) continue;
      chosen = *winner;
      const Hypothesis& w = hypotheses_[chosen];
      target_blocked[w.target] = 1;
      for (int k : w.track) track_blocked[size_t(k)] = 1;
      if (!codes_accept(w)) continue;
    }
    const Hypothesis& accepted = hypotheses_[chosen];
    std::array<int64_t, 4> ids{};
    for (size_t m = 0; m < 4; ++m) ids[m] = tracks[size_t(accepted.track[m])].track->id();
    out.push_back(identification_of(accepted, ids));
  }
  if (options_.edge_identification) identify_at_edge(tracks, wanted, track_blocked, target_blocked, &out);
  // Evidence lasts while its hypothesis is weighed frame after frame, and through
  // frames where some of its tracks are dark or merged (no geometry to weigh then);
  // it ends with a track that ended or was claimed, or a frame all four were
  // measured in and it was not weighed.
  std::map<int64_t, bool> measured;
  for (const CandidateTrack& c : tracks) measured[c.track->id()] = c.measured;
  for (auto it = geometry_evidence_.begin(); it != geometry_evidence_.end();) {
    bool keep = it->second.touched;
    if (!keep) {
      bool all_there = true, all_measured = true;
      for (int64_t id : it->first.second) {
        const auto m = measured.find(id);
        all_there = all_there && m != measured.end();
        all_measured = all_measured && m != measured.end() && m->second;
      }
      keep = all_there && !all_measured;
    }
    it = keep ? std::next(it) : geometry_evidence_.erase(it);
  }
  return out;
}

std::vector<size_t> TargetIdentifier::rivals_of(const std::vector<CandidateTrack>& tracks, size_t i, double margin) {
  std::vector<size_t> group{i};
  const Hypothesis h = hypotheses_[i];
  // Sorted by cost up to sorted_count_; the other assignments of sets of tracks
  // (holds()) follow, as they are found.
  for (size_t j = 0; j < hypotheses_.size(); ++j) {
    if (!(hypotheses_[j].cost < h.cost + margin)) {
      if (j < sorted_count_) j = sorted_count_ - 1;
      continue;
    }
    if (j == i || !h.shares(hypotheses_[j])) continue;
    if (holds(tracks, j) && hypotheses_[j].rms_px < h.rms_px + options_.geometry_margin_px) group.push_back(j);
  }
  return group;
}

bool TargetIdentifier::unweighed_rival(const Hypothesis& h) const {
  const double margin = coded_ ? options_.code_margin : std::numeric_limits<double>::infinity();
  for (const Unweighed& u : unweighed_) {
    if (u.target == h.target) continue;
    double all_least = 0;
    for (double l : u.least) all_least += l;
    for (size_t m = 0; m < 4; ++m)
      for (const auto& [track, cost] : u.candidates[m]) {
        if (std::find(h.track.begin(), h.track.end(), track) == h.track.end()) continue;
        // The least any of u's hypotheses with this track as marker m can cost
        // (free-running: the phases' minima bound the sum from below).
        if (cost + (all_least - u.least[m]) < h.cost + margin) return true;
      }
  }
  return false;
}

bool TargetIdentifier::codes_accept(const Hypothesis& h) const {
  if (!coded_ || !has_binary_codes(h.target)) return true;
  if (h.codes.counted < options_.min_bits || h.cost > allowed_errors(h.codes.counted)) return false;
  for (size_t m = 0; m < 4; ++m) {
    const int c = code_of_[h.target][m];
    if (c < 0 || h.track[m] < 0) continue;
    const TrackCodes& tc = track_codes_[size_t(h.track[m])];
    const CodeMatch& mm =
        free_running_ ? tc.phases[size_t(c)][size_t(h.phase) % tc.phases[size_t(c)].size()] : tc.matches[size_t(c)];
    if (mm.counted < options_.min_bits_per_track) return false;
  }
  return true;
}

std::optional<size_t> TargetIdentifier::geometry_winner(const std::vector<CandidateTrack>& tracks,
                                                        const std::vector<size_t>& group) {
  std::vector<const GeometryEvidence*> evidence;
  for (size_t j : group) {
    const Hypothesis& h = hypotheses_[j];
    GeometryKey key{h.target, {}};
    for (size_t m = 0; m < 4; ++m) key.second[m] = tracks[size_t(h.track[m])].track->id();
    GeometryEvidence& e = geometry_evidence_[key];
    if (!e.touched) {
      e.ssr_px2 += 4 * h.rms_px * h.rms_px;
      ++e.frames;
      e.touched = true;
    }
    evidence.push_back(&e);
  }
  size_t best = 0;
  for (size_t k = 1; k < group.size(); ++k)
    if (evidence[k]->mean() < evidence[best]->mean()) best = k;
  const GeometryEvidence& b = *evidence[best];
  // Gaussian pixel noise sigma, from the best hypothesis' residuals (2 degrees of
  // freedom a frame: 8 coordinates, 6 pose parameters), never below the floor;
  // before min_geometry_frames, never below the decisive level.
  const double own = b.ssr_px2 / (2.0 * b.frames);
  const double sigma2 = std::max(own, options_.geometry_noise_floor_px * options_.geometry_noise_floor_px);
  const double decisive2 = std::max(own, options_.decisive_noise_px * options_.decisive_noise_px);
  for (size_t k = 0; k < group.size(); ++k) {
    if (k == best) continue;
    const GeometryEvidence& r = *evidence[k];
    const int frames = std::min(b.frames, r.frames);
    const double s2 = frames < options_.min_geometry_frames ? decisive2 : sigma2;
    const double nats = frames * (r.mean() - b.mean()) / (2 * s2);
    if (nats < options_.min_geometry_evidence) return std::nullopt;
  }
  return group[best];
}

}  // namespace tetrapulse
