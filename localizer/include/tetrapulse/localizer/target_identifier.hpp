#pragma once
// Identification: which unclaimed blob tracks are which target's markers.
//
// A hypothesis names a target and four tracks, one per marker. Its evidence:
//   codes     the tracks' read bits (track_bits.hpp) against the markers' codes
//             (code_match.hpp): synchronized boards under the time base's clock;
//             free-running boards under one clock per target whose phase is
//             searched (phase_steps per bit over the whole code cycle, so any
//             cyclic shift is tried); constant modulation has no codes.
//             Frequency codes (square waves, frequency_identifier.hpp) are not
//             read bit by bit: a marker playing one takes only tracks that the
//             frequency identifier gave exactly that code, and a marker playing
//             a binary code never takes such a track (the two families are
//             never confused). A target whose markers all play frequency codes
//             needs no read bits; geometry then names its markers.
//   look      a marker takes only tracks of its own look (light, dark, a colour:
//             target_appearance.hpp) in a rig that mixes them.
//   geometry  the tracks' pixels this frame must be explained by one pose of the
//             target: known-correspondence P4P (p4p.hpp), refined, with an RMS
//             reprojection error of at most max_rms_px. At least three of the
//             pixels must be blobs measured in this exposure: dark tracks'
//             extrapolated pixels or parts of merged blobs can let a permutation
//             of a target's markers (or another target's marker) fit, so such a
//             hypothesis waits (a fourth may be a dark track's prediction: on_off
//             codes rarely light all four at once).
// A hypothesis is accepted when its code cost (mismatches, code_match.hpp) is
// within the error budget, it has read enough bits, its geometry holds, and no
// rival comes close: a rival is any other hypothesis for the same target or
// sharing a track whose code cost is below cost + code_margin and whose
// geometry holds with an RMS below rms + geometry_margin_px. So codes decide
// between targets of equal geometry, geometry decides between the markers of
// targets whose markers share a code, and both must agree. Ambiguity means
// waiting for more frames, never guessing.
// Rivals that geometry cannot tell apart in one frame (a target seen from
// straight above, a permutation of its markers fitting within a pixel) are
// weighed over the frames they last: each hypothesis of the same tracks sums its
// squared residuals (SSR, px^2, four markers a frame); the one with the least
// mean SSR wins when, for every rival,
//   n (mean SSR_rival - mean SSR_best) / (2 sigma^2) >= min_geometry_evidence nats,
//   sigma^2 = max(SSR_best / (2 n), geometry_noise_floor_px^2),
// over n >= min_geometry_frames frames: the log-likelihood ratio under Gaussian
// pixel noise whose level the best hypothesis' own residuals give. A rival that
// fits far worse is refuted sooner: over fewer frames when the same ratio holds
// with sigma at least decisive_noise_px, a centroid noise no measured, unmerged
// blob exceeds (a permutation of a drone's markers fitting at 0.9 px against
// 0.005 px for the truth is refuted in its first frame, not its third).
//
// Of hypotheses tied in codes, the best geometry is weighed first: its rivals are
// those within geometry_margin_px of it.
// Unmodulated targets' hypotheses are enumerated guided by geometry: tracks for
// markers 0-2 (in reach of each other), then only a fourth track that a P3P root
// of those three puts marker 3 on (within 8 px beyond its radius); without codes
// to narrow them, 16 tracks in reach would give ~40 000 combinations a target.
// Unmodulated targets have nothing but geometry to name them, and four blobs of
// two targets can fit a third pose within the residual bound. Their markers'
// image sizes are evidence the residuals do not use: a hypothesis whose pose
// would show its spheres larger than their blobs (the median over its measured
// markers of blob radius / the sphere's predicted image radius below
// min_size_ratio, counting markers predicted at least min_sized_radius_px) holds no
// target.
// Hypotheses need four tracks (three: below); tracks too far apart for one
// target (judged from their blob sizes and the marker diameter) are never combined. At most
// max_hypotheses are weighed a call, given to the targets with the fewest
// combinations first; a target left over (its codes have not narrowed its tracks
// yet) waits, and blocks any hypothesis that one of its own could rival on a
// shared track (a lower bound of its code cost within code_margin).
// Three tracks: a target with one marker out of view (at the image's edge) is
// still found (target_identifier_edge.cpp). Three tracks fit any three markers
// exactly, so such a hypothesis holds only when exactly one P3P root of its three
// measured blobs puts the fourth marker out of view (its centre not an image
// radius inside the border), and it is accepted only after min_edge_frames frames
// in which it held, its codes passed as above, and no other hypothesis on its
// tracks or target within code_margin had a root putting its missing marker out
// of view, with no frame between in which it failed (frames with a track dark or
// merged judge nothing). Only tracks within the target's image size of the
// border take part (the missing marker is that close to each). The four-track
// pass goes first; its tracks and waiting targets are not reused.
// Pixels in the OpenCV convention; poses as pose.hpp; times in rig-time ns.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/localizer/blob_tracker.hpp"
#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/code_clock.hpp"
#include "tetrapulse/localizer/code_match.hpp"
#include "tetrapulse/localizer/p3p.hpp"
#include "tetrapulse/localizer/pose.hpp"
#include "tetrapulse/localizer/pose_refinement.hpp"
#include "tetrapulse/localizer/targets.hpp"
#include "tetrapulse/localizer/track_bits.hpp"

