// Identification of a target with one marker out of view (target_identifier.hpp,
// "three tracks"): a drone at the edge of the image, a robot half under a
// camera's border. Three tracks fit any three of a target's markers exactly
// (P3P has up to four roots and no residual), so geometry cannot weigh them by
// reprojection; what it can say is where each root puts the fourth marker. A
// root that puts it in view, where no blob is, is not the target. A hypothesis
// holds when exactly one of its roots puts the missing marker out of view, and it
// is accepted when it has done so, with no rival that does as well, in
// min_edge_frames frames its three tracks were measured in, with no frame between
// in which it failed: codes as for four tracks, geometry by elimination, and
// ambiguity waits.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "identification_hypothesis.hpp"
#include "track_neighbours.hpp"
#include "tetrapulse/localizer/p3p.hpp"

namespace tetrapulse {

bool TargetIdentifier::edge_geometry(const std::vector<CandidateTrack>& tracks, Hypothesis* h) const {
  if (h->geometry_state != 0) return h->geometry_state > 0;
  h->geometry_state = -1;
  const Target& target = targets_.targets[h->target];
  Bearing3 x;
  Point3x3 X;
  std::array<Eigen::Vector2d, 3> px;
  size_t j = 0;
  for (size_t m = 0; m < 4; ++m) {
    if (int(m) == h->missing) continue;
    const CandidateTrack& c = tracks[size_t(h->track[m])];
    // Parts of merged blobs and predictions of dark tracks can fit a wrong
    // permutation; three markers must all be measured.
    if (!c.measured || !camera_.unproject(c.pixel, &x[j])) return false;
    X[j] = target.markers[m].position_m;
    px[j] = c.pixel;
    ++j;
  }
  PoseCandidates roots;
  const int n = solve_p3p(options_.solver, x, X, &roots);
  const Eigen::Vector3d& hidden = target.markers[size_t(h->missing)].position_m;
  h->out_of_view_poses = 0;
  for (int r = 0; r < n; ++r) {
    double ssr = 0;
    bool projects = true;
    for (size_t k = 0; k < 3 && projects; ++k) {
      Eigen::Vector2d p;
      projects = camera_.project(roots[size_t(r)].apply(X[k]), &p);
      ssr += (p - px[k]).squaredNorm();
    }
    const double rms = std::sqrt(ssr / 3);
    if (!projects || !(rms <= options_.max_rms_px)) continue;
    // Out of view as the evaluation counts it: the centre is not at least one
    // image radius inside the border (a marker past it gives no whole blob).
    const Eigen::Vector3d p = roots[size_t(r)].apply(hidden);
    Eigen::Vector2d q;
    const bool in_view = camera_.project(p, &q) &&
                         camera_.in_image(q, camera_.info().fx * target.marker_diameter_m / 2 / p.norm());
    if (in_view) continue;
    ++h->out_of_view_poses;
    h->pose = roots[size_t(r)];
    h->rms_px = rms;
  }
  if (h->out_of_view_poses != 1) return false;
  h->geometry_state = 1;
  return true;
}

void TargetIdentifier::identify_at_edge(const std::vector<CandidateTrack>& tracks, const std::vector<bool>& wanted,
                                        std::vector<char>& track_blocked, std::vector<char>& target_blocked,
                                        std::vector<Identification>* out) {
  // Kept between calls: while targets are sought, thousands of hypotheses a frame,
  // and a vector grown anew each call spent more time faulting in fresh pages and
  // copying than the pass itself.
  std::vector<Hypothesis>& hs = edge_hypotheses_;
  hs.clear();
  bool over = false;
  for (size_t t = 0; t < targets_.targets.size() && !over; ++t) {
    // Targets that waited on rivals in the four-track pass stay rivals here.
    if (t >= wanted.size() || !wanted[t]) continue;
    if (std::any_of(out->begin(), out->end(), [t](const Identification& id) { return id.target == t; })) continue;
    // A marker out of view lies within the target's image size of each of the
    // others (the bound near() uses), so all three lie that close to the border.
    const auto by_border = [&](const CandidateTrack& c) { return !camera_.in_image(c.pixel, reach_px(c.radius_px, t)); };
    // Only measured tracks: a frame with one dark or merged judges nothing, and
    // the evidence of its hypotheses waits.
    std::array<std::vector<int>, 4> candidates;
    for (size_t m = 0; m < 4; ++m)
      for (size_t i = 0; i < tracks.size(); ++i)
        if (tracks[i].measured && !track_blocked[i] && by_border(tracks[i]) && may_be(tracks[i], i, t, m))
          candidates[m].push_back(int(i));
    const auto near = [&](int a, int b) { return a != b && this->near(tracks[size_t(a)], tracks[size_t(b)], t); };
    std::array<std::vector<char>, 4> is_candidate;
    for (size_t k = 0; k < 4; ++k) {
      is_candidate[k].assign(tracks.size(), 0);
      for (int i : candidates[k]) is_candidate[k][size_t(i)] = 1;
    }
    for (int missing = 0; missing < 4 && !over; ++missing) {
      std::array<size_t, 3> m{};
      for (size_t k = 0, j = 0; k < 4; ++k)
        if (int(k) != missing) m[j++] = k;
      Hypothesis h;
      h.target = t;
      h.missing = missing;
      h.track[size_t(missing)] = -1;
      // Candidates near a are among its neighbours, in the same (index) order.
      for (int a : candidates[m[0]]) {
        if (over) break;
        for (int b : neighbours_->of(size_t(a))) {
          if (!is_candidate[m[1]][size_t(b)] || !near(a, b)) continue;
          for (int c : neighbours_->of(size_t(a))) {
            if (!is_candidate[m[2]][size_t(c)] || !near(a, c) || !near(b, c)) continue;
            if (hs.size() >= options_.max_hypotheses) {
              over = true;
              break;
            }
            h.track[m[0]] = a;
            h.track[m[1]] = b;
            h.track[m[2]] = c;
            score_codes(&h);
            hs.push_back(h);
          }
          if (over) break;
        }
      }
    }
  }
  // Too many to weigh: the codes have not narrowed the tracks yet; wait.
  if (over) hs.clear();
  // Nothing to accept (codes not read far enough yet): rivals need no weighing.
  if (std::none_of(hs.begin(), hs.end(), [&](const Hypothesis& h) { return !target_blocked[h.target] && codes_accept(h); }))
    hs.clear();
  std::vector<uint32_t> order(hs.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return hs[a].cost < hs[b].cost; });
  const double margin = coded_ ? options_.code_margin : std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < order.size(); ++i) {
    Hypothesis& h = hs[order[i]];
    if (target_blocked[h.target] || !codes_accept(h) || h.shifted_cost < h.cost + margin) continue;
    if (std::any_of(h.track.begin(), h.track.end(), [&](int k) { return k >= 0 && track_blocked[size_t(k)]; }))
      continue;
    GeometryKey key{h.target, {}};
    for (size_t m = 0; m < 4; ++m) key.second[m] = h.track[m] >= 0 ? tracks[size_t(h.track[m])].track->id() : -1;
    if (!edge_geometry(tracks, &h) || unweighed_rival(h)) {
      edge_evidence_.erase(key);
      continue;
    }
    bool rival = false;
    for (size_t j = 0; j < order.size() && !rival; ++j) {
      Hypothesis& r = hs[order[j]];
      if (!(r.cost < h.cost + margin)) break;  // sorted by cost
      if (j == i || !h.shares(r)) continue;
      edge_geometry(tracks, &r);
      rival = r.out_of_view_poses > 0;
    }
    // Either way these tracks and this target are settled for this call.
    target_blocked[h.target] = 1;
    for (int k : h.track)
      if (k >= 0) track_blocked[size_t(k)] = 1;
    if (rival) {
      edge_evidence_.erase(key);
      continue;
    }
    if (++edge_evidence_[key] < options_.min_edge_frames) continue;
    out->push_back(identification_of(h, key.second));
  }
  // Evidence ends with any of its tracks.
  std::vector<int64_t> ids;
  for (const CandidateTrack& c : tracks) ids.push_back(c.track->id());
  std::sort(ids.begin(), ids.end());
  for (auto it = edge_evidence_.begin(); it != edge_evidence_.end();) {
    const auto& key = it->first.second;
    const bool all = std::all_of(key.begin(), key.end(),
                                 [&](int64_t id) { return id < 0 || std::binary_search(ids.begin(), ids.end(), id); });
    it = all ? std::next(it) : edge_evidence_.erase(it);
  }
}

}  // namespace tetrapulse
