#include "blob_regions.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <opencv2/core.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__aarch64__)
#include <arm_neon.h>
#endif

namespace tetrapulse::blob_internal {
namespace {

// Smallest integer value v with v > level, clamped to what an int holds.
int above(double level) {
  if (!(level < 1e9)) return std::numeric_limits<int>::max();
  if (level < -1e9) return std::numeric_limits<int>::min();
  return static_cast<int>(std::floor(level)) + 1;
}

// Whether some byte of `word` is >= level (1..255), all 8 at once: a byte b
// below 128 gains bit 7 from b + (128 - level) exactly when b >= level (no carry
// leaves it); above level 128, only bytes with bit 7 set can qualify, and their
// low 7 bits are compared the same way. A carry out of a byte >= 128 may mark
// the next byte wrongly, but only when some byte already qualifies.
bool any_byte_at_least(uint64_t word, int level) {
  constexpr uint64_t kOnes = 0x0101010101010101ull, kHigh = 0x8080808080808080ull;
  if (level <= 128) return (((word + kOnes * uint64_t(128 - level)) | word) & kHigh) != 0;
  return (((word & ~kHigh) + kOnes * uint64_t(256 - level)) & word & kHigh) != 0;
}

// The first x in [x, end) from which a value >= level (1..255) may follow in an
// 8-bit row, 64 pixels at a time while none of them reaches it (a whole image's
// two seed scans were a quarter of a full frame's instructions read 8 at a time):
// x itself, or the start of the first 64 that hold one, or where fewer than 64 are
// left. A byte reaches the level when its saturating difference from level - 1 is
// not zero (SSE2 on x86-64, NEON on aarch64; elsewhere x).
#if defined(__SSE2__)
// Each of the 16 bytes from `at` less `below` (level - 1 in every byte), saturated:
// not zero exactly where the byte reaches the level.
__m128i excess(const uint8_t* row, int at, __m128i below) {
  return _mm_subs_epu8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(row + at)), below);
}
#endif

int skip_64(const uint8_t* row, int x, int end, int level) {
#if defined(__SSE2__)
  const __m128i below = _mm_set1_epi8(static_cast<char>(level - 1));
  const auto above = [&](int at) { return excess(row, at, below); };
  for (; x + 64 <= end; x += 64) {
    const __m128i any = _mm_or_si128(_mm_or_si128(above(x), above(x + 16)), _mm_or_si128(above(x + 32), above(x + 48)));
    if (_mm_movemask_epi8(_mm_cmpeq_epi8(any, _mm_setzero_si128())) != 0xFFFF) break;
  }
#elif defined(__aarch64__)
  const uint8x16_t below = vdupq_n_u8(uint8_t(level - 1));
  const auto above = [&](int at) { return vqsubq_u8(vld1q_u8(row + at), below); };
  for (; x + 64 <= end; x += 64) {
    const uint8x16_t any = vorrq_u8(vorrq_u8(above(x), above(x + 16)), vorrq_u8(above(x + 32), above(x + 48)));
    if (vmaxvq_u8(any) != 0) break;
  }
#endif
  return x;
}

// skip_64, then 8 pixels at a time: the start of the first 8-pixel chunk from x
// that may hold a value >= level, or where fewer than 8 are left.
int skip_below(const uint8_t* row, int x, int end, int level) {
  x = skip_64(row, x, end, level);
  for (uint64_t word; x + 8 <= end; x += 8) {
    std::memcpy(&word, row + x, sizeof word);
    if (any_byte_at_least(word, level)) break;
  }
  return x;
}

#if defined(__SSE2__)
// Bit i set when row[at + i] >= level, for the 16 pixels from `at` (below: level - 1
// in every byte).
uint32_t bits_at_least(const uint8_t* row, int at, __m128i below) {
  return ~uint32_t(_mm_movemask_epi8(_mm_cmpeq_epi8(excess(row, at, below), _mm_setzero_si128()))) & 0xFFFFu;
}

#endif

