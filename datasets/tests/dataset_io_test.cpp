#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <fstream>

#include <opencv2/imgcodecs.hpp>

#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/datasets/rig_dataset.hpp"

namespace tetrapulse {
namespace {

namespace fs = std::filesystem;

const char* kPaperTargets = R"(timebase:
  synchronized: true
  epoch_ns: 0
  bit_period_ns: 10000000
modulation:
  kind: two_level
  low: 0.3
targets:
  - id: 1
    name: landmark
    marker_diameter_m: 0.03
    markers:
      - position_m: [0.0000, -0.1651, 0.2366]
        code: "1101001110"
      - position_m: [0.0000,  0.1304, 0.1845]
        code: "1011100100"
      - position_m: [0.0626, -0.0221, 0.0539]
        code: "0111010011"
      - position_m: [-0.0802, 0.0249, 0.0621]
)";

const char* kCamera = R"(image_width: 752
image_height: 480
camera_name: firefly
camera_matrix:
  rows: 3
  cols: 3
  data: [376.0, 0, 375.5, 0, 376.0, 239.5, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.1, 0.01, 0, 0, 0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
)";

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("tp_dataset_" + std::to_string(::getpid()) + "_" +
                                                  std::to_string(counter_++))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string str() const { return path_.string(); }
  std::string file(const std::string& name, const std::string& text) const {
    const std::string p = (path_ / name).string();
    std::ofstream(p) << text;
    return p;
  }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

TEST(TargetsYaml, ReadsTheContractExample) {
  auto t = parse_targets_yaml(kPaperTargets, "targets.yaml");
  ASSERT_TRUE(t) << t.error().what();
  EXPECT_TRUE(t->timebase.synchronized);
  EXPECT_EQ(t->timebase.bit_period_ns, 10000000);
  EXPECT_EQ(t->modulation.kind, ModulationKind::kTwoLevel);
  EXPECT_DOUBLE_EQ(t->modulation.low, 0.3);
  ASSERT_EQ(t->targets.size(), 1u);
  EXPECT_EQ(code_text(*t->targets[0].markers[0].code), "1101001110");
  EXPECT_FALSE(t->targets[0].markers[3].code.has_value());
  EXPECT_DOUBLE_EQ(t->targets[0].markers[2].position_m.x(), 0.0626);
}

TEST(TargetsYaml, FormatRoundTripsEveryField) {
  auto t = parse_targets_yaml(kPaperTargets, "targets.yaml");
  ASSERT_TRUE(t);
  t->targets[0].name = "tricky \"name\"\twith: yaml";
  const std::string text = format_targets_yaml(*t);
  auto back = parse_targets_yaml(text, "again.yaml");
  ASSERT_TRUE(back) << back.error().what();
  EXPECT_EQ(format_targets_yaml(*back), text);
  EXPECT_EQ(back->targets[0].name, t->targets[0].name);
}

TEST(TargetsYaml, OldFilesReadAsLightGreyMarkers) {
  auto t = parse_targets_yaml(kPaperTargets, "targets.yaml");
  ASSERT_TRUE(t);
  EXPECT_FALSE(t->needs_colour());
  for (const Marker& m : t->targets[0].markers) {
    EXPECT_EQ(m.appearance, Appearance::kLight);
    EXPECT_FALSE(m.colour.has_value());
  }
  const std::string text = format_targets_yaml(*t);
  EXPECT_EQ(text.find("appearance"), std::string::npos);  // nothing new written for LED rigs
  EXPECT_EQ(text.find("colour"), std::string::npos);
}

TEST(TargetsYaml, AppearanceAndColourPerTargetAndMarker) {
  std::string text = kPaperTargets;
  const std::string at = "    markers:";
  text.replace(text.find(at), at.size(), "    appearance: dark\n    colour: red\n    markers:");
  const std::string m1 = "        code: \"1011100100\"";
  text.replace(text.find(m1), m1.size(), m1 + "\n        colour: {u: 40.5, v: -30}");
  const std::string m2 = "        code: \"0111010011\"";
  text.replace(text.find(m2), m2.size(), m2 + "\n        appearance: light\n        colour: none");
  auto t = parse_targets_yaml(text, "targets.yaml");
  ASSERT_TRUE(t) << t.error().what();
  const Target& target = t->targets[0];
  EXPECT_EQ(target.markers[0].appearance, Appearance::kDark);
  ASSERT_TRUE(target.markers[0].colour);
  EXPECT_EQ(target.markers[0].colour->name, "red");
  EXPECT_GT(target.markers[0].colour->v, 100);  // red: Cr far above grey
  EXPECT_LT(target.markers[0].colour->u, 0);
  ASSERT_TRUE(target.markers[1].colour);
  EXPECT_DOUBLE_EQ(target.markers[1].colour->u, 40.5);
  EXPECT_DOUBLE_EQ(target.markers[1].colour->v, -30);
  EXPECT_EQ(target.markers[2].appearance, Appearance::kLight);
  EXPECT_FALSE(target.markers[2].colour);
  EXPECT_TRUE(t->needs_colour());
  const std::string again = format_targets_yaml(*t);
  auto back = parse_targets_yaml(again, "again.yaml");
  ASSERT_TRUE(back) << back.error().what() << "\n" << again;
  EXPECT_EQ(format_targets_yaml(*back), again);
}

TEST(TargetsYaml, BadAppearanceAndColourNameFileAndField) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"    appearance: shiny\n", "targets[0].appearance"},
      {"    colour: mauve\n", "targets[0].colour"},
      {"    colour: {u: 3}\n", "targets[0].colour.v"},
      {"    colour: {u: 2, v: 1}\n", "too close to grey"},
      {"    colour: {u: 500, v: 1}\n", "targets[0].colour"},
      {"    colour: [1, 2]\n", "targets[0].colour"},
  };
  for (const auto& [insert, mentions] : cases) {
    std::string text = kPaperTargets;
    text.insert(text.find("    markers:"), insert);
    auto t = parse_targets_yaml(text, "targets.yaml");
    ASSERT_FALSE(t) << "accepted: " << insert;
    EXPECT_EQ(t.error().file, "targets.yaml");
    EXPECT_NE(t.error().message.find(mentions), std::string::npos) << t.error().what();
    EXPECT_GT(t.error().line, 0) << t.error().what();
  }
}

