// camera.yaml: the ROS camera_info YAML layout (docs/rig-dataset.md).
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/datasets/yaml_fields.hpp"

namespace tetrapulse {

using yaml_fields::Fields;

namespace {

// A ROS matrix block {rows, cols, data}; checks the declared shape against the data.
std::vector<double> read_matrix(Fields& f, const YAML::Node& doc, const std::string& key, int rows, int cols_min,
                                int cols_max) {
  YAML::Node m = f.child(doc, key, "");
  if (f.failed()) return {};
  const int r = f.scalar<int>(f.child(m, "rows", key), key + ".rows", "an integer");
  const int c = f.scalar<int>(f.child(m, "cols", key), key + ".cols", "an integer");
  std::vector<double> data = f.numbers(f.child(m, "data", key), key + ".data");
  if (f.failed()) return {};
  if (r != rows || c < cols_min || c > cols_max) {
    f.fail(m, cols_min == cols_max
                  ? fmt::format("{}: expected rows: {}, cols: {}, got {}x{}", key, rows, cols_min, r, c)
                  : fmt::format("{}: expected rows: {}, cols: {}..{}, got {}x{}", key, rows, cols_min, cols_max, r, c));
    return {};
  }
  if (static_cast<int>(data.size()) != r * c) {
    f.fail(m["data"], fmt::format("{}.data: expected {} numbers ({}x{}), got {}", key, r * c, r, c, data.size()));
    return {};
  }
  for (size_t i = 0; i < data.size(); ++i) {
    if (!std::isfinite(data[i])) {
      f.fail(m["data"], fmt::format("{}.data[{}]: not a finite number", key, i));
      return {};
    }
  }
  return data;
}

}  // namespace

DatasetResult<CameraInfo> parse_camera_yaml(const std::string& text, const std::string& name) {
  auto doc = yaml_fields::load_yaml(text, name);
  if (!doc) return tl::unexpected(doc.error());
  Fields f(name);
  CameraInfo cam;
  cam.width = f.scalar<int>(f.child(*doc, "image_width", ""), "image_width", "an integer");
  cam.height = f.scalar<int>(f.child(*doc, "image_height", ""), "image_height", "an integer");
  if (!f.failed() && (cam.width <= 0 || cam.height <= 0 || cam.width > 65536 || cam.height > 65536)) {
    f.fail((*doc)["image_width"], fmt::format("image_width/image_height: {}x{} is not a valid image size",
                                              cam.width, cam.height));
  }
  YAML::Node name_node = f.child(*doc, "camera_name", "", false);
  if (name_node.IsDefined()) cam.name = f.scalar<std::string>(name_node, "camera_name", "a string");

  const std::vector<double> K = read_matrix(f, *doc, "camera_matrix", 3, 3, 3);
  if (!f.failed()) {
    cam.fx = K[0];
    cam.fy = K[4];
    cam.cx = K[2];
    cam.cy = K[5];
    if (!(cam.fx > 0) || !(cam.fy > 0)) {
      f.fail((*doc)["camera_matrix"], "camera_matrix: focal lengths data[0] and data[4] must be positive");
    } else if (K[1] != 0 || K[3] != 0 || K[6] != 0 || K[7] != 0 || K[8] != 1) {
      f.fail((*doc)["camera_matrix"],
             "camera_matrix: expected [fx 0 cx; 0 fy cy; 0 0 1] (skew must be 0, last row 0 0 1)");
    }
  }

  const std::string model = f.scalar<std::string>(f.child(*doc, "distortion_model", ""), "distortion_model",
                                                  "a string");
  if (!f.failed()) {
    if (model == "plumb_bob") {
      cam.model = DistortionModel::kPlumbBob;
    } else if (model == "equidistant") {
      cam.model = DistortionModel::kEquidistant;
    } else {
      f.fail((*doc)["distortion_model"],
             fmt::format("distortion_model: '{}' is not supported (plumb_bob or equidistant)", model));
    }
  }
  if (!f.failed()) {
    // plumb_bob: k1 k2 p1 p2 [k3]; equidistant: k1 k2 k3 k4.
    const bool pinhole = cam.model == DistortionModel::kPlumbBob;
    const std::vector<double> D = read_matrix(f, *doc, "distortion_coefficients", 1, pinhole ? 4 : 4, pinhole ? 5 : 4);
    for (size_t i = 0; i < D.size(); ++i) cam.distortion[i] = D[i];
  }
  if (f.failed()) return tl::unexpected(f.error());
  return cam;
}

DatasetResult<CameraInfo> read_camera_yaml(const std::string& path) {
  auto text = read_text_file(path);
  if (!text) return tl::unexpected(text.error());
  return parse_camera_yaml(*text, path);
}

std::string format_camera_yaml(const CameraInfo& c) {
  std::vector<double> D(c.distortion.begin(), c.distortion.begin() + c.distortion_count());
  std::string out;
  out += fmt::format("image_width: {}\nimage_height: {}\n", c.width, c.height);
  out += fmt::format("camera_name: {}\n", yaml_fields::quoted(c.name));
  out += fmt::format("camera_matrix:\n  rows: 3\n  cols: 3\n  data: [{}, 0, {}, 0, {}, {}, 0, 0, 1]\n", c.fx, c.cx,
                     c.fy, c.cy);
  out += fmt::format("distortion_model: {}\n", distortion_model_name(c.model));
  out += fmt::format("distortion_coefficients:\n  rows: 1\n  cols: {}\n  data: [{}]\n", D.size(), fmt::join(D, ", "));
  out += "rectification_matrix:\n  rows: 3\n  cols: 3\n  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n";
  out += fmt::format("projection_matrix:\n  rows: 3\n  cols: 4\n  data: [{}, 0, {}, 0, 0, {}, {}, 0, 0, 0, 1, 0]\n",
                     c.fx, c.cx, c.fy, c.cy);
  return out;
}

}  // namespace tetrapulse
