// Shortest round-trip number text for messages (see number_text.h).
#include "anisomesh/core/number_text.h"

#include <array>
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

// 10^k for k in [0, 21] (exact in 70 bits), made once.
unsigned __int128 pow10u128(int k) {
  static const auto table = [] {
    std::array<unsigned __int128, 22> t{};
    t[0] = 1;
    for (size_t i = 1; i < t.size(); ++i) t[i] = t[i - 1] * 10;
    return t;
  }();
  return table[size_t(k)];
}

// round(m * 2^e * 10^p) to nearest, ties to even, when exact in 128 bits; false otherwise.
bool scaledRound(std::uint64_t m, int e, int p, std::uint64_t& out) {
  if (p < 0 || p > 21) return false;
  const unsigned __int128 x = static_cast<unsigned __int128>(m) * pow10u128(p);  // < 2^53 * 10^21 < 2^123
  if (e >= 0) {
    if (e > 10) return false;
    const unsigned __int128 y = x << e;
    if (y >> 64) return false;
    out = static_cast<std::uint64_t>(y);
    return true;
  }
  const int s = -e;
  if (s >= 127) return false;
  unsigned __int128 q = x >> s;
  const unsigned __int128 rest = x - (q << s), half = static_cast<unsigned __int128>(1) << (s - 1);
  if (rest > half || (rest == half && (q & 1))) ++q;
  if (q >> 64) return false;
  out = static_cast<std::uint64_t>(q);
  return true;
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
  int k = static_cast<int>(std::floor(std::log10(a)));
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
  char digits[17];
  for (int i = 16; i >= 0; --i) {
    digits[i] = static_cast<char>('0' + n % 10);
    n /= 10;
  }
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