// Bit i set when labels[i] == label, for the n (1..64) labels from `labels`.
uint64_t label_bits(const int32_t* labels, int n, int32_t label) {
  uint64_t bits = 0;
#if defined(__SSE2__)
  if (n >= 4) {  // four at a time, the last four overlapping the previous ones
    const __m128i want = _mm_set1_epi32(label);
    for (int at = 0; at < n; at += 4) {
      const int from = std::min(at, n - 4);
      const __m128i same = _mm_cmpeq_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(labels + from)), want);
      bits |= uint64_t(_mm_movemask_ps(_mm_castsi128_ps(same))) << from;
    }
    return bits;
  }
#endif
  for (int i = 0; i < n; ++i) bits |= uint64_t(labels[i] == label) << i;
  return bits;
}

// The turn o -> a -> b in the (y, x) plane: positive counter-clockwise.
int64_t cross(const HullPoint& o, const HullPoint& a, const HullPoint& b) {
  return (a.y - o.y) * (b.x - o.x) - (a.x - o.x) * (b.y - o.y);
}

// Area of the convex hull of `p` (twice the pixel-corner coordinates, so whole
// numbers: exact), sorted lexicographically (Andrew's monotone chain).
double convex_hull_area(const std::vector<HullPoint>& p, std::vector<HullPoint>* hull) {
  if (p.size() < 3) return 0.0;
  hull->resize(2 * p.size());
  auto& h = *hull;
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {  // one side
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // the other
    while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  int64_t twice = 0;  // twice the area, in doubled coordinates: 8 times the area
  for (size_t i = 0; i + 1 < k; ++i) twice += h[i].y * h[i + 1].x - h[i + 1].y * h[i].x;
  return double(twice < 0 ? -twice : twice) / 8.0;
}

}  // namespace

void RegionGrower::reset(cv::Size size) {
  if (size != size_) {
    size_ = size;
    labels_.assign(size_t(std::max(0, size.area())), 0);
  } else {
    clear();
  }
  pixels_.clear();
  next_label_ = 1;
}

void RegionGrower::clear() {
  for (const int32_t index : pixels_) labels_[size_t(index)] = 0;
  pixels_.clear();
}

void RegionGrower::grow(const cv::Mat& work, cv::Rect window, const Levels& levels, double seed_level,
                        std::vector<Region>* regions) {
  const int seed_min = above(std::max(seed_level, levels.f2));
  const int keep_min = above(levels.f2);
  const int top = work.depth() == CV_8U ? 255 : 65535;
  if (seed_min > top || window.area() <= 0) return;
  // Large 16-bit windows: find the rows' seeds with a vectorised comparison first
  // (8-bit rows are skipped 8 pixels at a time without one: skip_below).
  const bool masked = window.area() >= 4096 && (work.depth() != CV_8U || seed_min < 1);
  if (masked) {
    if (seed_mask_.size() != work.size()) seed_mask_.create(work.size(), CV_8U);
    cv::Mat dst = seed_mask_(window);
    cv::compare(work(window), cv::Scalar(std::max(seed_min, 0)), dst, cv::CMP_GE);
  }
  if (work.depth() == CV_8U) {
    grow_typed<uint8_t>(work, window, seed_min, keep_min, masked, regions);
  } else {
    grow_typed<uint16_t>(work, window, seed_min, keep_min, masked, regions);
  }
}

