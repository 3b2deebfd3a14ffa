// libFuzzer: any bytes become an image (size, type, polarity, pixels) and a
// list of ROIs; BlobExtractor must answer without a sanitizer finding.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "tetrapulse/localizer/blob_extractor.hpp"

namespace {

class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
  int16_t i16() { return int16_t(uint16_t(u8()) | uint16_t(u8()) << 8); }
  size_t left() const { return size_ - pos_; }
  const uint8_t* here() const { return data_ + pos_; }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tetrapulse;
  Bytes in(data, size);
  const int width = in.u8() % 64, height = in.u8() % 64;
  const uint8_t flags = in.u8();
  const int types[3] = {CV_8UC1, CV_16UC1, CV_8UC3};
  const int type = types[flags % 3];
  BlobExtractorConfig config;
  config.polarity = (flags & 4) ? MarkerPolarity::kDark : MarkerPolarity::kLight;
  if (type == CV_8UC3 && (flags & 8)) config.colour = ColourTarget{double(in.u8()), double(in.u8()), double(in.u8() % 64), 0};
  config.min_area = in.u8() % 8;
  config.max_erosions = in.u8() % 8;
  const int expected = int(in.u8() % 24) - 2;
  std::vector<BlobRoi> rois(in.u8() % 12);
  for (BlobRoi& r : rois) {
    r.center = {in.i16() / 4.0, in.i16() / 4.0};
    r.radius = in.i16() / 64.0;
    r.aperture_radius = in.i16() / 256.0;
  }
  cv::Mat image(height, width, type, cv::Scalar::all(0));
  const size_t bytes = image.total() * image.elemSize();
  if (bytes > 0) std::memcpy(image.data, in.here(), std::min(bytes, in.left()));
  BlobExtractor extractor(config);
  BlobExtraction out;
  (void)extractor.extract(image, expected, &out);
  (void)extractor.extract(image, rois, &out);
  return 0;
}
