#pragma once
// Nelder-Mead downhill simplex: x* = argmax f(x), x in R^k, from x0.
// Nelder & Mead, The Computer Journal 7(4), 1965, with the dimension-adaptive
// coefficients of Gao & Han, Comput. Optim. Appl. 51, 2012 (reflection 1, expansion
// 1 + 2/k, contraction 3/4 - 1/(2k), shrink 1 - 1/k). Direct search, so f may be
// non-smooth (Eq. 1's min) and discontinuous (its penalty). Deterministic.
#include <functional>

#include <Eigen/Core>

namespace tetrapulse::hardware {

struct NelderMeadOptions {
  double step = 0.01;          // initial simplex: x0 and x0 + step along each axis (units of x)
  double x_tolerance = 1e-9;   // converged when every vertex is within this of the best, per axis,
  double f_tolerance = 1e-12;  // and every value within this of the best
  int max_evaluations = 5000;  // per call, restarts included
  int restarts = 4;            // fresh simplices around the best point after convergence, while they gain
};

struct NelderMeadResult {
  Eigen::VectorXd x;
  double f = 0;
  int evaluations = 0;
};

using Objective = std::function<double(const Eigen::VectorXd&)>;

NelderMeadResult nelder_mead_maximize(const Objective& f, const Eigen::VectorXd& x0, const NelderMeadOptions& options);

}  // namespace tetrapulse::hardware
