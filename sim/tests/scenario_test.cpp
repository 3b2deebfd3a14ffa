// Scenario files: the built-ins (geometry, codes), and malformed files that must
// give a located error naming the field, never a crash.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <set>
#include <sstream>

#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/codebook/codebook_frequency.hpp"
#include "tetrapulse/sim/builtin_scenarios.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"

namespace tetrapulse::sim {
namespace {

const std::string kHardware = std::string(TETRAPULSE_SOURCE_DIR) + "/hardware/targets/";

Scenario builtin(const std::string& name) {
  const BuiltinScenario* b = find_builtin_scenario(name);
  EXPECT_NE(b, nullptr) << name;
  auto s = parse_scenario(b ? b->text : "", name);
  EXPECT_TRUE(s) << s.error().what();
  return s ? *s : Scenario{};
}

TEST(BuiltinScenarios, AllExistAndParse) {
  const std::set<std::string> expected = {"paper-exp1", "paper-far", "swarm",      "unsync",     "passive",
                                          "clutter",    "fisheye",   "frequency",  "agile",      "distortion",
                                          "beam-spread", "dropouts",  "sat-exp1-5x", "sat-exp1-20x", "sat-landing",
                                          "sat-clutter", "sat-fisheye", "agile-sat",  "crowd",      "crowd-on-off", "sat-bloom",
                                          "sat-passive", "passive-dark", "colour", "mixed", "climb-colour"};
  std::set<std::string> names;
  for (const BuiltinScenario& b : builtin_scenarios()) {
    names.insert(b.name);
    auto s = parse_scenario(b.text, b.name + ".yaml");
    ASSERT_TRUE(s) << s.error().what();
    EXPECT_EQ(s->name, b.name);
    EXPECT_FALSE(s->description.empty()) << b.name;
    EXPECT_LE(s->frames.ci_count, 60) << b.name << ": the CI variant must stay small";
    EXPECT_GT(s->frames.count, s->frames.ci_count) << b.name;
    EXPECT_EQ(s->simulation.size(), s->targets.targets.size());
  }
  EXPECT_EQ(names, expected);
}

void expect_geometry(const Scenario& s, const std::string& hardware_file) {
  auto hw = read_targets_yaml(kHardware + hardware_file);
  ASSERT_TRUE(hw) << hw.error().what();
  const Target& ref = hw->targets.front();
  for (const Target& t : s.targets.targets) {
    EXPECT_DOUBLE_EQ(t.marker_diameter_m, ref.marker_diameter_m) << s.name << " target " << t.id;
    for (size_t m = 0; m < 4; ++m) {
      EXPECT_EQ(t.markers[m].position_m, ref.markers[m].position_m) << s.name << " target " << t.id << " marker " << m;
    }
  }
}

TEST(BuiltinScenarios, TargetsHaveThePapersGeometry) {
  for (const char* name : {"paper-exp1", "paper-far", "passive", "clutter", "fisheye"}) {
    expect_geometry(builtin(name), "paper-large.yaml");
  }
  for (const char* name : {"swarm", "unsync", "frequency"}) expect_geometry(builtin(name), "paper-half-active.yaml");
}

TEST(BuiltinScenarios, PaperExperimentOneSetup) {
  const Scenario s = builtin("paper-exp1");
  EXPECT_EQ(s.camera.width, 752);
  EXPECT_EQ(s.camera.height, 480);
  EXPECT_NEAR(2 * std::atan(s.camera.width / 2.0 / s.camera.fx) * 180 / M_PI, 90.0, 1e-9);
  EXPECT_EQ(s.frames.period_ns, 10'000'000);  // 100 fps
  const auto& m = std::get<SmoothRandomMotion>(s.camera_motion);
  EXPECT_NEAR(m.centre.t.z() - m.amplitude_m.z(), 0.68, 1e-9);
  EXPECT_NEAR(m.centre.t.z() + m.amplitude_m.z(), 1.74, 1e-9);
  const Scenario swarm = builtin("swarm");
  EXPECT_EQ(swarm.camera.width, 1280);
  EXPECT_EQ(swarm.camera.height, 960);
  EXPECT_NEAR(std::get<StaticMotion>(swarm.camera_motion).pose.t.z(), 2.3, 1e-12);
  const Scenario fisheye = builtin("fisheye");
  EXPECT_EQ(fisheye.camera.model, DistortionModel::kEquidistant);
  EXPECT_NEAR(fisheye.camera.width / 2.0 / fisheye.camera.fx * 2 * 180 / M_PI, 150.0, 1e-9);
}

// --- Code constraints --------------------------------------------------------

int hamming(const Code& a, const Code& b) { return __builtin_popcountll(a.bits ^ b.bits); }

Code rotate(const Code& c, uint32_t k) {
  Code r = c;
  r.bits = 0;
  for (uint32_t i = 0; i < c.length; ++i) r.bits |= uint64_t{c.bit((i + k) % c.length)} << i;
  return r;
}

uint32_t longest_cyclic_zero_run(const Code& c) {
  uint32_t best = 0, run = 0;
  for (uint32_t i = 0; i < 2 * c.length; ++i) {
    run = c.bit(i) ? 0 : run + 1;
    best = std::max(best, run);
  }
  return std::min<uint32_t>(best, c.length);
}

// Why the codes of one scenario fail its time base's constraints, or "" when they pass.
std::string code_violations(const std::vector<Code>& codes, bool synchronized) {
  std::ostringstream why;
  for (size_t i = 0; i < codes.size(); ++i) {
    const Code& c = codes[i];
    const int weight = __builtin_popcountll(c.bits);
    if (synchronized) {
      if (c.length != 12) why << code_text(c) << ": length " << unsigned(c.length) << " (want 12); ";
      if (weight < 5 || weight > 7) why << code_text(c) << ": weight " << weight << " (want 5..7); ";
      if (longest_cyclic_zero_run(c) > 2) why << code_text(c) << ": a cyclic zero run over 2; ";
      for (size_t j = i + 1; j < codes.size(); ++j) {
        if (hamming(c, codes[j]) < 3) why << code_text(c) << " vs " << code_text(codes[j]) << ": distance < 3; ";
      }
    } else {
      if (c.length != 15) why << code_text(c) << ": length " << unsigned(c.length) << " (want 15); ";
      if (longest_cyclic_zero_run(c) > 3) why << code_text(c) << ": a cyclic zero run over 3; ";
      for (uint32_t k = 1; k < c.length; ++k) {
        if (hamming(c, rotate(c, k)) < 3) why << code_text(c) << ": its own shift " << k << " is within distance 2; ";
      }
      for (size_t j = i + 1; j < codes.size(); ++j) {
        for (uint32_t k = 0; k < c.length; ++k) {
          if (hamming(c, rotate(codes[j], k)) < 3) why << code_text(c) << " vs a shift of " << code_text(codes[j]) << "; ";
        }
      }
    }
  }
  return why.str();
}

std::vector<Code> all_codes(const Scenario& s) {
  std::vector<Code> codes;
  for (const Target& t : s.targets.targets) {
    for (const Marker& m : t.markers) {
      if (m.code) codes.push_back(*m.code);
    }
  }
  return codes;
}

TEST(BuiltinScenarios, CodesMeetTheirTimeBasesConstraints) {
  for (const BuiltinScenario& b : builtin_scenarios()) {
    const Scenario s = builtin(b.name);
    const std::vector<Code> codes = all_codes(s);
    if (s.targets.modulation.kind == ModulationKind::kConstant) {
      EXPECT_TRUE(codes.empty()) << b.name;
      continue;
    }
    // Passive targets (no code on any marker: geometry names them, as in mixed) aside,
    // every marker carries a code.
    const size_t coded_targets = size_t(std::count_if(s.targets.targets.begin(), s.targets.targets.end(), [](const Target& t) {
      return std::any_of(t.markers.begin(), t.markers.end(), [](const Marker& m) { return m.code.has_value(); });
    }));
    EXPECT_GT(coded_targets, 0u) << b.name;
    EXPECT_EQ(codes.size(), 4 * coded_targets) << b.name << ": one code per marker";
    if (std::all_of(codes.begin(), codes.end(), [](const Code& c) {
          return protocol::is_square_wave(c);
        })) {
      // Frequency codes (SPEC.md §8.5): the distinct ones separable at this camera.
      std::vector<uint64_t> words;
      std::vector<uint8_t> lengths;
      for (const Code& c : codes) {
        bool seen = false;
        for (size_t i = 0; i < words.size(); ++i) seen = seen || (words[i] == c.bits && lengths[i] == c.length);
        if (seen) continue;
        words.push_back(c.bits);
        lengths.push_back(static_cast<uint8_t>(c.length));
      }
      protocol::FrequencySpec spec;
      spec.camera = protocol::CameraTiming{s.frames.period_ns, s.frames.exposure_ns};
      spec.bit_period_ns = s.targets.timebase.bit_period_ns;
      const protocol::FrequencyReport r = protocol::check_frequency_codes(spec, words.data(), lengths.data(), words.size());
      EXPECT_TRUE(r.ok()) << b.name << ": " << protocol::frequency_fault_name(r.fault) << " at code " << r.code;
      continue;
    }
    // One code per target (the crowds): a target whose markers all carry one code counts it once.
    std::vector<Code> distinct;
    for (size_t t = 0; t < coded_targets; ++t) {
      const auto first = codes.begin() + static_cast<std::ptrdiff_t>(4 * t);
      const bool one = std::all_of(first, first + 4, [&](const Code& c) { return c.bits == first->bits && c.length == first->length; });
      distinct.insert(distinct.end(), first, one ? first + 1 : first + 4);
    }
    EXPECT_EQ(code_violations(distinct, s.targets.timebase.synchronized), "") << b.name;
  }
}

TEST(BuiltinScenarios, TheCodeCheckCatchesBadCodes) {
  const auto code = [](const char* t) { return *parse_code(t, nullptr); };
  EXPECT_NE(code_violations({code("010011100101"), code("010011100110")}, true), "");     // distance 2
  EXPECT_NE(code_violations({code("000111100101")}, true), "");                           // zero run 3
  EXPECT_NE(code_violations({code("111111100101")}, true), "");                           // weight 9
  EXPECT_NE(code_violations({code("101010101010101")}, false), "");                       // its own shift
  EXPECT_NE(code_violations({code("111001110001011"), code("111100111000101")}, false), "");  // a shift of the other
}

// --- Malformed files ------------------------------------------------------------

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

int line_of(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  return at == std::string::npos ? -1 : 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

struct Malformed {
  const char* what;
  std::string text;
  std::string expected;  // the message must contain this
  int line;              // expected line; 0 = any line > 0; -1 = no line
};

TEST(ScenarioYaml, MalformedFilesNameTheFieldAndLine) {
  const std::string base = find_builtin_scenario("clutter")->text;
  const std::string unsync = find_builtin_scenario("unsync")->text;
  const std::string fisheye = find_builtin_scenario("fisheye")->text;
  const std::vector<Malformed> cases = {
      {"unknown field", replace(base, "  hfov_deg: 90", "  hfov_dg: 90"), "camera.hfov_dg: unknown field",
       line_of(base, "  hfov_deg: 90")},
      {"missing exposure", replace(base, "  exposure_ns: 2000000\n", ""), "frames.exposure_ns: missing required field", 0},
      {"exposure too long", replace(base, "exposure_ns: 2000000", "exposure_ns: 20000000"),
       "frames.exposure_ns: must not exceed period_ns", line_of(base, "exposure_ns: 2000000")},
      {"bad motion kind", replace(base, "kind: smooth_random", "kind: teleport"), "camera.motion.kind: 'teleport'",
       line_of(base, "kind: smooth_random")},
      {"clock error beyond the contract", replace(base, "clock_ppm: 120", "clock_ppm: 350"),
       "targets[0].board.clock_ppm: must be in [-200, 200], got 350", line_of(base, "clock_ppm: 120")},
      {"bad code", replace(base, "code: \"011001001001\"", "code: \"011201001001\""), "targets[0].markers[1].code", 0},
      {"three markers", replace(base, "      - position_m: [-0.0802, 0.0249, 0.0621]\n        code: \"010010010110\"\n", ""),
       "targets[0].markers: expected exactly four markers", 0},
      {"YAML syntax", replace(base, "amplitude_m: [0.15, 0.10, 0.53]", "amplitude_m: [0.15, 0.10, 0.53"), "YAML syntax", 0},
      {"occlusion marker out of range", replace(base, "{marker: 2, from_s: 0.3", "{marker: 4, from_s: 0.3"),
       "targets[0].occlusions[1].marker: must be in [0, 3], got 4", line_of(base, "{marker: 2, from_s: 0.3")},
      {"occlusion ends before it starts", replace(base, "from_s: 0.1, to_s: 0.16", "from_s: 0.1, to_s: 0.05"),
       "targets[0].occlusions[0].to_s: must be later than from_s", 0},
      {"sync loss without sync", replace(unsync, "      clock_offset_ns: 3712345", "      clock_offset_ns: 3712345\n      sync_loss_s: [[1, 2]]"),
       "targets[0].board.sync_loss_s: the time base is not synchronized", 0},
      {"can sync without a synchronized time base",
       replace(unsync, "      clock_offset_ns: 3712345", "      clock_offset_ns: 3712345\n      sync: can"),
       "targets[0].board.sync: 'can': the time base is not synchronized, so only none", 0},
      {"unknown sync", replace(base, "clock_ppm: 120", "clock_ppm: 120\n      sync: ptp"),
       "targets[0].board.sync: 'ptp' is not gpio or can", 0},
      {"fisheye coefficient count", replace(fisheye, "[0.01, -0.005, 0.001, 0.0]", "[0.01, -0.005, 0.001, 0.0, 0.0]"),
       "camera.distortion_coefficients: expected 4 (k1 k2 k3 k4) numbers", 0},
      {"flicker kind", replace(base, "{kind: sine,", "{kind: strobe,"), "distractors[1].flicker.kind: 'strobe'", 0},
      {"not a number", replace(base, "radiance_e_per_ms: 1600", "radiance_e_per_ms: bright"),
       "targets[0].radiance_e_per_ms: expected a number, got 'bright'", line_of(base, "radiance_e_per_ms: 1600")},
      {"negative diameter", replace(base, "marker_diameter_m: 0.03", "marker_diameter_m: -0.03"),
       "targets[0].marker_diameter_m: must be positive", 0},
      {"waypoints out of order", replace(find_builtin_scenario("swarm")->text, "{t_s: 4.8,", "{t_s: 3.8,"),
       "targets[2].motion.points[3].t_s: must be later than", 0},
      {"codebook not wired in yet", base + "codebook: {size: 4}\n", "codebook: codes from the codebook generator", 0},
      {"no camera", replace(base, "camera:\n  name: firefly-mv", "kamera:\n  name: firefly-mv"), "kamera: unknown field", 0},
      {"empty file", "", "expected a YAML mapping", -1},
      {"a list, not a mapping", "- 1\n- 2\n", "expected a YAML mapping", -1},
  };
  for (const Malformed& c : cases) {
    auto s = parse_scenario(c.text, "bad.yaml");
    ASSERT_FALSE(s) << c.what;
    const DatasetError& e = s.error();
    EXPECT_EQ(e.file, "bad.yaml") << c.what;
    EXPECT_NE(e.message.find(c.expected), std::string::npos) << c.what << ": " << e.what();
    if (c.line > 0) {
      EXPECT_EQ(e.line, c.line) << c.what << ": " << e.what();
    } else if (c.line == 0) {
      EXPECT_GT(e.line, 0) << c.what << ": " << e.what();
    }
    if (c.line >= 0) {  // "bad.yaml:LINE: field: what"
      EXPECT_EQ(e.what().rfind("bad.yaml:" + std::to_string(e.line) + ": ", 0), 0u) << e.what();
    }
  }
}

TEST(ScenarioYaml, UnknownNameOrMissingFileIsAnError) {
  auto s = load_scenario("no-such-scenario");
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().what().find("no-such-scenario"), std::string::npos);
}

// Random damage to a built-in never crashes the reader: it reads or it explains.
RC_GTEST_PROP(ScenarioYaml, DamagedFilesReadOrExplain, ()) {
  const auto& all = builtin_scenarios();
  std::string text = all[*rc::gen::inRange<size_t>(0, all.size())].text;
  const int edits = *rc::gen::inRange(1, 6);
  for (int i = 0; i < edits && !text.empty(); ++i) {
    const size_t at = *rc::gen::inRange<size_t>(0, text.size());
    switch (*rc::gen::inRange(0, 4)) {
      case 0: text.erase(at, *rc::gen::inRange<size_t>(1, 40)); break;
      case 1: text[at] = *rc::gen::element(':', '-', '[', ']', '{', '"', '\n', ' ', '9', 'x', '#', '\t'); break;
      case 2: text.insert(at, *rc::gen::element<std::string>("\n  - ", ": ", "-1e400", "nan", "[]", "{}", "  ")); break;
      default: text.resize(at); break;
    }
  }
  auto s = parse_scenario(text, "damaged.yaml");
  if (!s) {
    RC_ASSERT(!s.error().message.empty());
    RC_ASSERT(s.error().file == "damaged.yaml");
  }
}

}  // namespace
}  // namespace tetrapulse::sim