namespace tetrapulse {
namespace localizer_internal {
class TrackNeighbours;
}  // namespace localizer_internal

struct IdentificationOptions {
  P3PSolver solver = kDefaultP3PSolver;
  double max_rms_px = 2.0;          // geometry cross-check
  double geometry_margin_px = 1.0;  // a rival this much worse in geometry is no rival
  double code_margin = 3.0;         // a rival this many bit errors worse is no rival
  int min_bits = 12;                // read bits over a hypothesis' four tracks (coded targets)
  int min_bits_per_track = 2;
  int bits_per_error = 16;          // one read error tolerated per this many bits
  int phase_steps = 8;              // free-running phase search: phases per bit
  int max_samples = 48;             // newest samples of each track used
  size_t max_hypotheses = 20000;    // more combinations than this: wait for more bits
  // Rivals close in geometry, weighed over frames (see above).
  double min_geometry_evidence = 12.0;   // nats
  int min_geometry_frames = 3;
  double geometry_noise_floor_px = 0.05;
  double decisive_noise_px = 0.3;  // noise assumed before min_geometry_frames (see above)
  // Unmodulated targets: blob sizes against the pose's (see above).
  double min_size_ratio = 0.75;
  double min_sized_radius_px = 3.0;
  // Three tracks, a marker out of view (see above): frames it must hold.
  bool edge_identification = true;
  int min_edge_frames = 3;
};

// A track as the identifier sees it this frame.
struct CandidateTrack {
  const BlobTrack* track = nullptr;
  const TrackBits* bits = nullptr;                    // read bits of track->history()
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();    // blob this frame, or the track's prediction
  double radius_px = 0;                                // blob radius, for the size of its target
  bool measured = true;     // `pixel` is an unmerged blob of this frame (not a prediction, not a split part)
  int frequency_code = -1;  // rig_codes() index of the frequency code this track carries (-1: none decided)
  int look = 0;             // its blobs' look (Blob::look): only markers of that look take it
};

struct Identification {
  size_t target = 0;                    // index in TargetsFile::targets
  std::array<int64_t, 4> track_of{};    // track id of each marker
  Pose pose;                            // from the geometry check
  double rms_px = 0;
  CodeMatch codes;                      // the accepted code evidence
  CodeClock clock;                      // the target's clock (estimated when free-running)
};

class TargetIdentifier {
 public:
  TargetIdentifier(const CameraModel& camera, const TargetsFile& targets, IdentificationOptions options = {});
  ~TargetIdentifier();
  TargetIdentifier(TargetIdentifier&&) noexcept;

  // Identifies targets among `tracks` (no two hypotheses accepted share a track or
  // a target). `wanted[i]`: whether target i may be identified now (false for
  // targets already being tracked).
  std::vector<Identification> identify(const std::vector<CandidateTrack>& tracks, const std::vector<bool>& wanted);

  // Hypotheses scored in the last call (for diagnostics and benchmarks).
  size_t last_hypotheses() const { return last_hypotheses_; }

