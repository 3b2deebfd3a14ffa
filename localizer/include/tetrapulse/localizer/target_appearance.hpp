#pragma once
// What targets.yaml says of the markers' looks (appearance, colour) turned into
// the blob extractor's settings, so that no command-line flag has to repeat it.
#include <string>

#include <tl/expected.hpp>

#include "tetrapulse/localizer/blob_extractor.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse {

// `base` with polarity dark when every marker is dark, and the colour target
// when markers have a colour (ColourTarget's line from grey runs through it);
// both centre every blob by its circle fit (painted, scene-lit markers).
// One extraction serves a frame, so a rig must be of one kind: light and dark
// markers mixed, coloured and grey ones mixed, or two colours are an error
// naming the first target that differs. A rig of light grey markers gives `base`.
tl::expected<BlobExtractorConfig, std::string> blobs_for_targets(BlobExtractorConfig base, const TargetsFile& targets);

}  // namespace tetrapulse
