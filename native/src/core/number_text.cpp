// Shortest round-trip number text for messages (see number_text.h).
#include "anisomesh/core/number_text.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace anisomesh {

std::string numberText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

namespace {

// 10^p for p in [0, 22] as hi * 2^64 + lo (10^20 and above have a high half).
struct Pow10Table {
  std::uint64_t lo[23], hi[23];
};
constexpr Pow10Table makePow10Table() {
  Pow10Table t{};
  t.lo[0] = 1;
  for (int p = 1; p < 23; ++p) {  // times 10 = times 8 + times 2, with the carries out of lo
    const std::uint64_t lo = t.lo[p - 1], times8 = lo << 3, sum = times8 + (lo << 1);
    t.lo[p] = sum;
    t.hi[p] = t.hi[p - 1] * 10 + (lo >> 61) + (lo >> 63) + (sum < times8 ? 1 : 0);
  }
  return t;
}
constexpr Pow10Table kPow10 = makePow10Table();
static_assert(kPow10.lo[19] == 10000000000000000000ull && kPow10.hi[19] == 0, "10^19");
static_assert(kPow10.hi[22] == 0x21e && kPow10.lo[22] == 0x19e0c9bab2400000ull, "10^22");

// a * b as hi:lo from four 32-bit partial products. The arithmetic below stays in 64-bit
// words: in WebAssembly, __int128 products and shifts are calls into compiler-rt.
inline void multiply64(std::uint64_t a, std::uint64_t b, std::uint64_t* hi, std::uint64_t* lo) {
  const std::uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
  const std::uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
  const std::uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
  *lo = (mid << 32) | (p00 & 0xffffffffu);
  *hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
}

// round(m * 2^e * 10^p) to nearest, ties to even, when exact in 128 bits and the result
// fits in 64; false otherwise.
bool scaledRound(std::uint64_t m, int e, int p, std::uint64_t& out) {
  if (p < 0 || p > 22) return false;
  std::uint64_t xh, xl;  // x = m * 10^p < 2^53 * 10^22 < 2^127
  multiply64(m, kPow10.lo[p], &xh, &xl);
  xh += m * kPow10.hi[p];
  if (e >= 0) {
    if (e > 10 || xh != 0 || (e > 0 && (xl >> (64 - e)) != 0)) return false;
    out = xl << e;
    return true;
  }
  const int s = -e;  // q = x >> s, rounded on the s bits dropped (rest) against half = 2^(s - 1)
  if (s >= 127) return false;
  std::uint64_t q;
  bool above, tie;
  if (s >= 64) {  // (q < 2^63: no carry out of the increment below)
    const int t = s - 64;
    q = xh >> t;
    if (t == 0) {
      above = xl > (std::uint64_t{1} << 63), tie = xl == (std::uint64_t{1} << 63);
    } else {
      const std::uint64_t restHi = xh & ((std::uint64_t{1} << t) - 1), halfHi = std::uint64_t{1} << (t - 1);
      above = restHi > halfHi || (restHi == halfHi && xl != 0), tie = restHi == halfHi && xl == 0;
    }
  } else {
    if ((xh >> s) != 0) return false;  // q >= 2^64
    q = (xh << (64 - s)) | (xl >> s);
    const std::uint64_t rest = xl & ((std::uint64_t{1} << s) - 1), half = std::uint64_t{1} << (s - 1);
    above = rest > half, tie = rest == half;
  }
  if (above || (tie && (q & 1))) {
    if (++q == 0) return false;  // 2^64
  }
  out = q;
  return true;
}

// "00" .. "99".
constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// The 8 digits of x < 10^8 at d[0..7], by multiplications (exact quotients for these
// ranges: x / 10^4 for x < 10^8, y / 100 for y < 10^4) and a table of digit pairs.
inline void eightDigits(std::uint32_t x, char* d) {
  const std::uint32_t hi = std::uint32_t((std::uint64_t(x) * 109951163u) >> 40), lo = x - hi * 10000;
  const std::uint32_t a = (hi * 5243) >> 19, b = hi - a * 100, c = (lo * 5243) >> 19, f = lo - c * 100;
  std::memcpy(d, kDigitPairs + 2 * a, 2);
  std::memcpy(d + 2, kDigitPairs + 2 * b, 2);
  std::memcpy(d + 4, kDigitPairs + 2 * c, 2);
  std::memcpy(d + 6, kDigitPairs + 2 * f, 2);
}

}  // namespace

