#include "tetrapulse/sim/frame_renderer.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "tetrapulse/sim/sphere_silhouette.hpp"

namespace tetrapulse::sim {

namespace {
// Spheres whose cone begins this far outside the image's field of view are skipped
// (a distorted pinhole model folds far-off points back into the image).
constexpr double kFieldMarginRad = 2.0 * M_PI / 180.0;
}  // namespace

FrameRenderer::FrameRenderer(const Scene& scene, const RenderSettings& settings, SensorModel& sensor)
    : scene_(scene), settings_(settings), sensor_(sensor) {
  for (int s = std::max(1, settings.min_oversampling); s <= 32; s *= 2) responses_.emplace_back(settings.psf_sigma_px, s);
  const LensProjector& cam = scene_.camera;
  const double w = cam.width() - 0.5, h = cam.height() - 0.5;
  const Eigen::Vector2d border[] = {{-0.5, -0.5}, {w, -0.5}, {-0.5, h}, {w, h},
                                    {w / 2, -0.5}, {w / 2, h}, {-0.5, h / 2}, {w, h / 2}};
  for (const Eigen::Vector2d& px : border) {
    Eigen::Vector3d bearing;
    const double angle = cam.unproject(px, &bearing) ? std::acos(std::clamp(bearing.z(), -1.0, 1.0)) : M_PI / 2;
    max_field_angle_ = std::max(max_field_angle_, angle);
  }
}

Eigen::Vector3d FrameRenderer::centre_in_camera(const LightSphere& light, double t_ns) const {
  return scene_.body_in_camera(light.body, t_ns * 1e-9).apply(light.position_m);
}

double FrameRenderer::beam_factor(const LightSphere& light, const Eigen::Vector3d& c, double t_ns) const {
  if (light.beam_exponent == 0) return 1.0;
  const Eigen::Vector3d axis_C = scene_.body_in_camera(light.body, t_ns * 1e-9).R * light.beam_axis_B;
  const double cosine = -axis_C.dot(c) / c.norm();  // the camera seen from the light
  return cosine > 0 ? std::pow(cosine, light.beam_exponent) : 0.0;
}

bool FrameRenderer::in_field_of_view(const Eigen::Vector3d& c, double radius_m) const {
  const double alpha = sphere_half_angle(c, radius_m);
  if (!std::isfinite(alpha)) return false;
  const double off_axis = std::acos(std::clamp(c.z() / c.norm(), -1.0, 1.0));
  return off_axis - alpha <= max_field_angle_ + kFieldMarginRad;
}

void FrameRenderer::add_sphere(const LightSphere& light, int64_t t0, int64_t exposure, const Channels& out) {
  const double t_start = static_cast<double>(t0), t_end = static_cast<double>(t0 + exposure);
  const Eigen::Vector3d c0 = centre_in_camera(light, t_start);
  const Eigen::Vector3d c1 = centre_in_camera(light, 0.5 * (t_start + t_end));
  const Eigen::Vector3d c2 = centre_in_camera(light, t_end);
  const double r = light.radius_m;
  if (!in_field_of_view(c0, r) && !in_field_of_view(c1, r) && !in_field_of_view(c2, r)) return;

  // How far the image moves over the exposure sets the sub-steps.
  const LensProjector& cam = scene_.camera;
  Eigen::Vector2d p0, p1, p2;
  double travel_px;
  if (cam.project(c0, &p0) && cam.project(c1, &p1) && cam.project(c2, &p2)) {
    travel_px = (p1 - p0).norm() + (p2 - p1).norm();
  } else {
    const double f = std::max(cam.info().fx, cam.info().fy);
    const auto angle = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); };
    travel_px = f * (angle(c0, c1) + angle(c1, c2));
  }
  const int steps = static_cast<int>(
      std::clamp(std::ceil(travel_px / settings_.blur_step_px), 1.0, static_cast<double>(settings_.max_substeps)));

  const LedEmitter& emitter = *scene_.emitters[static_cast<size_t>(light.emitter)];
  const double radiance_e_per_ns = light.radiance_e_per_ms * 1e-6;
  if (outlines_.size() < static_cast<size_t>(steps)) outlines_.resize(static_cast<size_t>(steps));
  weights_.clear();
  for (int k = 0; k < steps; ++k) {
    const int64_t a = t0 + exposure * k / steps;
    const int64_t b = t0 + exposure * (k + 1) / steps;
    if (b <= a) continue;
    const double e = emitter.mean_emission(light.emitter_index, a, b);
    if (!(e > 0)) continue;
    const Eigen::Vector3d c = steps == 1 ? c1 : centre_in_camera(light, 0.5 * static_cast<double>(a + b));
    if (!in_field_of_view(c, r)) continue;
    // A painted ball: the time it is in view (ms); its shading comes per cell below.
    const double beam = light.painted ? 1.0 : beam_factor(light, c, 0.5 * static_cast<double>(a + b));
    if (!(beam > 0)) continue;
    if (!sphere_outline(cam, c, r, settings_.outline_tolerance_px, &outlines_[weights_.size()])) continue;
    weights_.push_back(beam * e * (light.painted ? 1e-6 : radiance_e_per_ns) * static_cast<double>(b - a));
  }
  if (weights_.empty()) return;

  // The patch: every outline's cells, within the image grown by the PSF's reach.
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
  for (size_t k = 0; k < weights_.size(); ++k) {
    for (const Eigen::Vector2d& p : outlines_[k]) {
      xmin = std::min(xmin, p.x());
      xmax = std::max(xmax, p.x());
      ymin = std::min(ymin, p.y());
      ymax = std::max(ymax, p.y());
    }
  }
  // Oversampling from the silhouette's size (its outline's mean radius).
  double perimeter = 0;
  const std::vector<Eigen::Vector2d>& first = outlines_[0];
  for (size_t k = 0; k < first.size(); ++k) perimeter += (first[(k + 1) % first.size()] - first[k]).norm();
  const double radius_px = perimeter / (2 * M_PI);
  const PixelResponse* response = &responses_.front();
  for (const PixelResponse& candidate : responses_) {
    response = &candidate;
    if (radius_px * candidate.oversampling() >= settings_.min_cells_across) break;
  }
  const int s = response->oversampling(), R = response->radius();
  const auto cell = [s](double u) { return std::floor((u + 0.5) * s); };  // fine cell holding pixel coordinate u
  const double fx0 = std::max(-R * s * 1.0, cell(xmin)), fx1 = std::min((cam.width() + R) * s - 1.0, cell(xmax));
  const double fy0 = std::max(-R * s * 1.0, cell(ymin)), fy1 = std::min((cam.height() + R) * s - 1.0, cell(ymax));
  if (fx1 < fx0 || fy1 < fy0) return;
  const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  const int pw = static_cast<int>(fx1) - x0 + 1, ph = static_cast<int>(fy1) - y0 + 1;
  patch_.reset(x0, y0, pw, ph);
  // A fine cell is 1 / s^2 of a pixel.
  const double per_cell = 1.0 / (s * s);
  for (size_t k = 0; k < weights_.size(); ++k) patch_.add_polygon(outlines_[k], weights_[k] * per_cell, s);
  patch_.resolve();
  if (light.painted) shade_painted(light, c1, 0.5 * (t_start + t_end), s);

  // The light in each channel: its colour's share of it (a grey sensor: the mean).
  response->apply(FineImage{patch_.row(0), pw, ph, pw + 1, x0, y0}, &blurred_);
  for (const Channel& c : out) add_pixels(blurred_, c.rgb_index < 0 ? light.rgb.mean() : light.rgb[c.rgb_index], c.image);
  if (light.painted) {  // the background the ball hides, in every channel alike
    response->apply(FineImage{hidden_.data(), pw, ph, pw + 1, x0, y0}, &blurred_);
    for (const Channel& c : out) add_pixels(blurred_, -1.0, c.image);
  }
}

