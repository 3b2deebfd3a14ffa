#include "tetrapulse/localizer/target_appearance.hpp"

#include <gtest/gtest.h>

namespace tetrapulse {
namespace {

TargetsFile rig(int targets) {
  TargetsFile f;
  for (int i = 0; i < targets; ++i) {
    Target t;
    t.id = i;
    f.targets.push_back(t);
  }
  return f;
}

TEST(TargetAppearance, LightGreyRigKeepsTheGivenSettings) {
  BlobExtractorConfig base;
  base.f2_sigmas = 3.5;
  const auto c = blobs_for_targets(base, rig(2));
  ASSERT_TRUE(c) << c.error();
  EXPECT_EQ(c->polarity, MarkerPolarity::kLight);
  EXPECT_FALSE(c->colour);
  EXPECT_FALSE(c->fit_every_circle);
  EXPECT_EQ(c->f2_sigmas, 3.5);
  EXPECT_EQ(c->circle_rim_fraction, 0.5);
}

TEST(TargetAppearance, DarkRigTurnsPolarityAndFitsCircles) {
  TargetsFile f = rig(2);
  for (Target& t : f.targets)
    for (Marker& m : t.markers) m.appearance = Appearance::kDark;
  const auto c = blobs_for_targets({}, f);
  ASSERT_TRUE(c) << c.error();
  EXPECT_EQ(c->polarity, MarkerPolarity::kDark);
  EXPECT_TRUE(c->fit_every_circle);
  EXPECT_LT(c->circle_rim_fraction, 0.5);
}

TEST(TargetAppearance, ColourRigSetsTheChromaLine) {
  TargetsFile f = rig(1);
  for (Marker& m : f.targets[0].markers) m.colour = named_colour("green");
  const auto c = blobs_for_targets({}, f);
  ASSERT_TRUE(c) << c.error();
  ASSERT_TRUE(c->colour);
  EXPECT_LT(c->colour->cr, 128);  // green: both chroma channels below grey
  EXPECT_LT(c->colour->cb, 128);
}

TEST(TargetAppearance, MixedRigIsRefusedNamingTheMarker) {
  TargetsFile f = rig(2);
  f.targets[1].markers[2].appearance = Appearance::kDark;
  const auto c = blobs_for_targets({}, f);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().find("target 1 marker 2 is dark"), std::string::npos) << c.error();

  TargetsFile two = rig(1);
  for (Marker& m : two.targets[0].markers) m.colour = named_colour("red");
  two.targets[0].markers[3].colour = named_colour("blue");
  EXPECT_FALSE(blobs_for_targets({}, two));
}

TEST(TargetAppearance, MixedRigGetsOneLookPerKindInOrderOfFirstMarker) {
  TargetsFile f = rig(4);
  for (Marker& m : f.targets[1].markers) m.appearance = Appearance::kDark;
  for (Marker& m : f.targets[2].markers) m.colour = named_colour("red");
  f.targets[3].markers[1].colour = MarkerColour{named_colour("red")->u * 0.5, named_colour("red")->v * 0.5, ""};
  f.targets[3].markers[2].colour = named_colour("blue");
  const RigLooks looks = rig_looks({}, f);
  ASSERT_EQ(looks.configs.size(), 4u);  // light, dark, red (a paler red too), blue
  EXPECT_TRUE(looks.mixed());
  EXPECT_EQ(looks.configs[0].polarity, MarkerPolarity::kLight);
  EXPECT_FALSE(looks.configs[0].colour);
  EXPECT_EQ(looks.configs[1].polarity, MarkerPolarity::kDark);
  ASSERT_TRUE(looks.configs[2].colour);
  EXPECT_GT(looks.configs[2].colour->cr, 128);
  ASSERT_TRUE(looks.configs[3].colour);
  EXPECT_GT(looks.configs[3].colour->cb, 128);
  ASSERT_EQ(looks.look_of.size(), 4u);
  EXPECT_EQ(looks.look_of[0], (std::array<int, 4>{0, 0, 0, 0}));
  EXPECT_EQ(looks.look_of[1], (std::array<int, 4>{1, 1, 1, 1}));
  EXPECT_EQ(looks.look_of[2], (std::array<int, 4>{2, 2, 2, 2}));
  EXPECT_EQ(looks.look_of[3], (std::array<int, 4>{0, 2, 3, 0}));
}

TEST(TargetAppearance, OneKindRigHasOneLook) {
  const RigLooks looks = rig_looks({}, rig(3));
  EXPECT_FALSE(looks.mixed());
  ASSERT_EQ(looks.configs.size(), 1u);
  for (const auto& of : looks.look_of) EXPECT_EQ(of, (std::array<int, 4>{0, 0, 0, 0}));
  EXPECT_EQ(rig_looks({}, TargetsFile{}).configs.size(), 1u);  // no markers: the base settings
}

}  // namespace
}  // namespace tetrapulse