struct BadCase {
  std::string from, to;  // textual edit of the valid file
  int line;              // expected error line
  std::string mentions;  // expected text in the message
};

TEST(TargetsYaml, BadFieldsAreNamedWithTheirLine) {
  const std::vector<BadCase> cases = {
      {"bit_period_ns: 10000000", "bit_period_ns: -5", 4, "timebase.bit_period_ns"},
      {"bit_period_ns: 10000000", "bit_period_ns: fast", 4, "timebase.bit_period_ns"},
      {"kind: two_level", "kind: blinky", 6, "modulation.kind"},
      {"low: 0.3", "low: 1.5", 7, "modulation.low"},
      {"code: \"1011100100\"", "code: \"10211\"", 17, "targets[0].markers[1].code"},
      {"      - position_m: [-0.0802, 0.0249, 0.0621]\n", "", 11, "exactly four markers"},
      {"[0.0626, -0.0221, 0.0539]", "[0.0626, -0.0221]", 18, "targets[0].markers[2].position_m"},
      {"marker_diameter_m: 0.03", "marker_diameter_m: 0", 11, "marker_diameter_m"},
      {"  epoch_ns: 0\n", "", 1, "timebase.epoch_ns"},
      {"targets:", "targets: [", 9, "YAML syntax"},
  };
  for (const auto& c : cases) {
    std::string text = kPaperTargets;
    const size_t at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, c.from.size(), c.to);
    auto t = parse_targets_yaml(text, "targets.yaml");
    ASSERT_FALSE(t) << "accepted: " << c.to;
    EXPECT_EQ(t.error().file, "targets.yaml");
    EXPECT_NE(t.error().message.find(c.mentions), std::string::npos) << t.error().what();
    EXPECT_GT(t.error().line, 0) << t.error().what();
  }
}

TEST(CameraYaml, ReadsRosCameraInfoAndRoundTrips) {
  auto c = parse_camera_yaml(kCamera, "camera.yaml");
  ASSERT_TRUE(c) << c.error().what();
  EXPECT_EQ(c->width, 752);
  EXPECT_EQ(c->name, "firefly");
  EXPECT_DOUBLE_EQ(c->cx, 375.5);
  EXPECT_DOUBLE_EQ(c->distortion[0], -0.1);
  const std::string text = format_camera_yaml(*c);
  auto back = parse_camera_yaml(text, "again.yaml");
  ASSERT_TRUE(back) << back.error().what();
  EXPECT_EQ(format_camera_yaml(*back), text);
}