void FrameRenderer::add_pixels(const PixelImage& b, double factor, cv::Mat* light_e) {
  for (int j = std::max(0, -b.y0); j < b.height && b.y0 + j < light_e->rows; ++j) {
    float* dst = light_e->ptr<float>(b.y0 + j);
    const double* src = b.data.data() + static_cast<size_t>(j) * static_cast<size_t>(b.width);
    for (int i = std::max(0, -b.x0); i < b.width && b.x0 + i < light_e->cols; ++i) {
      dst[b.x0 + i] += static_cast<float>(factor * src[i]);
    }
  }
}

// Each fine cell of the patch holds (covered area) x (time in view, ms). A painted
// ball there shows paint x (ambient + (1 - ambient) max(0, n.l)), n the sphere's
// normal where the cell centre's ray meets it (the limb's normal for a ray that
// passes by: edge cells), l the light in the camera frame: the patch becomes that.
// And it hides the background, whose light the sensor adds everywhere: hidden_
// gets (covered area) x (time) x background, taken off afterwards. The ball's
// position is the exposure's middle (shading moves little within one).
void FrameRenderer::shade_painted(const LightSphere& light, const Eigen::Vector3d& centre, double t_ns, int s) {
  const LensProjector& cam = scene_.camera;
  const Eigen::Vector3d l_C = (scene_.camera_motion.at(t_ns * 1e-9).R.transpose() * scene_.light_direction_W).normalized();
  Eigen::Vector2d centre_px;
  if (!cam.project(centre, &centre_px)) centre_px = Eigen::Vector2d(cam.width() / 2.0, cam.height() / 2.0);
  const double floor = sensor_.background_e_per_ms_at(static_cast<int>(std::lround(centre_px.x())),
                                                      static_cast<int>(std::lround(centre_px.y())));
  const double r = light.radius_m, ambient = scene_.ambient;
  const size_t stride = static_cast<size_t>(patch_.width()) + 1;
  hidden_.assign(stride * static_cast<size_t>(patch_.height()), 0.0);
  for (int j = 0; j < patch_.height(); ++j) {
    double* row = patch_.row(j);
    double* hidden = hidden_.data() + static_cast<size_t>(j) * stride;
    for (int i = 0; i < patch_.width(); ++i) {
      if (row[i] == 0) continue;
      hidden[i] = row[i] * floor;
      // Fine cell (x0 + i, y0 + j) is centred on pixel coordinate (cell + 0.5) / s - 0.5.
      const Eigen::Vector2d u((patch_.x0() + i + 0.5) / s - 0.5, (patch_.y0() + j + 0.5) / s - 0.5);
      Eigen::Vector3d d;
      if (!cam.unproject(u, &d)) d = centre.normalized();
      d.normalize();
      const double along = d.dot(centre);
      const double miss2 = centre.squaredNorm() - along * along;  // squared distance of the ray from the centre
      const Eigen::Vector3d hit = miss2 < r * r ? d * (along - std::sqrt(r * r - miss2)) : d * along;
      const Eigen::Vector3d n = (hit - centre).normalized();
      const double shade = ambient + (1.0 - ambient) * std::max(0.0, n.dot(l_C));
      row[i] *= light.paint_e_per_ms * shade;
    }
  }
}

