#include "tetrapulse/hardware/nelder_mead.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace tetrapulse::hardware {

namespace {

class Simplex {
 public:
  Simplex(const Objective& f, int* evaluations) : f_(f), evaluations_(evaluations) {}

  // One descent from a fresh simplex around x0; returns when converged or out of budget.
  void run(const Eigen::VectorXd& x0, double f0, const NelderMeadOptions& o, int budget) {
    const int k = static_cast<int>(x0.size());
    const double alpha = 1.0, beta = 1.0 + 2.0 / k, gamma = 0.75 - 0.5 / k, delta = 1.0 - 1.0 / k;
    x_.resize(k, k + 1);
    v_.resize(k + 1);
    order_.resize(k + 1);
    x_.col(0) = x0;
    v_[0] = f0;
    for (int i = 0; i < k; ++i) {
      x_.col(i + 1) = x0;
      x_(i, i + 1) += o.step;
      v_[i + 1] = eval(x_.col(i + 1));
    }
    Eigen::VectorXd c(k), xr(k), xe(k), xc(k);
    while (*evaluations_ < budget) {
      std::iota(order_.begin(), order_.end(), 0);
      std::sort(order_.begin(), order_.end(), [&](int a, int b) { return v_[a] > v_[b] || (v_[a] == v_[b] && a < b); });
      const int best = order_[0], worst = order_[k], second = order_[k - 1];
      if (converged(o, best)) return;
      c.setZero();
      for (int i = 0; i < k; ++i) c += x_.col(order_[i]);
      c /= k;
      xr = c + alpha * (c - x_.col(worst));
      const double fr = eval(xr);
      if (fr > v_[best]) {
        xe = c + beta * (xr - c);
        const double fe = eval(xe);
        if (fe > fr) {
          replace(worst, xe, fe);
        } else {
          replace(worst, xr, fr);
        }
      } else if (fr > v_[second]) {
        replace(worst, xr, fr);
      } else {
        const bool outside = fr > v_[worst];
        xc = outside ? Eigen::VectorXd(c + gamma * (xr - c)) : Eigen::VectorXd(c + gamma * (x_.col(worst) - c));
        const double fc = eval(xc);
        if (outside ? fc >= fr : fc > v_[worst]) {
          replace(worst, xc, fc);
        } else {
          for (int i = 1; i <= k; ++i) {
            const int j = order_[i];
            x_.col(j) = x_.col(best) + delta * (x_.col(j) - x_.col(best));
            v_[j] = eval(x_.col(j));
          }
        }
      }
    }
  }

  Eigen::VectorXd best_x() const { return x_.col(best_index()); }
  double best_f() const { return v_[best_index()]; }

 private:
  double eval(const Eigen::VectorXd& x) {
    ++*evaluations_;
    const double v = f_(x);
    return std::isnan(v) ? -INFINITY : v;  // a NaN never wins
  }

  void replace(int i, const Eigen::VectorXd& x, double f) {
    x_.col(i) = x;
    v_[i] = f;
  }

  bool converged(const NelderMeadOptions& o, int best) const {
    for (int i = 0; i < x_.cols(); ++i) {
      if ((x_.col(i) - x_.col(best)).cwiseAbs().maxCoeff() > o.x_tolerance) return false;
      if (v_[best] - v_[i] > o.f_tolerance) return false;
    }
    return true;
  }

  int best_index() const {
    int b = 0;
    for (int i = 1; i < static_cast<int>(v_.size()); ++i) {
      if (v_[i] > v_[b]) b = i;
    }
    return b;
  }

  const Objective& f_;
  int* evaluations_;
  Eigen::MatrixXd x_;  // vertices as columns
  std::vector<double> v_;
  std::vector<int> order_;
};

}  // namespace

NelderMeadResult nelder_mead_maximize(const Objective& f, const Eigen::VectorXd& x0, const NelderMeadOptions& o) {
  NelderMeadResult result;
  result.x = x0;
  result.f = f(x0);
  result.evaluations = 1;
  if (std::isnan(result.f)) result.f = -INFINITY;
  if (x0.size() == 0) return result;
  Simplex simplex(f, &result.evaluations);
  for (int round = 0; round <= o.restarts && result.evaluations < o.max_evaluations; ++round) {
    simplex.run(result.x, result.f, o, o.max_evaluations);
    const double gain = simplex.best_f() - result.f;
    if (gain > 0) {
      result.x = simplex.best_x();
      result.f = simplex.best_f();
    }
    if (round > 0 && gain <= o.f_tolerance) break;
  }
  return result;
}

}  // namespace tetrapulse::hardware