template <typename T>
void RegionGrower::grow_typed(const cv::Mat& work, cv::Rect window, int seed_min, int keep_min, bool masked,
                              std::vector<Region>* regions) {
  const int width = size_.width;
  const int x0 = window.x, x1 = window.x + window.width;
  const int y0 = window.y, y1 = window.y + window.height;
#if defined(__SSE2__)
  if constexpr (sizeof(T) == 1) {
    if (!masked && seed_min >= 1 && keep_min >= 1 && window.width >= 16 && window.width <= kMaxBitsWidth &&
        window.height <= kMaxBitsHeight) {
      grow_narrow(work, window, seed_min, keep_min, regions);
      return;
    }
  }
#endif
  for (int y = y0; y < y1; ++y) {
    const T* row = work.ptr<T>(y);
    const int32_t* labels = labels_.data() + size_t(y) * width;
    if (!masked) {
#if defined(__SSE2__)
      // 8-bit rows at least 16 wide that grow_narrow does not take (wider than 62:
      // a whole image): the seeds of 16 pixels at a time as bits, visited in order (a
      // region grown from one labels others further on), the last 16 overlapping the
      // previous ones.
      if constexpr (sizeof(T) == 1) {
        if (seed_min >= 1 && x1 - x0 >= 16) {
          const __m128i below = _mm_set1_epi8(static_cast<char>(seed_min - 1));
          for (int x = skip_64(row, x0, x1, seed_min); x < x1; x = skip_64(row, x, x1, seed_min)) {
            const int at = std::min(x, x1 - 16);
            for (uint32_t bits = bits_at_least(row, at, below) >> (x - at); bits != 0; bits &= bits - 1) {
              const int sx = x + __builtin_ctz(bits);
              if (labels[sx] == 0) grow_from<T>(work, window, y * width + sx, keep_min, regions);
            }
            x = at + 16;
          }
          continue;
        }
      }
#endif
      for (int x = x0; x < x1;) {
        int end = x1;
        if constexpr (sizeof(T) == 1) {
          if (seed_min >= 1) {
            x = skip_below(row, x, x1, seed_min);  // background, 8 pixels at a time
            end = std::min(x + 8, x1);             // then the 8 that may hold a seed, one by one
          }
        }
        for (; x < end; ++x)
          if (row[x] >= seed_min && labels[x] == 0) grow_from<T>(work, window, y * width + x, keep_min, regions);
      }
      continue;
    }
    const uint8_t* seeds = seed_mask_.ptr<uint8_t>(y);
    for (int x = x0; x < x1; ++x) {
      // Skip 8 seedless pixels at a time.
      while (x + 8 <= x1) {
        uint64_t word;
        std::memcpy(&word, seeds + x, sizeof word);
        if (word != 0) break;
        x += 8;
      }
      if (x >= x1) break;
      if (!seeds[x]) continue;
      if (row[x] < seed_min || labels[x] != 0) continue;
      grow_from<T>(work, window, y * width + x, keep_min, regions);
    }
  }
}

#if defined(__SSE2__)
void RegionGrower::grow_narrow(const cv::Mat& work, cv::Rect window, int seed_min, int keep_min,
                               std::vector<Region>* regions) {
  const int width = size_.width, rows = window.height;
  // Each row's seeds, and its open pixels: above f2 and not labelled yet (by this
  // window's earlier pass or an overlapping window).
  const __m128i seed_below = _mm_set1_epi8(static_cast<char>(seed_min - 1));
  const __m128i keep_below = _mm_set1_epi8(static_cast<char>(keep_min - 1));
  seed_rows_.resize(size_t(rows));
  open_rows_.resize(size_t(rows));
  for (int r = 0; r < rows; ++r) {
    const int y = window.y + r;
    const uint8_t* row = work.ptr<uint8_t>(y) + window.x;
    uint64_t seeds = 0, open = 0;
    for (int at = 0; at < window.width; at += 16) {
      const int from = std::min(at, window.width - 16);  // the last 16 overlap
      seeds |= uint64_t(bits_at_least(row, from, seed_below)) << from;
      open |= uint64_t(bits_at_least(row, from, keep_below)) << from;
    }
    const int32_t* labels = labels_.data() + size_t(y) * width + window.x;
    for (uint64_t b = open; b != 0; b &= b - 1)
      if (labels[__builtin_ctzll(b)] != 0) open &= ~(b & -b);
    seed_rows_[size_t(r)] = seeds;
    open_rows_[size_t(r)] = open;
  }
  for (int r = 0; r < rows; ++r)
    for (uint64_t b = seed_rows_[size_t(r)]; b != 0; b &= b - 1) {
      const int i = __builtin_ctzll(b);
      if (open_rows_[size_t(r)] >> i & 1) grow_bits(window, i, r, regions);
    }
}

