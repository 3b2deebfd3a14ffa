#pragma once
// Renders what the camera collects over one exposure [t0_ns, t0_ns + exposure_ns)
// of rig time (global shutter):
//   light_p = sum over spheres s, sub-steps k of
//             radiance_s * emission_s([a_k, b_k)) * (b_k - a_k) * pixel_p(PSF (x) silhouette_s(mid_k))
// with emission the emitter's exact mean over the sub-step and the silhouette the
// sphere's true image (sphere_silhouette.hpp) at the sub-step's middle, covered
// exactly on a grid s times finer than the pixels (coverage_patch.hpp), then
// blurred and integrated over each pixel (pixel_response.hpp). The fine grid
// still places each bit of light at its cell's centre, which moves a small
// silhouette's centroid by a fraction of a cell; s (4, 8, 16 or 32) is chosen per
// sphere so that its image spans at least min_cells_across cells in radius. Sub-steps are
// chosen per sphere so that it moves at most blur_step_px between them (motion
// blur); a still sphere takes one.
// A painted ball (LightSphere::painted) replaces radiance x emission by its shading
// under the scene's light, per fine cell, less the background it hides.
// The sensor (sensor_model.hpp) then adds background, noise and quantisation.
#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "tetrapulse/sim/coverage_patch.hpp"
#include "tetrapulse/sim/pixel_response.hpp"
#include "tetrapulse/sim/scene.hpp"
#include "tetrapulse/sim/sensor_model.hpp"

namespace tetrapulse::sim {

struct RenderSettings {
  double psf_sigma_px = 0.6;            // Gaussian PSF, pixels
  double blur_step_px = 0.25;           // largest motion between sub-steps, pixels
  int max_substeps = 64;                // per sphere and exposure
  double outline_tolerance_px = 1e-3;   // largest gap between the outline polygon and the true silhouette
  int min_oversampling = 4;             // coverage grid cells per pixel along each axis, at least
  double min_cells_across = 16;         // image radius in grid cells, at least (up to 32 cells per pixel)
};

class FrameRenderer {
 public:
  FrameRenderer(const Scene& scene, const RenderSettings& settings, SensorModel& sensor);

  // Adds the electrons each pixel collects from the spheres to `light_e` (CV_32F,
  // camera-sized), as a grey sensor sees them (each light's mean over R, G, B).
  void add_light(int64_t t0_ns, int64_t exposure_ns, cv::Mat* light_e);
  // The same per colour channel: rgb_e = {R, G, B}, each a whole camera-sized image.
  void add_light_rgb(int64_t t0_ns, int64_t exposure_ns, const std::array<cv::Mat*, 3>& rgb_e);

  // The whole frame: light, then the sensor (noise drawn from noise_seed). A Bayer
  // sensor (SensorConfig::bayer) gives an 8-bit BGR image (CV_8UC3), demosaiced.
  void render(int64_t t0_ns, int64_t exposure_ns, uint64_t noise_seed, cv::Mat* image);

 private:
  // Camera-frame centre of light `light` at rig time t (ns).
  Eigen::Vector3d centre_in_camera(const LightSphere& light, double t_ns) const;
  // False when the sphere lies wholly outside the lens's field of view.
  bool in_field_of_view(const Eigen::Vector3d& centre_C, double radius_m) const;
  // Radiance factor of the LED beam towards the camera (1 for a uniform light) at rig time t_ns, centre c (camera frame).
  double beam_factor(const LightSphere& light, const Eigen::Vector3d& centre_C, double t_ns) const;
  struct Channel {
    cv::Mat* image;
    int rgb_index;  // 0 R, 1 G, 2 B; -1 grey
  };
  using Channels = std::vector<Channel>;
  void add_sphere(const LightSphere& light, int64_t t0_ns, int64_t exposure_ns, const Channels& out);
  static void add_pixels(const PixelImage& b, double factor, cv::Mat* light_e);
  // A painted ball's patch (coverage x time in view) turned into its light less the
  // background it hides; centre in the camera frame at rig time t_ns, s cells per pixel.
  void shade_painted(const LightSphere& light, const Eigen::Vector3d& centre, double t_ns, int s);

  const Scene& scene_;
  RenderSettings settings_;
  SensorModel& sensor_;
  std::vector<PixelResponse> responses_;  // oversampling 4, 8, 16, 32 (from min_oversampling)
  double max_field_angle_ = 0;  // largest angle from the optical axis that the image shows (rad)
  // Scratch, kept between calls to avoid allocations.
  std::vector<std::vector<Eigen::Vector2d>> outlines_;
  std::vector<double> weights_;
  CoveragePatch patch_;
  PixelImage blurred_;
  std::vector<double> hidden_;  // a painted ball's hidden background, laid out as patch_
  cv::Mat light_;
  std::array<cv::Mat, 3> channel_light_;
  cv::Mat raw_;
};

}  // namespace tetrapulse::sim
