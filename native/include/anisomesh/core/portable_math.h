// Portable, bit-reproducible elementary functions.
//
// glibc and musl (used by the Emscripten/wasm build) differ in the last ulp of
// exp, log, sin, ... on some inputs, and those differences cascade into
// different meshes.  The functions of anisomesh::pm are built ONLY from
// operations that IEEE 754 requires to be correctly rounded (+ - * / sqrt) and
// exact helpers (floor, ldexp, frexp, fabs, copysign, classification), so the
// same input gives the same bits on every conforming platform, provided the
// compiler does not contract a*b+c into an FMA (x86-64 g++ without -march and
// wasm have no FMA; do not build this with -march=native/-mfma on one side
// only, nor with -ffast-math).
//
// Methods (own implementation): Cody-Waite argument reduction with 2/3-part
// constants, Taylor series evaluated with Horner, double-double (Dekker /
// Veltkamp, FMA-free) corrections where the last bit matters.
//
// Accuracy (measured against glibc, see tests/native/portable_math_test.cpp):
// within 2 ulp everywhere tested, most functions within 1 ulp.
// sin/cos/tan: accurate argument reduction for |x| <= 2^20*pi/2 (~1.647e6);
// beyond that the reduction loses precision gradually (results stay
// deterministic, and finite for finite x).
#pragma once

#include <cmath>

#include "anisomesh/core/portable_math_kernels.h"

