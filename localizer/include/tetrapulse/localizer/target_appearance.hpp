#pragma once
// What targets.yaml says of the markers' looks (appearance, colour) turned into
// the blob extractor's settings, so that no command-line flag has to repeat it.
// A rig may mix looks (coded LEDs and dark painted balls, two colours): each look
// gets an extractor of its own, its blobs are tracked apart from the others' and
// only its own markers take them.
#include <array>
#include <string>
#include <vector>

#include <tl/expected.hpp>

#include "tetrapulse/localizer/blob_extractor.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

// The rig's distinct looks, in the order their first marker appears in targets.yaml:
// light grey, dark grey, or one hue (markers whose chroma lies within ~6 degrees of
// the first one's about grey are one look).
struct RigLooks {
  std::vector<BlobExtractorConfig> configs;   // one extractor's settings per look
  std::vector<std::array<int, 4>> look_of;    // [target][marker]: index into configs
  bool mixed() const { return configs.size() > 1; }
};

// Each look's settings: `base` with polarity dark for dark markers, the colour target
// for coloured ones (ColourTarget's line from grey runs through it); both centre every
// blob by its circle fit (painted, scene-lit markers). A rig of light grey markers
// alone (or no markers) gives `base` as its one look.
RigLooks rig_looks(const BlobExtractorConfig& base, const TargetsFile& targets);

// The one look of a rig that has one; an error naming the first marker that differs
// (for callers that run a single extraction).
tl::expected<BlobExtractorConfig, std::string> blobs_for_targets(const BlobExtractorConfig& base,
                                                                 const TargetsFile& targets);

}  // namespace tetrapulse
