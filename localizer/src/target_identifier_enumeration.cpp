// TargetIdentifier's hypotheses: for each wanted target, the sets of candidate
// tracks near each other whose codes may be its markers' (target_identifier.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "identification_hypothesis.hpp"
#include "track_neighbours.hpp"
#include "tetrapulse/localizer/target_identifier.hpp"

namespace tetrapulse {
namespace {

// How far from a P3P root's marker 3 a fourth track may lie beyond its radius (px):
// three noisy centres extrapolate the fourth by a few pixels.
constexpr double kFourthMarkerTolerancePx = 8.0;

double reach_of(double radius_px, double extent_ratio) { return 2 * extent_ratio * radius_px + 10; }

}  // namespace

double TargetIdentifier::reach_px(double radius_px, size_t t) const { return reach_of(radius_px, extent_ratio_[t]); }

bool TargetIdentifier::near(const CandidateTrack& a, const CandidateTrack& b, size_t t) const {
  return (a.pixel - b.pixel).norm() <= reach_px(std::max(a.radius_px, b.radius_px), t);
}

void TargetIdentifier::find_neighbours(const std::vector<CandidateTrack>& tracks, const std::vector<bool>& wanted) {
  // The largest reach of the wanted targets; a radius below zero reaches no farther
  // than zero's (nor does it for any target).
  double extent_ratio = 0;
  for (size_t t = 0; t < targets_.targets.size() && t < wanted.size(); ++t)
    if (wanted[t]) extent_ratio = std::max(extent_ratio, extent_ratio_[t]);
  neighbours_->find(tracks, [extent_ratio](double radius_px) { return reach_of(std::max(radius_px, 0.0), extent_ratio); });
}

void TargetIdentifier::enumerate(const std::vector<CandidateTrack>& tracks, const std::vector<bool>& wanted) {
  hypotheses_.clear();
  unweighed_.clear();
  const size_t n = tracks.size();
  if (n < 4) return;
  // Candidates of each marker of each wanted target: tracks whose bits do not rule its code out.
  struct Wanted {
    size_t target = 0;
    std::array<std::vector<int>, 4> candidates;
    double combinations = 0;  // before the distance test
  };
  std::vector<Wanted> order;
  for (size_t t = 0; t < targets_.targets.size(); ++t) {
    if (t >= wanted.size() || !wanted[t]) continue;
    Wanted w;
    w.target = t;
    for (size_t m = 0; m < 4; ++m)
      for (size_t i = 0; i < n; ++i)
        if (may_be(tracks[i], i, t, m)) w.candidates[m].push_back(int(i));
    w.combinations = interchangeable_[t] ? 1.0 / 24 : 1.0;
    for (const auto& c : w.candidates) w.combinations *= double(c.size());
    if (w.combinations > 0) order.push_back(std::move(w));
  }
  // Tracks near a candidate are found among its neighbours (a superset of the tracks
  // near() it for any wanted target), in index order as the candidates are: the
  // hypotheses come in the order a scan of all candidates gives them.
  std::array<std::vector<char>, 4> is_candidate;
  // The budget goes to the targets with the fewest combinations first: a target
  // whose codes have not narrowed its tracks yet (too many to weigh) waits for
  // more bits without holding up the others. A target left out is no rival of
  // any hypothesis weighed; its own tracks stay free for it (a hypothesis of
  // another target on them must still beat the codes).
  std::stable_sort(order.begin(), order.end(),
                   [](const Wanted& a, const Wanted& b) { return a.combinations < b.combinations; });
  // A hypothesis that costs more than any could be allowed, plus the code margin,
  // is neither accepted nor anyone's rival: partial sums above it are not
  // continued (each track alone passed may_be, four of them need not).
  double bound = std::numeric_limits<double>::infinity();
  if (coded_ && !free_running_) {
    int most = 0;
    for (const TrackCodes& tc : track_codes_)
      for (const CodeMatch& m : tc.matches) most = std::max(most, m.counted);
    bound = allowed_errors(4 * most) + options_.code_margin;
  }
  for (const Wanted& w : order) {
    const size_t t = w.target;
    const auto cost = [&](int i, size_t m) {
      const int c = code_of_[t][m];
      return c >= 0 ? track_codes_[size_t(i)].best_cost[size_t(c)] : 0.0;
    };
    // Tracks of one target lie within its image: at most its size over its markers' size, doubled.
    const auto near = [&](int a, int b) { return this->near(tracks[size_t(a)], tracks[size_t(b)], t); };
    for (size_t m = 0; m < 4; ++m) {
      is_candidate[m].assign(n, 0);
      for (int i : w.candidates[m]) is_candidate[m][size_t(i)] = 1;
    }
    const auto neighbours = [&](int a) -> const std::vector<int>& { return neighbours_->of(size_t(a)); };
    const size_t before = hypotheses_.size();
    bool over = false;
    Hypothesis h;
    h.target = t;
    if (interchangeable_[t]) {
      // Markers the codes cannot tell apart: one hypothesis per set of four tracks,
      // whose geometry names the markers (geometry(): all 24 assignments).
      h.unordered = true;
      // Sets c0 < c1 < c2 < c3 of candidates (track indices), each near the others.
      const std::vector<char>& candidate = is_candidate[0];
      for (const int c0 : w.candidates[0]) {
        if (over) break;
        const double cost0 = cost(c0, 0);
        for (const int c1 : neighbours(c0)) {
          if (over) break;
          if (c1 <= c0 || !candidate[size_t(c1)]) continue;
          const double cost01 = cost0 + cost(c1, 0);
          if (cost01 > bound || !near(c0, c1)) continue;
          for (const int c2 : neighbours(c0)) {
            if (over) break;
            if (c2 <= c1 || !candidate[size_t(c2)]) continue;
            const double cost012 = cost01 + cost(c2, 0);
            if (cost012 > bound || !near(c0, c2) || !near(c1, c2)) continue;
            for (const int c3 : neighbours(c0)) {
              if (c3 <= c2 || !candidate[size_t(c3)]) continue;
              if (cost012 + cost(c3, 0) > bound) continue;
              if (!near(c0, c3) || !near(c1, c3) || !near(c2, c3)) continue;
              if (hypotheses_.size() >= options_.max_hypotheses) {
                over = true;
                break;
              }
              h.track = {c0, c1, c2, c3};
              score_codes(&h);
              hypotheses_.push_back(h);
            }
          }
        }
      }
    }
    for (int a : w.candidates[0]) {
      if (over || h.unordered) break;
      for (int b : neighbours(a)) {
        if (over) break;
        if (!is_candidate[1][size_t(b)] || cost(a, 0) + cost(b, 1) > bound || !near(a, b)) continue;
        for (int c : neighbours(a)) {
          if (over) break;
          if (!is_candidate[2][size_t(c)] || c == b || !near(a, c) || !near(b, c)) continue;
          const double abc = cost(a, 0) + cost(b, 1) + cost(c, 2);
          if (abc > bound) continue;
          // Unmodulated: no codes narrow the fourth track; a P3P root of the first
          // three must put marker 3 on it (else 16 tracks in reach give ~40 000
          // combinations a target, and the budget names none).
          std::array<Eigen::Vector2d, 4> fourth;
          const int roots = coded_ ? 0 : predict_fourth(tracks, t, {a, b, c}, &fourth);
          if (!coded_ && roots == 0) continue;
          for (int d : neighbours(a)) {
            if (!is_candidate[3][size_t(d)] || d == b || d == c || abc + cost(d, 3) > bound) continue;
            if (!near(a, d) || !near(b, d) || !near(c, d)) continue;
            if (!coded_ && !std::any_of(fourth.begin(), fourth.begin() + roots, [&](const Eigen::Vector2d& px) {
                  return (px - tracks[size_t(d)].pixel).norm() <= kFourthMarkerTolerancePx + tracks[size_t(d)].radius_px;
                })) {
              continue;
            }
            if (hypotheses_.size() >= options_.max_hypotheses) {
              over = true;
              break;
            }
            h.track = {a, b, c, d};
            score_codes(&h);
            hypotheses_.push_back(h);
          }
        }
      }
    }
    if (over) {
      hypotheses_.resize(before);
      Unweighed u;
      u.target = t;
      for (size_t m = 0; m < 4; ++m) {
        u.least[m] = std::numeric_limits<double>::infinity();
        for (int i : w.candidates[m]) {
          u.candidates[m].emplace_back(i, cost(i, m));
          u.least[m] = std::min(u.least[m], cost(i, m));
        }
      }
      unweighed_.push_back(std::move(u));
    }
  }
}

}  // namespace tetrapulse
