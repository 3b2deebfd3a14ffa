#pragma once
// One code word of length L (1..64) and the measures the codebook constrains
// (SPEC.md §8). A word is a uint64_t whose bit i (value 1 << i) is character i
// of the code string, i.e. the bit a board plays at bit index i; bits at and
// above L are zero. Codes repeat, so runs and shifts are cyclic.
#include <cstdint>

namespace tetrapulse::protocol {

// The L low bits set. L in 1..64.
constexpr uint64_t word_mask(uint32_t length) {
  return length >= 64 ? ~uint64_t{0} : (uint64_t{1} << length) - 1;
}

// The word read from bit s on: character i of the result is character
// (i + s) mod L of w. s in 0..L-1. A board started s bits late plays this.
constexpr uint64_t rotate_word(uint64_t w, uint32_t s, uint32_t length) {
  return s == 0 ? w : ((w >> s) | (w << (length - s))) & word_mask(length);
}

// Number of 1 bits (portable bit counting, inline: it is the search's inner loop).
constexpr uint32_t word_weight(uint64_t w) {
  w = w - ((w >> 1) & 0x5555555555555555ull);
  w = (w & 0x3333333333333333ull) + ((w >> 2) & 0x3333333333333333ull);
  w = (w + (w >> 4)) & 0x0F0F0F0F0F0F0F0Full;
  return static_cast<uint32_t>((w * 0x0101010101010101ull) >> 56);
}

// Hamming distance: number of bit indices where a and b differ.
constexpr uint32_t hamming_distance(uint64_t a, uint64_t b) { return word_weight(a ^ b); }

// Longest cyclic run of `bit` (0 or 1) in w: the largest k such that k
// consecutive indices (mod L) all hold `bit`. L when every bit is `bit`.
uint32_t max_cyclic_run(uint64_t w, uint32_t length, bool bit);

// A distance and the shift at which it is reached.
struct ShiftDistance {
  uint32_t distance = 0;
  uint32_t shift = 0;
};

// Cyclic distance  min_{s=0..L-1} H(a, rotate_word(b, s)),  with the smallest s
// reaching it: how close b, played with an unknown phase, comes to a.
ShiftDistance cyclic_distance(uint64_t a, uint64_t b, uint32_t length);

// True when some shift s brings rotate_word(b, s) within distance < d of a
// (cyclic_distance(a, b).distance < d, stopping at the first such shift).
bool cyclically_closer_than(uint64_t a, uint64_t b, uint32_t length, uint32_t d);

// The least period of w: the smallest p >= 1 with rotate_word(w, p, L) == w (p divides L).
uint32_t least_period(uint64_t w, uint32_t length);

// Shift distance  min_{s=1..L-1} H(w, rotate_word(w, s)):  how well w's own
// phase can be told apart. 0 for a periodic word; {L, 0} when L = 1 (no
// non-trivial shift exists).
ShiftDistance self_shift_distance(uint64_t w, uint32_t length);

// A key whose integer order is the lexicographic order of the code strings
// (character 0 first): the L bits of w reversed.
uint64_t string_order_key(uint64_t w, uint32_t length);

// The rotation of w whose string is lexicographically least (the necklace
// representative; for an aperiodic word, its Lyndon word).
uint64_t least_rotation(uint64_t w, uint32_t length);

}  // namespace tetrapulse::protocol
