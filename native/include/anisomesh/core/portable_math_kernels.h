// Kernels of the portable elementary functions (portable_math.h): double-double
// arithmetic (Dekker / Veltkamp, FMA-free), exact helpers on the binary representation,
// argument reductions and series. Internal: call the functions of portable_math.h.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace anisomesh::pm {

namespace detail {

struct DD {
  double hi, lo;
};

// Exact helpers on the binary representation (same results as std::frexp /
// std::ldexp, which are exact, but inlined: the libm calls cost more than the
// arithmetic they wrap).
inline std::uint64_t toBits(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
inline double fromBits(std::uint64_t u) {
  double x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}
// 2^k for k in [-1022, 1023].
inline double pow2i(int k) { return fromBits(static_cast<std::uint64_t>(k + 1023) << 52); }
// x * 2^k with a single rounding (like std::ldexp).
inline double scale(double x, int k) {
  if (k > 1023) {
    x *= 0x1p1023;
    k -= 1023;
    if (k > 1023) {
      x *= 0x1p1023;
      k -= 1023;
      if (k > 1023) k = 1023;
    }
  } else if (k < -1022) {
    // Scale in steps of 2^-969 = 2^-1022 * 2^53 so that only the last step can round.
    x *= 0x1p-969;
    k += 969;
    if (k < -1022) {
      x *= 0x1p-969;
      k += 969;
      if (k < -1022) k = -1022;
    }
  }
  return x * pow2i(k);
}
// Like std::frexp: x = m * 2^e, |m| in [0.5, 1); 0, inf, NaN returned as is (e = 0).
inline double frexpBits(double x, int* e) {
  std::uint64_t u = toBits(x);
  int ex = static_cast<int>((u >> 52) & 0x7ff);
  if (ex == 0x7ff || x == 0.0) {
    *e = 0;
    return x;
  }
  int adj = 0;
  if (ex == 0) {  // subnormal
    u = toBits(x * 0x1p54);
    ex = static_cast<int>((u >> 52) & 0x7ff);
    adj = 54;
  }
  *e = ex - 1022 - adj;
  return fromBits((u & ~(0x7ffULL << 52)) | (0x3feULL << 52));
}

// s + e == a + b exactly.
inline DD twoSum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  const double e = (a - (s - bb)) + (b - bb);
  return {s, e};
}
// |a| >= |b| (or a == 0).
inline DD fastTwoSum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}
// Veltkamp split; |a| < 2^995.
inline void split(double a, double& hi, double& lo) {
  const double c = 134217729.0 * a;  // 2^27 + 1
  hi = c - (c - a);
  lo = a - hi;
}
// p + e == a * b exactly (Dekker, no FMA).  |a|,|b| < 2^995, no underflow.
inline DD twoProd(double a, double b) {
  const double p = a * b;
  double ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  const double e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
  return {p, e};
}
inline DD ddMul(DD a, DD b) {
  DD p = twoProd(a.hi, b.hi);
  p.lo += a.hi * b.lo + a.lo * b.hi;
  return fastTwoSum(p.hi, p.lo);
}

// More accurate product (cross terms also exact) for integer powers.
inline DD ddMulAcc(DD a, DD b) {
  const DD p = twoProd(a.hi, b.hi);
  const DD c1 = twoProd(a.hi, b.lo);
  const DD c2 = twoProd(a.lo, b.hi);
  DD m = twoSum(c1.hi, c2.hi);
  m.lo += c1.lo + c2.lo + a.lo * b.lo;
  DD s = twoSum(p.hi, m.hi);
  const DD t = twoSum(p.lo, m.lo);
  s.lo += t.hi;
  s = fastTwoSum(s.hi, s.lo);
  s.lo += t.lo;
  return fastTwoSum(s.hi, s.lo);
}

inline DD ddDiv(DD a, DD b) {
  const double q = a.hi / b.hi;
  const DD p = twoProd(q, b.hi);
  const double r = (((a.hi - p.hi) - p.lo) + a.lo - q * b.lo) / b.hi;
  return fastTwoSum(q, r);
}

