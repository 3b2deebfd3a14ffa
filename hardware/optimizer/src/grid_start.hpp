#pragma once
// Starting shapes for one restart, drawn from the paper's "predefined set of discrete
// lengths": L = max(grid levels, 6 n) evenly spaced lengths in [D1, D2], of which 6 n
// distinct ones are dealt at random to the n targets (distinct, so no two distances
// start equal and s_min > 0). Each target's six lengths go to its edges in the order
// that makes the tallest tetrahedron. While some target cannot reach face height H
// with its lengths, a random swap of one of its lengths with another target's (or an
// undealt one) is kept when it lowers the total shortfall: Nelder-Mead moves lengths
// only a little at a time, and cannot pass one through another without s_min -> 0.
#include <vector>

#include "tetrapulse/hardware/eq1_score.hpp"
#include "tetrapulse/hardware/seeded_stream.hpp"
#include "tetrapulse/hardware/tetrahedron.hpp"

namespace tetrapulse::hardware {

struct GridStartSettings {
  int targets = 1;
  Eq1Limits limits;
  int levels = 16;
  int swaps = 0;  // swap attempts per target
};

std::vector<Edges> draw_grid_start(const GridStartSettings& settings, SeededStream* random);

// The arrangement of six lengths over the edges with the largest min_face_height
// (30 arrangements are distinct up to relabelling the markers; all are tried).
Edges tallest_arrangement(const Edges& lengths);

}  // namespace tetrapulse::hardware