void RegionGrower::grow_bits(cv::Rect window, int c, int r, std::vector<Region>* regions) {
  if (bits_queue_.size() < size_t(window.area())) bits_queue_.resize(size_t(window.area()));
  uint32_t* const queue = bits_queue_.data();  // entries c | r << 16
  uint64_t* const open = open_rows_.data();
  const int rows = window.height;
  size_t tail = 0;
  queue[tail++] = uint32_t(c) | uint32_t(r) << 16;
  open[r] &= ~(uint64_t(1) << c);
  // Breadth-first, neighbours row by row as in grow_from: each of the three rows'
  // open neighbours as 3 bits (bit k: column pc - 1 + k), taken in order and
  // cleared from the row at once (one store a row: the next pixel's loads of the
  // same rows wait for it).
  for (size_t head = 0; head < tail; ++head) {
    const uint32_t at = queue[head];
    const int pc = int(at & 0xFFFF), pr = int(at >> 16);
    for (int ny = std::max(pr - 1, 0); ny <= std::min(pr + 1, rows - 1); ++ny) {
      uint64_t near = (open[ny] << 1 >> pc) & 7;
      if (near == 0) continue;
      open[ny] &= ~(near << pc >> 1);
      const uint32_t left = (uint32_t(ny) << 16) + uint32_t(pc - 1);  // wraps at pc = 0: k >= 1 there
      for (; near != 0; near &= near - 1) queue[tail++] = left + uint32_t(__builtin_ctzll(near));
    }
  }
  // Labels, the pixel list (in the order reached) and the bounding box.
  Region region;
  region.label = next_label_++;
  region.begin = static_cast<int>(pixels_.size());
  const int width = size_.width;
  int min_c = c, max_c = c, min_r = r, max_r = r;
  pixels_.resize(pixels_.size() + tail);
  int32_t* const pixels = pixels_.data() + region.begin;
  for (size_t k = 0; k < tail; ++k) {
    const int qc = int(queue[k] & 0xFFFF), qr = int(queue[k] >> 16);
    const int32_t index = (window.y + qr) * width + window.x + qc;
    labels_[size_t(index)] = region.label;
    pixels[k] = index;
    min_c = std::min(min_c, qc);
    max_c = std::max(max_c, qc);
    min_r = std::min(min_r, qr);
    max_r = std::max(max_r, qr);
  }
  region.box = cv::Rect(window.x + min_c, window.y + min_r, max_c - min_c + 1, max_r - min_r + 1);
  region.end = static_cast<int>(pixels_.size());
  regions->push_back(region);
}
#endif

template <typename T>
void RegionGrower::grow_from(const cv::Mat& work, cv::Rect window, int seed, int keep_min,
                             std::vector<Region>* regions) {
  const int width = size_.width;
  const int x0 = window.x, x1 = window.x + window.width;
  const int y0 = window.y, y1 = window.y + window.height;
  Region region;
  region.label = next_label_++;
  region.begin = static_cast<int>(pixels_.size());
  const int sy = seed / width, sx = seed - sy * width;
  const int32_t label_value = region.label;
  labels_[size_t(seed)] = label_value;
  pixels_.push_back(seed);
  // The queue is indexed, and grows (rarely: to the largest region yet) only when full.
  if (queue_.empty()) queue_.resize(256);
  size_t tail = 0;
  queue_[tail++] = {sx, sy};
  // Inlined, with nothing but locals and the two lists: as a called lambda updating
  // the bounding box through its captures it cost more than the neighbour tests.
  const auto take = [&](int nx, int ny, int32_t* label) __attribute__((always_inline)) {
    *label = label_value;
    pixels_.push_back(ny * width + nx);
    if (tail == queue_.size()) queue_.resize(2 * tail);
    queue_[tail++] = {nx, ny};
  };
  // The 8 neighbours row by row, as offsets in the labels and in the image.
  static constexpr int kDx[8] = {-1, 0, 1, -1, 1, -1, 0, 1}, kDy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};
  const std::ptrdiff_t step = std::ptrdiff_t(work.step1());
  std::ptrdiff_t label_offset[8], value_offset[8];
  for (int k = 0; k < 8; ++k) {
    label_offset[k] = kDy[k] * std::ptrdiff_t(width) + kDx[k];
    value_offset[k] = kDy[k] * step + kDx[k];
  }
  // Breadth-first, neighbours row by row (recovery's rim follows this order);
  // the queue keeps coordinates so that no pixel needs a division.
  for (size_t head = 0; head < tail; ++head) {
    const auto [px, py] = queue_[head];
    if (px > x0 && px < x1 - 1 && py > y0 && py < y1 - 1) {
      // Inside the window (nearly every pixel): no bounds to clamp, and the loop
      // unrolled (no counter or table lookup per neighbour).
      const T* value = work.ptr<T>(py) + px;
      int32_t* label = labels_.data() + size_t(py) * width + px;
#pragma GCC unroll 8
      for (int k = 0; k < 8; ++k)
        if (label[label_offset[k]] == 0 && value[value_offset[k]] >= keep_min)
          take(px + kDx[k], py + kDy[k], label + label_offset[k]);
      continue;
    }
    for (int ny = std::max(py - 1, y0); ny <= std::min(py + 1, y1 - 1); ++ny) {
      const T* nrow = work.ptr<T>(ny);
      int32_t* nlabels = labels_.data() + size_t(ny) * width;
      for (int nx = std::max(px - 1, x0); nx <= std::min(px + 1, x1 - 1); ++nx)
        if (nlabels[nx] == 0 && nrow[nx] >= keep_min) take(nx, ny, nlabels + nx);
    }
  }
  // The bounding box, from the queue (which holds every pixel taken).
  int min_x = sx, max_x = sx, min_y = sy, max_y = sy;
  for (size_t k = 1; k < tail; ++k) {
    const auto [qx, qy] = queue_[k];
    min_x = std::min(min_x, qx);
    max_x = std::max(max_x, qx);
    min_y = std::min(min_y, qy);
    max_y = std::max(max_y, qy);
  }
  region.box = cv::Rect(min_x, min_y, max_x - min_x + 1, max_y - min_y + 1);
  region.end = static_cast<int>(pixels_.size());
  regions->push_back(region);
}

