#include "tetrapulse/localizer/target_appearance.hpp"

#include <cmath>

#include <fmt/format.h>

namespace tetrapulse {

namespace {

const char* describe(Appearance a, const std::optional<MarkerColour>& c) {
  if (c) return "coloured";
  return a == Appearance::kDark ? "dark" : "light";
}

// Same hue within a few degrees: blends of either lie on one line from grey.
bool same_hue(const MarkerColour& a, const MarkerColour& b) {
  const double cross = a.u * b.v - a.v * b.u, dot = a.u * b.u + a.v * b.v;
  return dot > 0 && std::abs(std::atan2(cross, dot)) < 0.1;
}

}  // namespace

tl::expected<BlobExtractorConfig, std::string> blobs_for_targets(BlobExtractorConfig base, const TargetsFile& targets) {
  const Marker* first = nullptr;
  for (const Target& t : targets.targets) {
    for (size_t k = 0; k < t.markers.size(); ++k) {
      const Marker& m = t.markers[k];
      if (!first) {
        first = &m;
        continue;
      }
      const bool differs = m.colour.has_value() != first->colour.has_value() ||
                           (m.colour && !same_hue(*m.colour, *first->colour)) ||
                           (!m.colour && m.appearance != first->appearance);
      if (differs) {
        return tl::unexpected(fmt::format(
            "target {} marker {} is {}, the first marker {}: one rig's markers must all look alike (light, dark, or "
            "one colour)",
            t.id, k, describe(m.appearance, m.colour), describe(first->appearance, first->colour)));
      }
    }
  }
  if (!first) return base;
  if (first->colour) {
    ColourTarget c = base.colour.value_or(ColourTarget{});
    c.cr = 128.0 + first->colour->v;
    c.cb = 128.0 + first->colour->u;
    base.colour = c;
    base.fit_every_circle = true;  // painted colours are lit by the scene, LEDs through a lens: both may be cut
  } else if (first->appearance == Appearance::kDark) {
    base.polarity = MarkerPolarity::kDark;
    base.fit_every_circle = true;  // painted balls, shaded on the side away from the light
  }
  // Shaded balls dim towards the limb: the rim is followed low, near the floor's level
  // (a half-shadowed dark ball: 0.46 px centroid error, 0.15 px at 0.5 of the peak, 0.06 px at 0.25).
  if (base.fit_every_circle) base.circle_rim_fraction = 0.25;
  return base;
}

}  // namespace tetrapulse
