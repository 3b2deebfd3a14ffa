#include "tetrapulse/localizer/target_appearance.hpp"

#include <cmath>

#include <fmt/format.h>

namespace tetrapulse {

namespace {

const char* describe(const Marker& m) {
  if (m.colour) return "coloured";
  return m.appearance == Appearance::kDark ? "dark" : "light";
}

// Same hue within a few degrees: blends of either lie on one line from grey.
bool same_hue(const MarkerColour& a, const MarkerColour& b) {
  const double cross = a.u * b.v - a.v * b.u, dot = a.u * b.u + a.v * b.v;
  return dot > 0 && std::abs(std::atan2(cross, dot)) < 0.1;
}

bool same_look(const Marker& a, const Marker& b) {
  if (a.colour.has_value() != b.colour.has_value()) return false;
  return a.colour ? same_hue(*a.colour, *b.colour) : a.appearance == b.appearance;
}

BlobExtractorConfig look_config(BlobExtractorConfig base, const Marker& first) {
  if (first.colour) {
    ColourTarget c = base.colour.value_or(ColourTarget{});
    c.cr = 128.0 + first.colour->v;
    c.cb = 128.0 + first.colour->u;
    base.colour = c;
    base.fit_every_circle = true;  // painted colours are lit by the scene, LEDs through a lens: both may be cut
  } else if (first.appearance == Appearance::kDark) {
    base.polarity = MarkerPolarity::kDark;
    base.fit_every_circle = true;  // painted balls, shaded on the side away from the light
  }
  // Shaded balls dim towards the limb: the rim is followed low, near the floor's level
  // (a half-shadowed dark ball: 0.46 px centroid error, 0.15 px at 0.5 of the peak, 0.06 px at 0.25).
  if (base.fit_every_circle) base.circle_rim_fraction = 0.25;
  return base;
}

}  // namespace

RigLooks rig_looks(const BlobExtractorConfig& base, const TargetsFile& targets) {
  RigLooks looks;
  std::vector<const Marker*> firsts;
  for (const Target& t : targets.targets) {
    std::array<int, 4> of{};
    for (size_t k = 0; k < t.markers.size() && k < of.size(); ++k) {
      const Marker& m = t.markers[k];
      size_t l = 0;
      while (l < firsts.size() && !same_look(m, *firsts[l])) ++l;
      if (l == firsts.size()) firsts.push_back(&m);
      of[k] = int(l);
    }
    looks.look_of.push_back(of);
  }
  for (const Marker* m : firsts) looks.configs.push_back(look_config(base, *m));
  if (looks.configs.empty()) looks.configs.push_back(base);
  return looks;
}

tl::expected<BlobExtractorConfig, std::string> blobs_for_targets(const BlobExtractorConfig& base,
                                                                 const TargetsFile& targets) {
  const RigLooks looks = rig_looks(base, targets);
  if (!looks.mixed()) return looks.configs.front();
  const Marker* first = nullptr;
  for (size_t t = 0; t < targets.targets.size(); ++t)
    for (size_t k = 0; k < targets.targets[t].markers.size(); ++k) {
      const Marker& m = targets.targets[t].markers[k];
      if (!first) first = &m;
      if (looks.look_of[t][k] != 0) {
        return tl::unexpected(fmt::format("target {} marker {} is {}, the first marker {}: one extraction serves one "
                                          "look (light, dark, or one colour)",
                                          targets.targets[t].id, k, describe(m), describe(*first)));
      }
    }
  return looks.configs.front();
}

}  // namespace tetrapulse