// Round-to-nearest (ties away) of a double known to be < 2^52 in magnitude.
inline double roundHalf(double x) { return std::floor(x + 0.5); }

inline constexpr double kLn2Hi = 0x1.62e42fef00000p-1;  // 33 bits
inline constexpr double kLn2Lo = 0x1.473de6af278edp-34;
inline constexpr double kInvLn2 = 0x1.71547652b82fep+0;
inline constexpr double kInvLn2Lo = 0x1.777d0ffda0d24p-56;
inline constexpr double kPiHi = 0x1.921fb54442d18p+1;
inline constexpr double kPiLo = 0x1.1a62633145c07p-53;
inline constexpr double kPio2Hi = 0x1.921fb54442d18p+0;
inline constexpr double kPio2Lo = 0x1.1a62633145c07p-54;
inline constexpr double kPio2_1 = 0x1.921fb54400000p+0;   // 33 bits
inline constexpr double kPio2_2 = 0x1.0b4611a600000p-34;  // 33 bits
inline constexpr double kPio2_3 = 0x1.3198a2e037073p-69;
inline constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;

// exp(r) - 1 - r for |r| <= ~0.35: r^2 * (1/2! + r/3! + ... + r^11/13!).
inline double expTail(double r) {
  constexpr double c2 = 1.0 / 2, c3 = 1.0 / 6, c4 = 1.0 / 24, c5 = 1.0 / 120, c6 = 1.0 / 720, c7 = 1.0 / 5040,
                   c8 = 1.0 / 40320, c9 = 1.0 / 362880, c10 = 1.0 / 3628800, c11 = 1.0 / 39916800,
                   c12 = 1.0 / 479001600, c13 = 1.0 / 6227020800.0;
  const double r2 = r * r;
  // Two interleaved Horner chains (even / odd coefficients) for latency.
  const double even = c2 + r2 * (c4 + r2 * (c6 + r2 * (c8 + r2 * (c10 + r2 * c12))));
  const double odd = c3 + r2 * (c5 + r2 * (c7 + r2 * (c9 + r2 * (c11 + r2 * c13))));
  return r2 * (even + r * odd);
}

// Reduction x = k*ln2 + (rh + rl), |rh| <= ~ln2/2.  |xh| < 2^11*ln2 expected.
inline double expReduce(double xh, double xl, double& rh, double& rl) {
  const double k = roundHalf(xh * kInvLn2);
  const double hi = xh - k * kLn2Hi;  // exact
  const double lo = k * kLn2Lo - xl;
  rh = hi - lo;
  rl = (hi - rh) - lo;
  return k;
}

// exp(xh + xl), |xl| << |xh| ulp-ish.
inline double expKernel(double xh, double xl) {
  if (!(xh < 709.8)) return xh != xh ? xh : HUGE_VAL;
  if (xh < -745.2) return 0.0;
  double rh, rl;
  const double k = expReduce(xh, xl, rh, rl);
  const double p = 1.0 + (rh + (expTail(rh) + rl * (1.0 + rh)));
  return scale(p, static_cast<int>(k));
}

// expm1(x) as double-double for |x| < ~50 (internal helper for sinh/cosh/tanh).
inline DD expm1DD(double x) {
  if (std::fabs(x) <= 0.34657359027997264) return fastTwoSum(x, expTail(x));
  double rh, rl;
  const double k = expReduce(x, 0.0, rh, rl);
  const DD e = fastTwoSum(rh, expTail(rh) + rl * (1.0 + rh));
  DD one = twoSum(1.0, e.hi);
  one.lo += e.lo;
  const int ki = static_cast<int>(k);
  DD s = twoSum(scale(one.hi, ki), -1.0);
  s.lo += scale(one.lo, ki);
  return fastTwoSum(s.hi, s.lo);
}