namespace anisomesh::pm {

inline double exp(double x) { return detail::expKernel(x, 0.0); }

inline double log(double x) {
  double special;
  if (detail::logSpecialCase(x, &special)) return special;
  int e;
  const double f = detail::logReduce(x, &e);
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double r = detail::logSeries(z);
  const double hfsq = 0.5 * f * f;
  const double ed = static_cast<double>(e);
  return ed * detail::kLn2Hi + (f - (hfsq - (s * (hfsq + r) + ed * detail::kLn2Lo)));
}

inline double log2(double x) {
  double special;
  if (detail::logSpecialCase(x, &special)) return special;
  int e;
  // log(1+f) = hi + lo with hi truncated to 21 bits so that hi * kIvHi (33 bits) is exact.
  const double f = detail::logReduce(x, &e);
  const double s = f / (2.0 + f);
  const double z = s * s;
  const double r = detail::logSeries(z);
  const double hfsq = 0.5 * f * f;
  const double hi = detail::fromBits(detail::toBits(f - hfsq) & 0xffffffff00000000ULL);
  const double lo = ((f - hi) - hfsq) + s * (hfsq + r);
  constexpr double kIvHi = 0x1.7154765200000p+0, kIvLo = 0x1.705fc2eefa200p-33;
  const double vhi = hi * kIvHi;
  const double vlo = (lo + hi) * kIvLo + lo * kIvHi;
  const double ed = static_cast<double>(e);
  const double w = ed + vhi;  // |ed| >= 1 > |vhi| unless ed == 0 (then exact)
  return w + (vlo + ((ed - w) + vhi));
}

inline double sin(double x) {
  if (!std::isfinite(x)) return x - x;  // NaN
  double rh, rl;
  const int q = detail::trigReduce(std::fabs(x), rh, rl);
  double v;
  switch (q) {
    case 0:
      v = detail::sinKernel(rh, rl);
      break;
    case 1:
      v = detail::cosKernel(rh, rl);
      break;
    case 2:
      v = -detail::sinKernel(rh, rl);
      break;
    default:
      v = -detail::cosKernel(rh, rl);
      break;
  }
  return x < 0 ? -v : (x == 0 ? x : v);
}

inline double cos(double x) {
  if (!std::isfinite(x)) return x - x;
  double rh, rl;
  const int q = detail::trigReduce(std::fabs(x), rh, rl);
  switch (q) {
    case 0:
      return detail::cosKernel(rh, rl);
    case 1:
      return -detail::sinKernel(rh, rl);
    case 2:
      return -detail::cosKernel(rh, rl);
    default:
      return detail::sinKernel(rh, rl);
  }
}

// sin(x) and cos(x) with one argument reduction: the same bits as pm::sin(x), pm::cos(x).
inline void sincos(double x, double& s, double& c) {
  if (!std::isfinite(x)) {
    s = c = x - x;
    return;
  }
  double rh, rl;
  const int q = detail::trigReduce(std::fabs(x), rh, rl);
  const double sk = detail::sinKernel(rh, rl), ck = detail::cosKernel(rh, rl);
  double v;
  switch (q) {
    case 0:
      v = sk;
      c = ck;
      break;
    case 1:
      v = ck;
      c = -sk;
      break;
    case 2:
      v = -sk;
      c = -ck;
      break;
    default:
      v = -ck;
      c = sk;
      break;
  }
  s = x < 0 ? -v : (x == 0 ? x : v);
}

inline double tan(double x) {
  if (!std::isfinite(x)) return x - x;
  if (x == 0.0) return x;
  double rh, rl;
  const int q = detail::trigReduce(std::fabs(x), rh, rl);
  const detail::DD s = detail::sinKernelDD(rh, rl);
  const detail::DD c = detail::cosKernelDD(rh, rl);
  const detail::DD t = (q & 1) ? detail::ddDiv(c, s) : detail::ddDiv(s, c);
  const double v = (q & 1) ? -(t.hi + t.lo) : t.hi + t.lo;
  return x < 0 ? -v : v;
}

inline double atan(double x) {
  if (x != x) return x;
  const double a = std::fabs(x);
  const detail::DD r = detail::atanDD(a, 0.0);
  return std::copysign(r.hi + r.lo, x);
}

inline double atan2(double y, double x) {
  if (x != x || y != y) return x + y;
  const double ay = std::fabs(y), ax = std::fabs(x);
  const bool xneg = std::signbit(x);
  if (ay == 0.0) return xneg ? std::copysign(detail::kPiHi, y) : y;
  if (ax == 0.0) return std::copysign(detail::kPio2Hi, y);
  if (std::isinf(ay)) {
    if (std::isinf(ax)) return std::copysign(xneg ? 0x1.2d97c7f3321d2p+1 : 0x1.921fb54442d18p-1, y);
    return std::copysign(detail::kPio2Hi, y);
  }
  if (std::isinf(ax)) return xneg ? std::copysign(detail::kPiHi, y) : std::copysign(0.0, y);
  const detail::DD u = detail::divDD(ay, ax);
  const detail::DD a = detail::atanDD(u.hi, u.lo);
  double v;
  if (!xneg) {
    v = a.hi + a.lo;
  } else {
    const detail::DD s = detail::twoSum(detail::kPiHi, -a.hi);
    v = s.hi + ((s.lo + detail::kPiLo) - a.lo);
  }
  return std::copysign(v, y);
}

inline double asin(double x) {
  if (x != x) return x;
  const double a = std::fabs(x);
  if (a > 1.0) return std::nan("");
  if (a == 1.0) return std::copysign(detail::kPio2Hi, x);
  if (a == 0.0) return x;
  const detail::DD s = detail::sqrt1mx2(a);
  const detail::DD q = detail::divDD(a, s.hi);
  const double ql = q.lo - q.hi * s.lo / s.hi;
  const detail::DD r = detail::atanDD(q.hi, ql);
  return std::copysign(r.hi + r.lo, x);
}

inline double acos(double x) {
  if (x != x) return x;
  const double a = std::fabs(x);
  if (a > 1.0) return std::nan("");
  if (x == 1.0) return 0.0;
  if (x == -1.0) return detail::kPiHi;
  if (a == 0.0) return detail::kPio2Hi;
  const detail::DD s = detail::sqrt1mx2(a);
  const detail::DD q = detail::divDD(s.hi, a);
  const double ql = q.lo + s.lo / a;
  const detail::DD r = detail::atanDD(q.hi, ql);
  if (x > 0) return r.hi + r.lo;
  const detail::DD d = detail::twoSum(detail::kPiHi, -r.hi);
  return d.hi + ((d.lo + detail::kPiLo) - r.lo);
}

inline double sinh(double x) {
  if (!std::isfinite(x)) return x;
  const double a = std::fabs(x);
  double v;
  if (a < 22.0) {
    // sinh = (t + t / (t + 1)) / 2 with t = expm1(a), in double-double.
    const detail::DD t = detail::expm1DD(a);
    detail::DD t1 = detail::twoSum(t.hi, 1.0);
    t1.lo += t.lo;
    const detail::DD u = detail::ddDiv(t, t1);
    detail::DD w = detail::twoSum(t.hi, u.hi);
    w.lo += t.lo + u.lo;
    v = 0.5 * (w.hi + w.lo);
  } else {
    const detail::DD h = detail::twoSum(a, -detail::kLn2Hi);
    v = detail::expKernel(h.hi, h.lo - detail::kLn2Lo);
  }
  return std::copysign(v, x);
}

inline double cosh(double x) {
  if (x != x) return x;
  const double a = std::fabs(x);
  if (std::isinf(a)) return a;
  if (a < 22.0) {
    // cosh = (E + 1/E) / 2 with E = 1 + expm1(a), in double-double.
    const detail::DD t = detail::expm1DD(a);
    detail::DD e = detail::twoSum(1.0, t.hi);
    e.lo += t.lo;
    const detail::DD inv = detail::ddDiv({1.0, 0.0}, e);
    detail::DD w = detail::twoSum(e.hi, inv.hi);
    w.lo += e.lo + inv.lo;
    return 0.5 * (w.hi + w.lo);
  }
  const detail::DD h = detail::twoSum(a, -detail::kLn2Hi);
  return detail::expKernel(h.hi, h.lo - detail::kLn2Lo);
}

inline double tanh(double x) {
  if (x != x) return x;
  const double a = std::fabs(x);
  double v;
  if (a >= 22.0) {
    v = 1.0;
  } else {
    // tanh = t / (t + 2) with t = expm1(2a), in double-double.
    const detail::DD t = detail::expm1DD(2.0 * a);
    detail::DD d = detail::twoSum(t.hi, 2.0);
    d.lo += t.lo;
    const detail::DD q = detail::ddDiv(t, d);
    v = q.hi + q.lo;
  }
  return std::copysign(v, x);
}

inline double hypot(double x, double y) {
  double a = std::fabs(x), b = std::fabs(y);
  if (std::isinf(a) || std::isinf(b)) return HUGE_VAL;
  if (a != a || b != b) return a + b;
  if (a < b) {
    const double t = a;
    a = b;
    b = t;
  }
  if (b == 0.0) return a;
  if (a > 0x1p60 * b) return a + b;
  int e = 0;
  if (a > 0x1p450 || b < 0x1p-450) {
    // Scale so that a is in [0.5, 1): products stay far from overflow/underflow
    // (b >= a * 2^-60).  Exact.
    detail::frexpBits(a, &e);
    a = detail::scale(a, -e);
    b = detail::scale(b, -e);
  }
  const detail::DD a2 = detail::twoProd(a, a);
  const detail::DD b2 = detail::twoProd(b, b);
  detail::DD s = detail::twoSum(a2.hi, b2.hi);
  s.lo += a2.lo + b2.lo;
  s = detail::fastTwoSum(s.hi, s.lo);
  const double r = std::sqrt(s.hi);
  const detail::DD rr = detail::twoProd(r, r);
  const double rl = ((s.hi - rr.hi) - rr.lo + s.lo) / (2.0 * r);
  return e == 0 ? r + rl : detail::scale(r + rl, e);
}

inline double pow(double x, double y) {
  using namespace detail;
  if (y == 0.0 || x == 1.0) return 1.0;
  if (x != x || y != y) return x + y;
  const double ax = std::fabs(x);
  const bool yint = std::floor(y) == y;  // false for inf
  const bool yodd = isOddInteger(y);
  if (std::isinf(y)) {
    if (ax == 1.0) return 1.0;
    return (ax < 1.0) == (y < 0) ? HUGE_VAL : 0.0;
  }
  if (x == 0.0) {
    if (y < 0) return yodd ? std::copysign(HUGE_VAL, x) : HUGE_VAL;
    return yodd ? x : 0.0;
  }
  if (std::isinf(x)) {
    const double mag = y < 0 ? 0.0 : HUGE_VAL;
    return (x < 0 && yodd) ? -mag : mag;
  }
  if (x < 0 && !yint) return std::nan("");
  const bool neg = x < 0 && yodd;
  double v;
  if (ax == 1.0) {
    v = 1.0;
  } else if (y == 1.0) {
    v = ax;
  } else if (y == 2.0) {
    v = ax * ax;
  } else if (y == -1.0) {
    v = 1.0 / ax;
  } else if (y == 0.5) {
    v = std::sqrt(ax);
  } else if (yint && std::fabs(y) <= 64.0) {
    v = powInt(ax, static_cast<int>(std::fabs(y)), y < 0);
  } else {
    const DD l = logDD(ax);
    // y * l as double-double, guarding the Dekker split range.
    if (std::fabs(y) > 0x1p900) {
      const double t = y * l.hi;
      v = t > 0 ? HUGE_VAL : 0.0;
    } else {
      DD p = twoProd(y, l.hi);
      if (!(std::fabs(p.hi) < 1000.0)) {
        v = p.hi > 0 ? HUGE_VAL : 0.0;
      } else {
        p.lo += y * l.lo;
        const DD pn = fastTwoSum(p.hi, p.lo);
        v = expKernel(pn.hi, pn.lo);
      }
    }
  }
  return neg ? -v : v;
}

}  // namespace anisomesh::pm
