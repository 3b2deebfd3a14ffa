#include "background_flattening.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace tetrapulse::blob_internal {
namespace {

// The 30th percentile of a cell's pixels at even rows and columns.
template <typename T>
float low_of_cell(const cv::Mat& work, int x0, int y0, int cell, std::vector<int>* values) {
  values->clear();
  const int x1 = std::min(x0 + cell, work.cols), y1 = std::min(y0 + cell, work.rows);
  for (int y = y0; y < y1; y += 2) {
    const T* row = work.ptr<T>(y);
    for (int x = x0; x < x1; x += 2) values->push_back(row[x]);
  }
  auto low = values->begin() + std::ptrdiff_t(values->size() * 3 / 10);
  std::nth_element(values->begin(), low, values->end());
  return float(*low);
}

// Noise sigma from horizontal neighbours' differences on every fourth row.
template <typename T>
double noise_sigma(const cv::Mat& work, std::vector<int>* values) {
  values->clear();
  for (int y = 0; y < work.rows; y += 4) {
    const T* row = work.ptr<T>(y);
    for (int x = 0; x + 1 < work.cols; x += 2) values->push_back(std::abs(int(row[x + 1]) - int(row[x])));
  }
  if (values->empty()) return 0;
  auto mid = values->begin() + std::ptrdiff_t(values->size() / 2);
  std::nth_element(values->begin(), mid, values->end());
  return 1.4826 * double(*mid) / std::sqrt(2.0);
}

}  // namespace

void BackgroundFlattening::cell_map(const cv::Mat& work, int cell, cv::Mat* out) {
  const int nx = (work.cols + cell - 1) / cell, ny = (work.rows + cell - 1) / cell;
  cells_.create(ny, nx, CV_32F);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      cells_.at<float>(j, i) = work.depth() == CV_8U ? low_of_cell<uint8_t>(work, i * cell, j * cell, cell, &values_)
                                                     : low_of_cell<uint16_t>(work, i * cell, j * cell, cell, &values_);
  if (nx >= 3 && ny >= 3) cv::medianBlur(cells_, cells_, 3);
  // One more cell on every side, extrapolated linearly, so that the map follows a
  // gradient out to the image's edges rather than levelling off half a cell in.
  padded_.create(ny + 2, nx + 2, CV_32F);
  cells_.copyTo(padded_(cv::Rect(1, 1, nx, ny)));
  for (int j = 1; j <= ny; ++j) {
    padded_.at<float>(j, 0) = 2 * padded_.at<float>(j, 1) - padded_.at<float>(j, std::min(2, nx));
    padded_.at<float>(j, nx + 1) = 2 * padded_.at<float>(j, nx) - padded_.at<float>(j, std::max(nx - 1, 1));
  }
  for (int i = 0; i < nx + 2; ++i) {
    padded_.at<float>(0, i) = 2 * padded_.at<float>(1, i) - padded_.at<float>(std::min(2, ny), i);
    padded_.at<float>(ny + 1, i) = 2 * padded_.at<float>(ny, i) - padded_.at<float>(std::max(ny - 1, 1), i);
  }
  cv::resize(padded_, scaled_, cv::Size((nx + 2) * cell, (ny + 2) * cell), 0, 0, cv::INTER_LINEAR);
  scaled_(cv::Rect(cell, cell, work.cols, work.rows)).copyTo(*out);
}

const cv::Mat& BackgroundFlattening::apply(const cv::Mat& work, double saturation) {
  flattened_ = false;
  if (work.cols < 3 * kFineCell || work.rows < 3 * kFineCell) return work;
  const bool eight = work.depth() == CV_8U;
  const double sigma =
      std::max(1.0, eight ? noise_sigma<uint8_t>(work, &values_) : noise_sigma<uint16_t>(work, &values_));
  cell_map(work, kCoarseCell, &coarse_);
  std::vector<float> levels(coarse_.begin<float>(), coarse_.end<float>());
  std::sort(levels.begin(), levels.end());
  const double spread = levels[levels.size() * 9 / 10] - levels[levels.size() / 10];
  if (spread <= 4 * sigma) return work;
  cell_map(work, kFineCell, &fine_);
  // A large bright object lifts the fine map: it may lie at most 12 sigmas above the coarse one.
  cv::min(fine_, coarse_ + 12 * sigma, fine_);
  const double median = levels[levels.size() / 2];
  out_.create(work.size(), work.type());
  for (int y = 0; y < work.rows; ++y) {
    const float* b = fine_.ptr<float>(y);
    if (eight) {
      const uint8_t* in = work.ptr<uint8_t>(y);
      uint8_t* o = out_.ptr<uint8_t>(y);
      for (int x = 0; x < work.cols; ++x)
        o[x] = in[x] >= saturation ? in[x] : cv::saturate_cast<uint8_t>(in[x] - b[x] + median);
    } else {
      const uint16_t* in = work.ptr<uint16_t>(y);
      uint16_t* o = out_.ptr<uint16_t>(y);
      for (int x = 0; x < work.cols; ++x)
        o[x] = in[x] >= saturation ? in[x] : cv::saturate_cast<uint16_t>(in[x] - b[x] + median);
    }
  }
  flattened_ = true;
  return out_;
}

}  // namespace tetrapulse::blob_internal