void FrameRenderer::add_light(int64_t t0_ns, int64_t exposure_ns, cv::Mat* light_e) {
  const Channels grey{Channel{light_e, -1}};
  for (const LightSphere& light : scene_.lights) add_sphere(light, t0_ns, exposure_ns, grey);
}

void FrameRenderer::add_light_rgb(int64_t t0_ns, int64_t exposure_ns, const std::array<cv::Mat*, 3>& rgb_e) {
  const Channels rgb{Channel{rgb_e[0], 0}, Channel{rgb_e[1], 1}, Channel{rgb_e[2], 2}};
  for (const LightSphere& light : scene_.lights) add_sphere(light, t0_ns, exposure_ns, rgb);
}

void FrameRenderer::render(int64_t t0_ns, int64_t exposure_ns, uint64_t noise_seed, cv::Mat* image) {
  const int w = scene_.camera.width(), h = scene_.camera.height();
  light_.create(h, w, CV_32F);
  light_.setTo(0);
  if (!sensor_.config().bayer) {
    add_light(t0_ns, exposure_ns, &light_);
    sensor_.expose(light_, exposure_ns, noise_seed, image);
    return;
  }
  // A Bayer colour sensor (RGGB: R at even rows and columns, B at odd ones): each
  // pixel collects its filter's channel; the raw frame is demosaiced as a camera's
  // driver would (OpenCV bilinear: its BG code names the RGGB layout).
  for (cv::Mat& c : channel_light_) {
    c.create(h, w, CV_32F);
    c.setTo(0);
  }
  add_light_rgb(t0_ns, exposure_ns, {&channel_light_[0], &channel_light_[1], &channel_light_[2]});
  for (int y = 0; y < h; ++y) {
    float* dst = light_.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      const int channel = (y % 2 == 0 && x % 2 == 0) ? 0 : (y % 2 == 1 && x % 2 == 1) ? 2 : 1;
      dst[x] = channel_light_[static_cast<size_t>(channel)].at<float>(y, x);
    }
  }
  sensor_.expose(light_, exposure_ns, noise_seed, &raw_);
  cv::cvtColor(raw_, *image, cv::COLOR_BayerBG2BGR);
}

}  // namespace tetrapulse::sim
