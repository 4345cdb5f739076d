// The oracle's scalar types and their few functions (oracle/oracle.h): one overload set for
// __float128 and the 50-digit Big, 3-vectors, and dual numbers for the potentials' derivatives.
// Header-only templates, shared by the equations, the scene reading and the integration.
#pragma once

#include <array>
#include <cmath>
#include <type_traits>

#include "oracle/oracle.h"

namespace spinfold::oracle {

__extension__ typedef __float128 Quad;

// ---- the scalar types' functions: one overload set for __float128 and Big -----------------------
namespace num {
// __float128 arithmetic is the compiler's (GCC and clang; soft float in libgcc). Its few functions are
// written here so that no libquadmath (whose header clang does not see) is needed: the square root by
// Newton from the double one (each step doubles the digits), the rest through the 50-digit type (they
// are used only to build the start).
inline double to_double(Quad x) {
  return static_cast<double>(x);
}
// One type to the other as the sum of three doubles, which carry quad's 113 bits.
template <class To, class From>
To through_three_doubles(const From& x) {
  const double hi = static_cast<double>(x);
  const From r1 = x - From(hi);
  const double mid = static_cast<double>(r1);
  const double lo = static_cast<double>(r1 - From(mid));
  return To(hi) + To(mid) + To(lo);
}
inline Quad from_big(const Big& x) {
  return through_three_doubles<Quad>(x);
}
inline Big to_big(Quad x) {
  return through_three_doubles<Big>(x);
}
inline Quad abs(Quad x) {
  return x < 0 ? -x : x;
}
inline bool finite(Quad x) {
  return x == x && x - x == 0;  // false for NaN and ±inf
}
inline Quad sqrt(Quad x) {
  if (!(x > 0)) return x == 0 ? Quad(0) : from_big(boost::multiprecision::sqrt(to_big(x)));  // NaN
  Quad y = std::sqrt(static_cast<double>(x));
  for (int i = 0; i < 2; ++i) y = (y + x / y) / 2;
  return y;
}
// The functions both types share, for Big returning Big (not Boost's expression templates) and for
// Quad through Big: exact to quad's precision, slow, used to build the start and once per field
// evaluation (the bump's exp).
#define SPINFOLD_ORACLE_THROUGH_BIG(f)                    \
  inline Big f(const Big& x) {                            \
    return boost::multiprecision::f(x);                   \
  }                                                       \
  inline Quad f(Quad x) {                                 \
    return from_big(boost::multiprecision::f(to_big(x))); \
  }                                                       \
  static_assert(true)
SPINFOLD_ORACLE_THROUGH_BIG(sin);
SPINFOLD_ORACLE_THROUGH_BIG(cos);
SPINFOLD_ORACLE_THROUGH_BIG(sinh);
SPINFOLD_ORACLE_THROUGH_BIG(cosh);
SPINFOLD_ORACLE_THROUGH_BIG(exp);
SPINFOLD_ORACLE_THROUGH_BIG(asin);
SPINFOLD_ORACLE_THROUGH_BIG(asinh);
#undef SPINFOLD_ORACLE_THROUGH_BIG
inline Big sqrt(const Big& x) {
  return boost::multiprecision::sqrt(x);
}
inline Big atan2(const Big& y, const Big& x) {
  return boost::multiprecision::atan2(y, x);
}
inline Big abs(const Big& x) {
  return boost::multiprecision::abs(x);
}
inline bool finite(const Big& x) {
  return boost::multiprecision::isfinite(x);
}
inline double to_double(const Big& x) {
  return static_cast<double>(x);
}
template <class T>
T convert(const Big& x) {
  if constexpr (std::is_same_v<T, Quad>)
    return from_big(x);
  else
    return x;
}
template <class T>
Big big(const T& x) {
  if constexpr (std::is_same_v<T, Quad>)
    return to_big(x);
  else
    return x;
}
}  // namespace num

template <class T>
using V3 = std::array<T, 3>;

template <class T>
V3<T> operator+(const V3<T>& a, const V3<T>& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
template <class T>
V3<T> operator-(const V3<T>& a, const V3<T>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <class T>
V3<T> operator*(const T& s, const V3<T>& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
template <class T>
V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// ---- dual numbers: the potentials' derivatives without writing them out ----------------------
template <class T>
struct Dual {
  T v, d;
};
template <class T>
Dual<T> operator+(Dual<T> a, Dual<T> b) {
  return {a.v + b.v, a.d + b.d};
}
template <class T>
Dual<T> operator-(Dual<T> a, Dual<T> b) {
  return {a.v - b.v, a.d - b.d};
}
template <class T>
Dual<T> operator*(Dual<T> a, Dual<T> b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d};
}
template <class T>
Dual<T> operator/(Dual<T> a, Dual<T> b) {
  return {a.v / b.v, (a.d * b.v - a.v * b.d) / (b.v * b.v)};
}
template <class T>
Dual<T> dsqrt(Dual<T> a) {
  const T s = num::sqrt(a.v);
  return {s, a.d / (2 * s)};
}
template <class T>
Dual<T> cst(const T& c) {
  return {c, T(0)};
}

}  // namespace spinfold::oracle