TEST(CameraYaml, BadFieldsAreNamed) {
  const std::vector<std::pair<std::string, std::string>> edits = {
      {"data: [376.0, 0, 375.5, 0, 376.0, 239.5, 0, 0, 1]", "data: [376.0, 0, 375.5, 0, 376.0, 239.5, 0, 0]"},
      {"distortion_model: plumb_bob", "distortion_model: rational_polynomial"},
      {"image_width: 752", "image_width: -3"},
      {"cols: 5", "cols: 8"},
  };
  const std::vector<std::string> mentions = {"camera_matrix", "distortion_model", "image_width",
                                             "distortion_coefficients"};
  for (size_t i = 0; i < edits.size(); ++i) {
    std::string text = kCamera;
    text.replace(text.find(edits[i].first), edits[i].first.size(), edits[i].second);
    auto c = parse_camera_yaml(text, "camera.yaml");
    ASSERT_FALSE(c) << edits[i].second;
    EXPECT_NE(c.error().message.find(mentions[i]), std::string::npos) << c.error().what();
  }
}

TEST(FramesCsv, RejectsDuplicateAndUnsortedTimestampsNamingTheLine) {
  TempDir dir;
  auto dup = read_frames_csv(dir.file("a.csv", "frame,timestamp_ns,exposure_ns,file\n0,100,10,a.png\n1,100,10,b.png\n"));
  ASSERT_FALSE(dup);
  EXPECT_EQ(dup.error().line, 3);
  EXPECT_NE(dup.error().message.find("duplicates"), std::string::npos);
  auto unsorted =
      read_frames_csv(dir.file("b.csv", "frame,timestamp_ns,exposure_ns,file\n0,100,10,a.png\n1,90,10,b.png\n"));
  ASSERT_FALSE(unsorted);
  EXPECT_EQ(unsorted.error().line, 3);
  auto header = read_frames_csv(dir.file("c.csv", "frame,time,exposure_ns,file\n"));
  ASSERT_FALSE(header);
  EXPECT_EQ(header.error().line, 1);
  auto fields = read_frames_csv(dir.file("d.csv", "frame,timestamp_ns,exposure_ns,file\n0,100,10\n"));
  ASSERT_FALSE(fields);
  EXPECT_EQ(fields.error().line, 2);
  auto missing = read_frames_csv(dir.str() + "/nope.csv");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().what().find("nope.csv"), std::string::npos);
  auto skipped = read_frames_csv(dir.file("e.csv", "frame,timestamp_ns,exposure_ns,file\n0,100,10,a.png\n5,200,10,b.png\n"));
  ASSERT_TRUE(skipped) << skipped.error().what();
  EXPECT_EQ(skipped->back().frame, 5);
}

// Given a list for them, malformed rows cost only themselves: each is listed with its
// line, in line order, and every good row (checked against the good ones before) is kept.
TEST(FramesCsv, SkipsMalformedRowsNamingEachLine) {
  TempDir dir;
  std::vector<DatasetError> skipped;
  auto rows = read_frames_csv(dir.file("f.csv",
                                       "frame,timestamp_ns,exposure_ns,file\n"
                                       "0,100,10,a.png\n"
                                       "1,soon,10,b.png\n"  // line 3: not a number
                                       "2,300,10\n"         // line 4: a field short
                                       "3,300,10,d.png\n"
                                       "4,300,10,e.png\n"   // line 6: duplicates frame 3
                                       "5,500,10,f.png\n"),
                              &skipped);
  ASSERT_TRUE(rows) << rows.error().what();
  ASSERT_EQ(rows->size(), 3u);
  EXPECT_EQ((*rows)[1].frame, 3);
  EXPECT_EQ((*rows)[2].frame, 5);
  ASSERT_EQ(skipped.size(), 3u);
  EXPECT_EQ(skipped[0].line, 3);
  EXPECT_NE(skipped[0].message.find("timestamp_ns"), std::string::npos);
  EXPECT_EQ(skipped[1].line, 4);
  EXPECT_EQ(skipped[2].line, 6);
  EXPECT_NE(skipped[2].what().find("f.csv:6"), std::string::npos);
  // A wrong header is still the whole file's error.
  EXPECT_FALSE(read_frames_csv(dir.file("g.csv", "frame,time,exposure_ns,file\n0,1,1,a.png\n"), &skipped));
}

// The writer tests' camera.yaml and targets.yaml, parsed (none if either fails).
struct WriterInputs {
  CameraInfo camera;
  TargetsFile targets;
};
std::optional<WriterInputs> writer_inputs() {
  auto camera = parse_camera_yaml(kCamera, "camera.yaml");
  auto targets = parse_targets_yaml(kPaperTargets, "targets.yaml");
  if (!camera || !targets) return std::nullopt;
  return WriterInputs{*camera, *targets};
}