// sin(r + rl) / cos(r + rl) as double-double, |r| <= ~pi/4.
// sum_{n>=1} 2 z^n / (2n+1) for z = s^2 <= 0.0295 (log(1+f) = 2s + s * series).
inline double logSeries(double z) {
  return z * (2.0 / 3 +
              z * (2.0 / 5 +
                   z * (2.0 / 7 +
                        z * (2.0 / 9 +
                             z * (2.0 / 11 +
                                  z * (2.0 / 13 +
                                       z * (2.0 / 15 +
                                            z * (2.0 / 17 + z * (2.0 / 19 + z * (2.0 / 21 + z * (2.0 / 23)))))))))));
}

// log(x) as double-double for finite x > 0 (internal; ~2^-62 relative).
inline DD logDD(double x) {
  int e;
  double m = frexpBits(x, &e);  // m in [0.5,1)
  if (m < 0.70710678118654752) {
    m *= 2.0;
    --e;
  }
  const double f = m - 1.0;  // exact
  // s = f / (2 + f) as double-double.
  const DD d = twoSum(2.0, f);
  const double sh = f / d.hi;
  const DD q = twoProd(sh, d.hi);
  const double sl = ((f - q.hi) - q.lo - sh * d.lo) / d.hi;
  // log(1+f) = 2s + 2s^3/3 + s^5 * P(s^2)
  DD z = twoProd(sh, sh);
  z.lo += 2.0 * sh * sl;
  DD c = twoProd(z.hi, sh);  // s^3
  c.lo += z.lo * sh + z.hi * sl;
  constexpr double t3h = 0x1.5555555555555p-1, t3l = 0x1.5555555555555p-55;
  DD t = twoProd(c.hi, t3h);  // 2 s^3 / 3
  t.lo += c.hi * t3l + c.lo * t3h;
  const double zz = z.hi;
  const double p =
      2.0 / 5 +
      zz *
          (2.0 / 7 +
           zz * (2.0 / 9 + zz * (2.0 / 11 +
                                 zz * (2.0 / 13 +
                                       zz * (2.0 / 15 +
                                             zz * (2.0 / 17 + zz * (2.0 / 19 + zz * (2.0 / 21 + zz * (2.0 / 23)))))))));
  const double tail = c.hi * zz * p;
  DD r = twoSum(2.0 * sh, t.hi);
  r.lo += 2.0 * sl + (t.lo + tail);
  const double ed = static_cast<double>(e);
  DD out = twoSum(ed * kLn2Hi, r.hi);  // ed*kLn2Hi exact
  out.lo += r.lo + ed * kLn2Lo;
  return fastTwoSum(out.hi, out.lo);
}

// atan(u + ul) for u in [0, 1]: returned as hi + lo (hi is a table value).
inline DD atanSmall(double u, double ul) {
  static constexpr double kAtanHi[17] = {
      0x0.0p+0,
      0x1.ff55bb72cfdeap-5,
      0x1.fd5ba9aac2f6ep-4,
      0x1.7b97b4bce5b02p-3,
      0x1.f5b75f92c80ddp-3,
      0x1.362773707ebccp-2,
      0x1.6f61941e4def1p-2,
      0x1.a64eec3cc23fdp-2,
      0x1.dac670561bb4fp-2,
      0x1.0657e94db30d0p-1,
      0x1.1e00babdefeb4p-1,
      0x1.345f01cce37bbp-1,
      0x1.4978fa3269ee1p-1,
      0x1.5d58987169b18p-1,
      0x1.700a7c5784634p-1,
      0x1.819d0b7158a4dp-1,
      0x1.921fb54442d18p-1,
  };
  static constexpr double kAtanLo[17] = {
      0x0.0p+0,
      -0x1.c934d86d23f1dp-60,
      -0x1.cd37686760c17p-59,
      0x1.347b0b4f881cap-58,
      0x1.8ab6e3cf7afbdp-57,
      -0x1.963a544b672d8p-57,
      -0x1.c63aae6f6e918p-56,
      -0x1.24dec1b50b7ffp-56,
      0x1.a2b7f222f65e2p-56,
      -0x1.d5b495f6349e6p-56,
      -0x1.928df287a668fp-58,
      0x1.1021137c71102p-55,
      0x1.2419a87f2a458p-56,
      0x1.0028e4bc5e7cap-57,
      -0x1.8c34d25aadef6p-56,
      -0x1.bf76229d3b917p-56,
      0x1.1a62633145c07p-55,
  };
  // u is in [0, 1], so truncating u * 16 + 0.5 rounds to nearest (no libm call).
  const int j = static_cast<int>(u * 16.0 + 0.5);  // NOLINT(bugprone-incorrect-roundings)
  double t, tl;
  if (j == 0) {
    t = u;
    tl = ul;
  } else {
    const double c = j * 0.0625;
    const double num = u - c;  // exact (Sterbenz)
    const DD uc = twoProd(u, c);
    const DD den = twoSum(1.0, uc.hi);
    const double denl = den.lo + uc.lo;
    t = num / den.hi;
    const DD tq = twoProd(t, den.hi);
    tl = ((num - tq.hi) - tq.lo - t * denl) / den.hi + ul * (1.0 + c * c) / (den.hi * den.hi);
  }
  const double z = t * t;
  const double p =
      -1.0 / 3 + z * (1.0 / 5 + z * (-1.0 / 7 + z * (1.0 / 9 + z * (-1.0 / 11 + z * (1.0 / 13 + z * (-1.0 / 15))))));
  return {kAtanHi[j], t + (t * z * p + (tl + kAtanLo[j]))};
}