int formatG17(double v, char* buf) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  const bool negative = (bits >> 63) != 0;
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  const std::uint64_t fraction = bits & ((std::uint64_t{1} << 52) - 1);
  const double a = std::fabs(v);
  // Zero, subnormals, inf, NaN and magnitudes outside the exact range: the C library.
  if (biased == 0 || biased == 0x7ff || !(a >= 1e-5 && a < 1e17)) return std::snprintf(buf, 32, "%.17g", v);
  const std::uint64_t m = fraction | (std::uint64_t{1} << 52);
  const int e = biased - 1075;  // v = m * 2^e
  // 17 significant digits: N = round(a * 10^p) in [10^16, 10^17), decimal exponent 16 - p.
  constexpr std::uint64_t lo = 10000000000000000ull, hi = 100000000000000000ull;
  // floor(log10(a)) is k or k + 1 (a in [2^b, 2^(b+1)), b = biased - 1023, |b| < 60 here;
  // 78913 / 2^18 is log10(2) within 3e-8): the loop below settles it.
  int k = ((biased - 1023) * 78913) >> 18;
  std::uint64_t n = 0;
  for (int tries = 0;; ++tries) {
    if (tries > 3 || !scaledRound(m, e, 16 - k, n)) return std::snprintf(buf, 32, "%.17g", v);
    if (n >= hi)
      ++k;  // (rounding up to 10^17 too: the digits are then those of 10^(k+1))
    else if (n < lo)
      --k;
    else
      break;
  }
  // N = top * 10^8 + rest, top in [10^8, 10^9): a double quotient, off by one at most.
  std::uint64_t top = static_cast<std::uint64_t>(static_cast<double>(n) / 1e8);
  std::int64_t rest = static_cast<std::int64_t>(n - top * 100000000u);
  if (rest < 0) {
    --top, rest += 100000000;
  } else if (rest >= 100000000) {
    ++top, rest -= 100000000;
  }
  char digits[17];
  const std::uint32_t t = static_cast<std::uint32_t>(top), lead = t / 100000000u;
  digits[0] = static_cast<char>('0' + lead);
  eightDigits(t - lead * 100000000u, digits + 1);
  eightDigits(static_cast<std::uint32_t>(rest), digits + 9);
  int used = 17;  // %g drops trailing zeros of the fraction
  while (used > 1 && digits[used - 1] == '0') --used;
  char* o = buf;
  if (negative) *o++ = '-';
  if (k >= -4 && k < 17) {  // %f style with 16 - k decimals
    if (k < 0) {
      *o++ = '0';
      *o++ = '.';
      for (int i = 0; i < -k - 1; ++i) *o++ = '0';
      for (int i = 0; i < used; ++i) *o++ = digits[i];
    } else {
      for (int i = 0; i <= k; ++i) *o++ = digits[i];
      if (used > k + 1) {
        *o++ = '.';
        for (int i = k + 1; i < used; ++i) *o++ = digits[i];
      }
    }
  } else {  // %e style: d[.ddd]e+XX
    *o++ = digits[0];
    if (used > 1) {
      *o++ = '.';
      for (int i = 1; i < used; ++i) *o++ = digits[i];
    }
    *o++ = 'e';
    *o++ = k < 0 ? '-' : '+';
    const int x = k < 0 ? -k : k;
    if (x >= 100) *o++ = static_cast<char>('0' + x / 100);
    *o++ = static_cast<char>('0' + x / 10 % 10);
    *o++ = static_cast<char>('0' + x % 10);
  }
  *o = '\0';
  return static_cast<int>(o - buf);
}

void appendDoubleBits(std::string& out, double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  // 16 lower-case hex digits and a space, as "%016" PRIx64 " " prints them (without
  // snprintf: cache keys append thousands of these per surface run).
  char buf[17];
  for (int k = 15; k >= 0; --k, u >>= 4) buf[k] = "0123456789abcdef"[u & 0xfu];
  buf[16] = ' ';
  out.append(buf, sizeof buf);
}

}  // namespace anisomesh
