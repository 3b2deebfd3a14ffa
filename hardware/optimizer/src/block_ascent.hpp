#pragma once
// Maximises Eq. 1 over a system of targets one target at a time: each target's
// parameters go through Nelder-Mead with the others held fixed, cycling until a whole
// sweep gains nothing. The objective is always the system's Eq. 1, so the targets are
// optimised jointly; the simplex only ever sees one target's few parameters, where
// Nelder-Mead works well (it stalls in the 6 n dimensions of the whole system).
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/hardware/eq1_score.hpp"
#include "tetrapulse/hardware/nelder_mead.hpp"

namespace tetrapulse::hardware {

// Target `index` as Eq. 1 sees it, at parameters `x`.
using TargetModel = std::function<TargetShape(int index, const Eigen::VectorXd& x)>;
// Where target `index`'s simplex starts in each sweep, given its objective (others
// fixed); kept only when better than its current parameters. Empty: from the current
// parameters. A cheap global scan here lets a target jump past local optima.
using SweepStart = std::function<Eigen::VectorXd(int index, const Eigen::VectorXd& current, const Objective& f)>;

struct BlockAscentOptions {
  NelderMeadOptions simplex;
  int max_sweeps = 40;
  double tolerance = 1e-10;  // a sweep that gains no more than this (m) ends the ascent
};

// Updates *params (one vector per target) in place; returns the system's Eq. 1.
Eq1Score block_ascent(const TargetModel& model, const Eq1Limits& limits, const BlockAscentOptions& options,
                      std::vector<Eigen::VectorXd>* params, const SweepStart& sweep_start = {});

}  // namespace tetrapulse::hardware