void RegionGrower::measure(const cv::Mat& work, cv::Rect window, const Levels& levels, Region* region) {
  if (work.depth() == CV_8U) {
    measure_typed<uint8_t>(work, window, levels, region);
  } else {
    measure_typed<uint16_t>(work, window, levels, region);
  }
}

template <typename T>
void RegionGrower::measure_typed(const cv::Mat& work, cv::Rect window, const Levels& levels, Region* region) {
  const int width = size_.width;
  const double bg = levels.background;
  const int32_t label = region->label;
  RegionSums s;
  if (region->end <= region->begin || region->box.empty()) {
    region->sums = s;
    region->blob = s.blob();
    return;
  }
  const int min_x = region->box.x, max_x = region->box.x + region->box.width - 1;
  const int min_y = region->box.y, max_y = region->box.y + region->box.height - 1;
  s.bbox = cv::Rect(min_x, min_y, max_x - min_x + 1, max_y - min_y + 1);
  s.clipped = min_x == window.x || min_y == window.y || max_x == window.x + window.width - 1 ||
              max_y == window.y + window.height - 1;
  const int rows = s.bbox.height;
  row_min_.assign(size_t(rows), std::numeric_limits<int>::max());
  row_max_.assign(size_t(rows), -1);
  s.peak = -std::numeric_limits<double>::infinity();

  // One sweep of the box and a pixel around it: the region's pixels, and the
  // ring of unlabelled pixels touching it (they hold the spot's faint tail).
  const int wx0 = window.x, wx1 = window.x + window.width - 1, wy0 = window.y, wy1 = window.y + window.height - 1;
  const int x0 = std::max(min_x - 1, wx0), x1 = std::min(max_x + 1, wx1);
  // Moments of pixel centres are sums of integers: exact in int64, summed per row.
  int64_t sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  int top = -1;  // the region's brightest value and how many pixels hold it
  int top_n = 0;
  const int ya = std::max(min_y - 1, wy0), yb = std::min(max_y + 1, wy1);
  // Box and ring no wider than 64 (any region of an ROI window): each row's members
  // as bits, so that only members and pixels next to one are visited, in the same
  // order and with the same sums as the plain sweep below.
  const int cols = x1 - x0 + 1;
  const bool as_bits = cols <= 64;
  if (as_bits) {
    member_rows_.assign(size_t(yb - ya + 3), 0);  // rows ya - 1 .. yb + 1, the outer two empty
    for (int y = std::max(ya, min_y); y <= std::min(yb, max_y); ++y) {
      const int32_t* here = labels_.data() + size_t(y) * width + x0;
      member_rows_[size_t(y - ya + 1)] = label_bits(here, cols, label);
    }
  }
  const auto spread = [](uint64_t m) { return m | m << 1 | m >> 1; };
  // The weights' sums in locals (registers), stored once: in `s` every pixel's
  // addition waited on the previous one's store.
  double w = 0, wx = 0, wy = 0;
  const uint64_t in_cols = !as_bits ? 0 : cols == 64 ? ~uint64_t(0) : (uint64_t(1) << cols) - 1;
  for (int y = ya; y <= yb; ++y) {
    const T* row = work.ptr<T>(y);
    const int32_t* here = labels_.data() + size_t(y) * width;
    const int32_t* up = y > wy0 ? here - width : nullptr;
    const int32_t* down = y < wy1 ? here + width : nullptr;
    int64_t row_n = 0, row_sx = 0, row_sxx = 0;
    int row_min = std::numeric_limits<int>::max(), row_max = -1;
    // One pixel: a member's moments and weight, or a touching unlabelled pixel's weight.
    const auto visit = [&](int x, bool member, bool touches) __attribute__((always_inline)) {
      const int value = row[x];
      const double d = double(value) - bg;
      if (member) {
        ++row_n;
        row_sx += x;
        row_sxx += int64_t(x) * x;
        w += d;
        wx += d * x;
        wy += d * y;
        // The peak and clipping follow from the top value (v - bg rises with v).
        top_n = value > top ? 1 : top_n + (value == top);
        top = std::max(top, value);
        row_min = std::min(row_min, x);
        row_max = x;
        return;
      }
      if (here[x] != 0 || d <= 0 || !touches) return;
      w += d;
      wx += d * x;
      wy += d * y;
    };
    if (as_bits) {
      const uint64_t* m = member_rows_.data() + (y - ya + 1);
      const uint64_t members = m[0], near = (spread(m[-1]) | spread(m[0]) | spread(m[1])) & in_cols;
      for (uint64_t b = members | near; b != 0; b &= b - 1) {
        const int i = __builtin_ctzll(b);
        visit(x0 + i, members >> i & 1, true);
      }
    } else {
      for (int x = x0; x <= x1; ++x) {
        const int32_t l = here[x];
        if (l == label) {
          visit(x, true, true);
          continue;
        }
        if (l != 0 || row[x] <= bg) continue;
        const int a = std::max(x - 1, wx0), b = std::min(x + 1, wx1);
        bool touches = false;
        for (int nx = a; nx <= b && !touches; ++nx)
          touches = here[nx] == label || (up && up[nx] == label) || (down && down[nx] == label);
        visit(x, false, touches);
      }
    }
    if (row_n == 0) continue;
    s.area += int(row_n);
    sx += row_sx;
    sxx += row_sxx;
    sy += row_n * y;
    sxy += row_sx * y;
    syy += row_n * y * y;
    if (y >= min_y && y <= max_y) {
      row_min_[size_t(y - min_y)] = row_min;
      row_max_[size_t(y - min_y)] = row_max;
    }
  }
  s.w = w, s.wx = wx, s.wy = wy;
  if (top >= 0) {
    s.peak = double(top) - bg;
    s.saturated = top >= levels.saturation || (top_n >= Levels::kFlatTopPixels && top >= levels.flat_top_floor);
  }
  s.sx = double(sx);
  s.sy = double(sy);
  s.sxx = double(sxx);
  s.sxy = double(sxy);
  s.syy = double(syy);

  // The hull of the pixel squares needs, at each horizontal pixel edge, only
  // the leftmost and rightmost corner there. Stored as (y, x): sorted already,
  // and a mirror image has the same area.
  hull_points_.resize(2 * size_t(rows + 1));
  for (int r = 0; r <= rows; ++r) {
    const size_t above = size_t(std::max(r - 1, 0)), below = size_t(std::min(r, rows - 1));
    // Doubled: the edge y - 0.5, the corners left - 0.5 and right + 0.5.
    const int64_t y = 2 * int64_t(min_y + r) - 1;
    hull_points_[2 * size_t(r)] = {y, 2 * int64_t(std::min(row_min_[above], row_min_[below])) - 1};
    hull_points_[2 * size_t(r) + 1] = {y, 2 * int64_t(std::max(row_max_[above], row_max_[below])) + 1};
  }
  s.hull_area = convex_hull_area(hull_points_, &hull_);
  region->sums = s;
  region->blob = s.blob();
}

}  // namespace tetrapulse::blob_internal