// atan(u + ul) for u >= 0 (u may be +inf) as hi + lo.
inline DD atanDD(double u, double ul) {
  if (u <= 1.0) return atanSmall(u, ul);
  if (u > 0x1p60) return {kPio2Hi, kPio2Lo - 1.0 / u};
  const double q = 1.0 / u;
  const DD qu = twoProd(q, u);
  const double e = (1.0 - qu.hi) - qu.lo;
  const double ql = q * (e - q * ul);
  const DD a = atanSmall(q, ql);
  const DD s = twoSum(kPio2Hi, -a.hi);
  return {s.hi, (s.lo + kPio2Lo) - a.lo};
}

// Quotient a / b (a, b > 0 finite) as double-double, safe for any range.
inline DD divDD(double a, double b) {
  if (a > 0x1p-400 && a < 0x1p400 && b > 0x1p-400 && b < 0x1p400) {
    const double q = a / b;
    const DD p = twoProd(q, b);
    return {q, ((a - p.hi) - p.lo) / b};
  }
  int ea, eb;
  const double ma = frexpBits(a, &ea);
  const double mb = frexpBits(b, &eb);
  const double q = ma / mb;
  const DD p = twoProd(q, mb);
  const double ql = ((ma - p.hi) - p.lo) / mb;
  const int s = ea - eb;
  return {scale(q, s), scale(ql, s)};
}

// sqrt(1 - x*x) for |x| < 1 as double-double.
inline DD sqrt1mx2(double x) {
  const DD x2 = twoProd(x, x);
  DD d = twoSum(1.0, -x2.hi);
  d.lo -= x2.lo;
  d = fastTwoSum(d.hi, d.lo);
  const double s = std::sqrt(d.hi);
  const DD ss = twoProd(s, s);
  const double sl = ((d.hi - ss.hi) - ss.lo + d.lo) / (2.0 * s);
  return {s, sl};
}

// Trig reduction: |x| = k*pi/2 + (rh + rl), returns k mod 4.  ax >= 0 finite.
inline int trigReduce(double ax, double& rh, double& rl) {
  if (ax <= 0.78539816339744828) {
    rh = ax;
    rl = 0.0;
    return 0;
  }
  if (ax > 0x1p30) {
    // Out of the accurate range: first reduce exactly (fmod is exact) modulo
    // the 33-bit constant 4*kPio2_1.  Deterministic and bounded, not accurate.
    ax = std::fmod(ax, 4.0 * kPio2_1);
  }
  const double k = roundHalf(ax * kTwoOverPi);
  const double t = ax - k * kPio2_1;       // exact for k < 2^20
  const DD y = twoSum(t, -(k * kPio2_2));  // k*kPio2_2 exact for k < 2^20
  const DD r = fastTwoSum(y.hi, y.lo - k * kPio2_3);
  rh = r.hi;
  rl = r.lo;
  const double k4 = k - 4.0 * std::floor(k * 0.25);
  return static_cast<int>(k4);
}

