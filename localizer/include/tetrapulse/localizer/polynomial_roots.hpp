#pragma once
// Real roots of cubic and quartic polynomials in closed form (Cardano; Ferrari),
// polished by Newton steps on the original polynomial where the closed form loses
// digits. The P3P solvers use them: Lambda Twist's cubic in gamma, Kneip's quartic in
// cos(theta).
#include <array>

namespace tetrapulse {

// Real roots of c3 x^3 + c2 x^2 + c1 x + c0 = 0 with c3 != 0, ascending.
// Returns how many were written (1 or 3; a double root is written twice).
int real_cubic_roots(double c3, double c2, double c1, double c0, std::array<double, 3>* roots);

// The largest real root of c3 x^3 + c2 x^2 + c1 x + c0 = 0 with c3 != 0: the same
// as the last of real_cubic_roots, for a fraction of the work (no acos, cos or cbrt).
double largest_real_cubic_root(double c3, double c2, double c1, double c0);

// Real roots of c4 x^4 + c3 x^3 + c2 x^2 + c1 x + c0 = 0 with c4 != 0 (Ferrari's
// method). A pair of complex roots whose imaginary part is lost in rounding is
// written as a double real root, so that a tangency (a P3P pose on the boundary
// between two and four solutions) is not dropped. Returns how many were written (0..4).
int real_quartic_roots(double c4, double c3, double c2, double c1, double c0, std::array<double, 4>* roots);

}  // namespace tetrapulse
