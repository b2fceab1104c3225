#pragma once
// Dual2: second-order (truncated) dual numbers D₂ = ℝ[ε]/(ε³),
//   a = a0 + a1·ε + a2·ε²,   ε³ = 0.
// Arithmetic keeps the ε and ε² coefficients exactly, so a computation done
// in Dual2 with the errors entered as ε-coefficients yields the first-order
// (ε) and second-order (ε²) parts of its result separately. Usable as an
// Eigen scalar (NumTraits and ScalarBinaryOpTraits with double below).
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <ostream>

namespace abbe::model {

struct Dual2 {
  double v = 0.0;   // value
  double e1 = 0.0;  // ε coefficient
  double e2 = 0.0;  // ε² coefficient

  constexpr Dual2() = default;
  constexpr Dual2(double value) : v(value) {}  // NOLINT: implicit, like a real number
  constexpr Dual2(double value, double eps1, double eps2) : v(value), e1(eps1), e2(eps2) {}

  Dual2& operator+=(const Dual2& b) {
    v += b.v;
    e1 += b.e1;
    e2 += b.e2;
    return *this;
  }
  Dual2& operator-=(const Dual2& b) {
    v -= b.v;
    e1 -= b.e1;
    e2 -= b.e2;
    return *this;
  }
  Dual2& operator*=(const Dual2& b) { return *this = *this * b; }
  Dual2& operator/=(const Dual2& b) { return *this = *this / b; }

  friend constexpr Dual2 operator+(const Dual2& a) { return a; }
  friend constexpr Dual2 operator-(const Dual2& a) { return {-a.v, -a.e1, -a.e2}; }
  friend constexpr Dual2 operator+(const Dual2& a, const Dual2& b) {
    return {a.v + b.v, a.e1 + b.e1, a.e2 + b.e2};
  }
  friend constexpr Dual2 operator-(const Dual2& a, const Dual2& b) {
    return {a.v - b.v, a.e1 - b.e1, a.e2 - b.e2};
  }
  // (a0 + a1ε + a2ε²)(b0 + b1ε + b2ε²), ε³ terms dropped.
  friend constexpr Dual2 operator*(const Dual2& a, const Dual2& b) {
    return {a.v * b.v, a.v * b.e1 + a.e1 * b.v, a.v * b.e2 + a.e1 * b.e1 + a.e2 * b.v};
  }
  // c = a/b solves c·b = a order by order.
  friend constexpr Dual2 operator/(const Dual2& a, const Dual2& b) {
    double c0 = a.v / b.v;
    double c1 = (a.e1 - c0 * b.e1) / b.v;
    double c2 = (a.e2 - c0 * b.e2 - c1 * b.e1) / b.v;
    return {c0, c1, c2};
  }
  // Mixed with double (no promotion cost).
  friend constexpr Dual2 operator+(const Dual2& a, double b) { return {a.v + b, a.e1, a.e2}; }
  friend constexpr Dual2 operator+(double a, const Dual2& b) { return {a + b.v, b.e1, b.e2}; }
  friend constexpr Dual2 operator-(const Dual2& a, double b) { return {a.v - b, a.e1, a.e2}; }
  friend constexpr Dual2 operator-(double a, const Dual2& b) { return {a - b.v, -b.e1, -b.e2}; }
  friend constexpr Dual2 operator*(const Dual2& a, double b) {
    return {a.v * b, a.e1 * b, a.e2 * b};
  }
  friend constexpr Dual2 operator*(double a, const Dual2& b) {
    return {a * b.v, a * b.e1, a * b.e2};
  }
  friend constexpr Dual2 operator/(const Dual2& a, double b) {
    return {a.v / b, a.e1 / b, a.e2 / b};
  }
  friend constexpr Dual2 operator/(double a, const Dual2& b) { return Dual2(a) / b; }

  // Comparisons look at the value only (as for ceres::Jet).
  friend constexpr bool operator==(const Dual2& a, const Dual2& b) { return a.v == b.v; }
  friend constexpr bool operator!=(const Dual2& a, const Dual2& b) { return a.v != b.v; }
  friend constexpr bool operator<(const Dual2& a, const Dual2& b) { return a.v < b.v; }
  friend constexpr bool operator>(const Dual2& a, const Dual2& b) { return a.v > b.v; }
  friend constexpr bool operator<=(const Dual2& a, const Dual2& b) { return a.v <= b.v; }
  friend constexpr bool operator>=(const Dual2& a, const Dual2& b) { return a.v >= b.v; }
};

// f(a0 + h) with h = a1ε + a2ε²: f0 + f1·h + ½f2·h², h² = a1²ε².
inline Dual2 chain_rule(const Dual2& a, double f0, double f1, double f2) {
  return {f0, f1 * a.e1, f1 * a.e2 + 0.5 * f2 * a.e1 * a.e1};
}
inline Dual2 sqrt(const Dual2& a) {
  double s = std::sqrt(a.v);
  return chain_rule(a, s, 0.5 / s, -0.25 / (s * a.v));
}
inline Dual2 sin(const Dual2& a) {
  double s = std::sin(a.v), c = std::cos(a.v);
  return chain_rule(a, s, c, -s);
}
inline Dual2 cos(const Dual2& a) {
  double s = std::sin(a.v), c = std::cos(a.v);
  return chain_rule(a, c, -s, -c);
}
inline Dual2 abs(const Dual2& a) { return a.v < 0.0 ? -a : a; }
inline bool isfinite(const Dual2& a) {
  return std::isfinite(a.v) && std::isfinite(a.e1) && std::isfinite(a.e2);
}
inline std::ostream& operator<<(std::ostream& os, const Dual2& a) {
  return os << '(' << a.v << " + " << a.e1 << "ε + " << a.e2 << "ε²)";
}

}  // namespace abbe::model

namespace Eigen {

template <>
struct NumTraits<abbe::model::Dual2> : GenericNumTraits<abbe::model::Dual2> {
  using Real = abbe::model::Dual2;
  using NonInteger = abbe::model::Dual2;
  using Nested = abbe::model::Dual2;
  using Literal = abbe::model::Dual2;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 3,
    AddCost = 3,
    MulCost = 9,
  };
  static inline Real epsilon() { return Real(std::numeric_limits<double>::epsilon()); }
  static inline Real dummy_precision() { return Real(1e-12); }
  static inline Real highest() { return Real(std::numeric_limits<double>::max()); }
  static inline Real lowest() { return Real(std::numeric_limits<double>::lowest()); }
  static inline int digits10() { return std::numeric_limits<double>::digits10; }
};

template <typename BinaryOp>
struct ScalarBinaryOpTraits<abbe::model::Dual2, double, BinaryOp> {
  using ReturnType = abbe::model::Dual2;
};
template <typename BinaryOp>
struct ScalarBinaryOpTraits<double, abbe::model::Dual2, BinaryOp> {
  using ReturnType = abbe::model::Dual2;
};

}  // namespace Eigen
