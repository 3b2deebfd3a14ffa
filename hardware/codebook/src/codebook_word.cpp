#include "tetrapulse/codebook/codebook_word.hpp"

namespace tetrapulse::protocol {

uint32_t max_cyclic_run(uint64_t w, uint32_t length, bool bit) {
  const uint64_t mask = word_mask(length);
  uint64_t x = bit ? (w & mask) : (~w & mask);
  if (x == mask) return length;
  // After k steps, bit i survives iff indices i..i+k (mod L) all hold `bit`.
  uint32_t run = 0;
  while (x != 0) {
    x &= rotate_word(x, 1, length);
    ++run;
  }
  return run;
}

ShiftDistance cyclic_distance(uint64_t a, uint64_t b, uint32_t length) {
  ShiftDistance best{hamming_distance(a, b), 0};
  for (uint32_t s = 1; s < length && best.distance > 0; ++s) {
    const uint32_t h = hamming_distance(a, rotate_word(b, s, length));
    if (h < best.distance) best = ShiftDistance{h, s};
  }
  return best;
}

bool cyclically_closer_than(uint64_t a, uint64_t b, uint32_t length, uint32_t d) {
  for (uint32_t s = 0; s < length; ++s) {
    if (hamming_distance(a, rotate_word(b, s, length)) < d) return true;
  }
  return false;
}

uint32_t least_period(uint64_t w, uint32_t length) {
  for (uint32_t p = 1; p < length; ++p) {
    if (length % p == 0 && rotate_word(w, p, length) == w) return p;
  }
  return length;
}

ShiftDistance self_shift_distance(uint64_t w, uint32_t length) {
  if (length <= 1) return ShiftDistance{length, 0};
  ShiftDistance best{length + 1, 0};
  for (uint32_t s = 1; s < length; ++s) {
    const uint32_t h = hamming_distance(w, rotate_word(w, s, length));
    if (h < best.distance) best = ShiftDistance{h, s};
  }
  return best;
}

uint64_t string_order_key(uint64_t w, uint32_t length) {
  // Reverse all 64 bits, then drop the 64 - L that were above the word.
  uint64_t r = w;
  r = ((r >> 1) & 0x5555555555555555ull) | ((r & 0x5555555555555555ull) << 1);
  r = ((r >> 2) & 0x3333333333333333ull) | ((r & 0x3333333333333333ull) << 2);
  r = ((r >> 4) & 0x0F0F0F0F0F0F0F0Full) | ((r & 0x0F0F0F0F0F0F0F0Full) << 4);
  r = ((r >> 8) & 0x00FF00FF00FF00FFull) | ((r & 0x00FF00FF00FF00FFull) << 8);
  r = ((r >> 16) & 0x0000FFFF0000FFFFull) | ((r & 0x0000FFFF0000FFFFull) << 16);
  r = (r >> 32) | (r << 32);
  return r >> (64 - length);
}

uint64_t least_rotation(uint64_t w, uint32_t length) {
  uint64_t best = w & word_mask(length);
  uint64_t best_key = string_order_key(best, length);
  for (uint32_t s = 1; s < length; ++s) {
    const uint64_t r = rotate_word(w, s, length);
    const uint64_t key = string_order_key(r, length);
    if (key < best_key) {
      best = r;
      best_key = key;
    }
  }
  return best;
}

}  // namespace tetrapulse::protocol
