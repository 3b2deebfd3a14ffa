#pragma once
// A 3-vector of three named doubles for the P3P solvers' inner code. Eigen's Vector3d
// works as a 2-packet plus a scalar, and its temporaries pass through the stack, where
// a store of one width reloaded at another stalls store forwarding; three scalars stay
// in registers (measured: 15 % of Lambda Twist's time).
#include <Eigen/Core>

namespace tetrapulse {

struct V3 {
  double x, y, z;
};

inline V3 v3(const Eigen::Vector3d& v) { return {v(0), v(1), v(2)}; }
inline V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline V3 select(bool pick, const V3& a, const V3& b) {
  return {pick ? a.x : b.x, pick ? a.y : b.y, pick ? a.z : b.z};
}

}  // namespace tetrapulse