// A recording that dies before finish() (a crash, a killed process, a pulled
// cable) is still a dataset: camera.yaml and targets.yaml are written at once,
// and every frame's row is in frames.csv as soon as its PNG is.
TEST(RigDataset, WriterLeavesADatasetAfterEveryFrameWithoutFinish) {
  TempDir dir;
  const auto in = writer_inputs();
  ASSERT_TRUE(in);
  const std::string folder = dir.str() + "/live";
  auto w = RigDatasetWriter::create(folder, in->camera, in->targets);
  ASSERT_TRUE(w) << w.error().what();
  {
    auto empty = RigDataset::open(folder);
    ASSERT_TRUE(empty) << empty.error().what();
    EXPECT_EQ(empty->frames().size(), 0u);
  }
  const cv::Mat img(480, 752, CV_8UC1, cv::Scalar(9));
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(w->add_frame(k, 1'000'000 + k * 10'000'000, 2'000'000, img));
    auto d = RigDataset::open(folder);  // what a reader finds if the process died now
    ASSERT_TRUE(d) << d.error().what();
    ASSERT_EQ(d->frames().size(), size_t(k + 1));
    EXPECT_EQ(d->frames().back().timestamp_ns, 1'000'000 + k * 10'000'000);
    EXPECT_TRUE(d->load_image(size_t(k)));
  }
  ASSERT_TRUE(w->finish());
  auto d = RigDataset::open(folder);
  ASSERT_TRUE(d) << d.error().what();
  EXPECT_EQ(d->frames().size(), 3u);
}

TEST(RigDataset, WriterNamesTheFileItCannotWrite) {
  TempDir dir;
  const auto in = writer_inputs();
  ASSERT_TRUE(in);
  const std::string folder = dir.str() + "/ro";
  std::filesystem::create_directories(folder + "/camera.yaml");  // a folder where the file should go
  auto w = RigDatasetWriter::create(folder, in->camera, in->targets);
  ASSERT_FALSE(w);
  EXPECT_NE(w.error().what().find("camera.yaml"), std::string::npos) << w.error().what();
}

TEST(RigDataset, WriterOutputReadsBackWithEveryFieldPreserved) {
  TempDir dir;
  const auto in = writer_inputs();
  ASSERT_TRUE(in);
  const std::string folder = dir.str() + "/ds";
  auto w = RigDatasetWriter::create(folder, in->camera, in->targets);
  ASSERT_TRUE(w) << w.error().what();
  cv::Mat img8(480, 752, CV_8UC1, cv::Scalar(7));
  cv::Mat img16(480, 752, CV_16UC1, cv::Scalar(4000));
  ASSERT_TRUE(w->add_frame(0, 1'000'000, 2'000'000, img8));
  ASSERT_TRUE(w->add_frame(2, 21'000'000, 2'000'000, img16));
  GroundTruthRecord g;
  g.frame = 2;
  g.target = 1;
  g.pose.t = Eigen::Vector3d(0.1, -0.2, 1.3);
  g.pose.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  w->add_groundtruth(g);
  ASSERT_TRUE(w->finish());

  auto d = RigDataset::open(folder);
  ASSERT_TRUE(d) << d.error().what();
  EXPECT_EQ(format_camera_yaml(d->camera()), format_camera_yaml(in->camera));
  EXPECT_EQ(format_targets_yaml(d->targets()), format_targets_yaml(in->targets));
  ASSERT_EQ(d->frames().size(), 2u);
  EXPECT_EQ(d->frames()[1].frame, 2);
  EXPECT_EQ(d->frames()[1].timestamp_ns, 21'000'000);
  ASSERT_EQ(d->groundtruth().size(), 1u);
  EXPECT_EQ(d->groundtruth()[0].pose.t, g.pose.t);
  EXPECT_EQ(d->groundtruth()[0].pose.q.coeffs(), g.pose.q.coeffs());
  auto a = d->load_image(0);
  auto b = d->load_image(1);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->type(), CV_8UC1);
  EXPECT_EQ(b->type(), CV_16UC1);
  EXPECT_EQ(b->at<uint16_t>(10, 10), 4000);

  // An image of the wrong size is refused, naming the file.
  cv::imwrite(folder + "/frames/000002.png", cv::Mat(100, 100, CV_8UC1, cv::Scalar(0)));
  auto wrong = d->load_image(1);
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().what().find("000002.png"), std::string::npos);
  EXPECT_NE(wrong.error().message.find("100x100"), std::string::npos);
}

}  // namespace
}  // namespace tetrapulse
