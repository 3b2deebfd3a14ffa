#include "tetrapulse/localizer/p3p.hpp"

#include "tetrapulse/localizer/p3p_kneip.hpp"
#include "tetrapulse/localizer/p3p_lambda_twist.hpp"

namespace tetrapulse {

const char* p3p_solver_name(P3PSolver solver) {
  return solver == P3PSolver::kKneip ? "kneip" : "lambda_twist";
}

int solve_p3p(P3PSolver solver, const Bearing3& x, const Point3x3& X, PoseCandidates* out) {
  return solver == P3PSolver::kKneip ? p3p_kneip(x, X, out) : p3p_lambda_twist(x, X, out);
}

}  // namespace tetrapulse