// sin(r + rl), |r| <= ~pi/4.
inline DD sinKernelDD(double r, double rl) {
  const double z = r * r;
  const double p =
      -1.0 / 6 +
      z * (1.0 / 120 +
           z * (-1.0 / 5040 + z * (1.0 / 362880 + z * (-1.0 / 39916800 + z * (1.0 / 6227020800.0 +
                                                                              z * (-1.0 / 1307674368000.0 +
                                                                                   z * (1.0 / 355687428096000.0)))))));
  return fastTwoSum(r, r * z * p + rl * (1.0 - 0.5 * z));
}

// cos(r + rl), |r| <= ~pi/4.
inline DD cosKernelDD(double r, double rl) {
  const double z = r * r;
  const double p =
      1.0 / 24 +
      z * (-1.0 / 720 +
           z * (1.0 / 40320 +
                z * (-1.0 / 3628800 +
                     z * (1.0 / 479001600 + z * (-1.0 / 87178291200.0 +
                                                 z * (1.0 / 20922789888000.0 + z * (-1.0 / 6402373705728000.0)))))));
  const double hz = 0.5 * z;
  const double w = 1.0 - hz;
  return fastTwoSum(w, ((1.0 - w) - hz) + (z * z * p - r * rl));
}

inline double sinKernel(double r, double rl) {
  const DD d = sinKernelDD(r, rl);
  return d.hi + d.lo;
}
inline double cosKernel(double r, double rl) {
  const DD d = cosKernelDD(r, rl);
  return d.hi + d.lo;
}

inline bool isOddInteger(double y) {
  if (!(std::fabs(y) < 0x1p53)) return false;
  const double h = 0.5 * std::fabs(y);
  return std::floor(y) == y && std::floor(h) != h;
}

// |x|^n for integer n in [1, 64], x finite nonzero, via double-double squaring.
inline double powInt(double x, int n, bool negative) {
  int e;
  const double m = frexpBits(std::fabs(x), &e);  // [0.5, 1)
  DD acc{1.0, 0.0};
  DD b{m, 0.0};
  int k = n;
  while (true) {
    if (k & 1) acc = ddMulAcc(acc, b);
    k >>= 1;
    if (!k) break;
    b = ddMulAcc(b, b);
  }
  // acc in [2^-64, 1].
  long long sc = static_cast<long long>(e) * n;
  if (negative) {
    const double q = 1.0 / acc.hi;
    const DD qa = twoProd(q, acc.hi);
    const double err = (1.0 - qa.hi) - qa.lo - q * acc.lo;
    acc = fastTwoSum(q, q * err);
    sc = -sc;
  }
  const double v = acc.hi + acc.lo;
  if (sc > 4000) sc = 4000;
  if (sc < -4000) sc = -4000;
  return scale(v, static_cast<int>(sc));
}

// log and log2 of x <= 0, NaN or +inf (then true, with the result in *out).
inline bool logSpecialCase(double x, double* out) {
  if (!(x > 0.0)) {
    *out = x == 0.0 ? -HUGE_VAL : std::nan("");  // x < 0 or NaN
    return true;
  }
  if (std::isinf(x)) {
    *out = x;
    return true;
  }
  return false;
}
// x = 2^e (1 + f) with 1 + f in [sqrt(1/2), sqrt(2)); returns f.
inline double logReduce(double x, int* e) {
  double m = frexpBits(x, e);
  if (m < 0.70710678118654752) {
    m *= 2.0;
    --*e;
  }
  return m - 1.0;
}
}  // namespace detail

}  // namespace anisomesh::pm