 private:
  struct Hypothesis;
  struct TrackCodes;
  struct GeometryEvidence {
    double ssr_px2 = 0;  // summed over `frames`
    int frames = 0;
    bool touched = false;  // in this call
    double mean() const { return frames > 0 ? ssr_px2 / frames : 0; }
  };
  using GeometryKey = std::pair<size_t, std::array<int64_t, 4>>;  // target, track of each marker
  void score_tracks(const std::vector<CandidateTrack>& tracks);
  // Whether candidate track i may be marker m of target t by its codes.
  bool may_be(const CandidateTrack& track, size_t i, size_t t, size_t m) const;
  // How far from a blob of `radius_px` the other markers of target t may lie: its
  // size over its markers' size, doubled, plus 10 px.
  double reach_px(double radius_px, size_t t) const;
  // Whether two tracks lie close enough to be markers of target t.
  bool near(const CandidateTrack& a, const CandidateTrack& b, size_t t) const;
  // Finds neighbours_ for this call: pairs near() for some wanted target.
  void find_neighbours(const std::vector<CandidateTrack>& tracks, const std::vector<bool>& wanted);
  // The three-track pass (target_identifier_edge.cpp), after the four-track one.
  void identify_at_edge(const std::vector<CandidateTrack>& tracks, const std::vector<bool>& wanted,
                        std::vector<char>& track_blocked, std::vector<char>& target_blocked,
                        std::vector<Identification>* out);
  bool edge_geometry(const std::vector<CandidateTrack>& tracks, Hypothesis* h) const;
  // The accepted hypothesis as reported, its markers on `track_ids` (-1: none).
  Identification identification_of(const Hypothesis& h, const std::array<int64_t, 4>& track_ids) const;
  void enumerate(const std::vector<CandidateTrack>& tracks, const std::vector<bool>& wanted);
  void score_codes(Hypothesis* h) const;
  // Whether h's tracks fit one pose of its target (h->pose, h->rms_px). An
  // unordered h becomes its best assignment; the others that fit wait in
  // assignments_ for holds() to add.
  bool geometry(const std::vector<CandidateTrack>& tracks, Hypothesis* h);
  bool ordered_geometry(const std::vector<CandidateTrack>& tracks, Hypothesis* h);
  // The key of h's class and tracks in shared_geometry_ (all ones: none).
  uint64_t shared_key(const Hypothesis& h, size_t track_count) const;
  // Bearing of tracks[k] (false: its pixel does not unproject), cached in this call.
  bool bearing_of(const std::vector<CandidateTrack>& tracks, size_t k, Eigen::Vector3d* x);
  bool unordered_geometry(const std::vector<CandidateTrack>& tracks, Hypothesis* h);
  void refine_geometry(const std::vector<MarkerObservation>& observations, Hypothesis* h) const;
  // geometry() of hypotheses_[i]; adds the other assignments of a set of tracks.
  bool holds(const std::vector<CandidateTrack>& tracks, size_t i);
  // Unmodulated targets: where the P3P roots of tracks `three` as markers 0-2 of target t
  // put marker 3 (pixels); how many roots put it in front of the camera.
  int predict_fourth(const std::vector<CandidateTrack>& tracks, size_t t, const std::array<int, 3>& three,
                     std::array<Eigen::Vector2d, 4>* fourth) const;
  // Unmodulated targets: whether h's pose shows its markers no larger than their blobs allow.
  bool sizes_agree(const std::vector<CandidateTrack>& tracks, const Hypothesis& h) const;
  double allowed_errors(int counted) const;
  bool has_binary_codes(size_t target) const;
  bool codes_accept(const Hypothesis& h) const;
  // hypotheses_[i] (its geometry holding) and its rivals (see above).
  std::vector<size_t> rivals_of(const std::vector<CandidateTrack>& tracks, size_t i, double margin);
  // Whether a target left unweighed this call (too many combinations) might have
  // a hypothesis on one of h's tracks costing less than h's cost + code_margin.
  bool unweighed_rival(const Hypothesis& h) const;
  // Of hypotheses_[group], the one the residuals of many frames pick (see above), if any yet.
  std::optional<size_t> geometry_winner(const std::vector<CandidateTrack>& tracks, const std::vector<size_t>& group);

  const CameraModel& camera_;
  const TargetsFile& targets_;
  IdentificationOptions options_;
  bool coded_ = false;
  bool free_running_ = false;
  std::vector<Code> codes_;                       // distinct codes
  std::vector<std::array<int, 4>> code_of_;      // code index of each target's markers (-1: none)
  std::vector<std::array<int, 4>> frequency_of_; // rig_codes() index of a marker's frequency code (-1: binary or none)
  std::vector<std::array<int, 4>> look_of_;      // each marker's look (RigLooks::look_of)
  std::vector<double> extent_ratio_;             // target's largest marker distance / marker radius
  // Targets with the same markers share a class (the index of its first target): a set
  // of tracks fits all of them alike, so its geometry is computed once per call.
  std::vector<uint32_t> geometry_class_;
  struct SharedGeometry {
    int8_t state = 0;
    Pose pose;
    double rms_px = 0;
  };
  std::unordered_map<uint64_t, SharedGeometry> shared_geometry_;  // this call's, by shared_key()
  std::vector<std::pair<int8_t, Eigen::Vector3d>> bearings_;     // this call's, by track (state as geometry_state)
  // This call's tracks near each other for some wanted target (track_neighbours.hpp):
  // the enumerations visit only these.
  std::unique_ptr<localizer_internal::TrackNeighbours> neighbours_;
  std::vector<TrackCodes> track_codes_;
  std::vector<Hypothesis> hypotheses_;
  std::vector<Hypothesis> sorted_;  // scratch of the sort by cost
  size_t sorted_count_ = 0;          // hypotheses_ sorted by cost; the rest added by holds()
  std::vector<Hypothesis> assignments_;  // see geometry()
  std::vector<Hypothesis> edge_hypotheses_;  // identify_at_edge's, kept for their capacity
  std::vector<bool> interchangeable_;    // per target: all four markers play one code
  // Targets with too many combinations to weigh in this call: each marker's
  // candidate tracks with their code cost, and the least cost per marker.
  struct Unweighed {
    size_t target = 0;
    std::array<std::vector<std::pair<int, double>>, 4> candidates;
    std::array<double, 4> least{};
  };
  std::vector<Unweighed> unweighed_;
  std::map<GeometryKey, GeometryEvidence> geometry_evidence_;
  // Three-track hypotheses (missing marker's track -1): frames they held alone,
  // since they last failed.
  std::map<GeometryKey, int> edge_evidence_;
  size_t last_hypotheses_ = 0;
};

}  // namespace tetrapulse
