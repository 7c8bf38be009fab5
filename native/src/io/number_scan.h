#pragma once
// Private: the scanners behind the text mesh formats' hot loops (tokens.h): decimal
// integers and doubles in their plain forms, eight characters at a time. Each gives the
// value the general path (std::from_chars, fast_float) gives, or declines (nullptr) and
// leaves the text to it.
#include <cstdint>
#include <cstring>

#include <fast_float/fast_float.h>

namespace anisomesh {
namespace io_detail {

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ && (defined(__GNUC__) || defined(__clang__))
constexpr bool kSwarDigits = true;  // eight characters per step (the first one in the low byte)
#else
constexpr bool kSwarDigits = false;
#endif

inline uint64_t load8(const char* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

// How many of the eight characters in v (the first in the low byte) are ASCII digits
// before the first other one. A byte is a digit when its high nibble is 3 and adding 6
// keeps it so; a carry out of a byte (>= 0xFA, not a digit) only reaches later bytes.
inline int leadingDigits(uint64_t v) {
  const uint64_t high = 0xF0F0F0F0F0F0F0F0ULL, threes = 0x3030303030303030ULL;
  const uint64_t x = ((v & high) ^ threes) | (((v + 0x0606060606060606ULL) & high) ^ threes);
  const uint64_t nonDigit = (((x & 0x7F7F7F7F7F7F7F7FULL) + 0x7F7F7F7F7F7F7F7FULL) | x) & 0x8080808080808080ULL;
#if defined(__GNUC__) || defined(__clang__)
  return nonDigit == 0 ? 8 : __builtin_ctzll(nonDigit) >> 3;
#else
  int n = 0;
  while (n < 8 && !(nonDigit >> (8 * n) & 0x80)) ++n;
  return n;
#endif
}

// The value of the first n (1..8) characters of v, all digits: shifted to the top (the
// bytes below read as leading zeros), then combined pairwise (fast_float's eight-digit step).
inline uint32_t digitsValue(uint64_t v, int n) {
  v = (v - 0x3030303030303030ULL) << (8 * (8 - n));  // borrows only reach the bytes shifted out
  v = v * 10 + (v >> 8);
  const uint64_t mask = 0x000000FF000000FFULL;
  v = (((v & mask) * 0x000F424000000064ULL) + (((v >> 16) & mask) * 0x0000271000000001ULL)) >> 32;
  return uint32_t(v);
}

inline bool isDigit(char c) { return static_cast<unsigned char>(c - '0') < 10; }

// Reads the digits at q into *w (w * 10 + digit each, wrapping past 19 digits) and
// returns their end.
inline const char* scanDigits(const char* q, const char* end, uint64_t* w) {
  static constexpr uint64_t kPow10[9] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000};
  if (kSwarDigits) {
    while (end - q >= 8) {
      const uint64_t v = load8(q);
      const int n = leadingDigits(v);
      if (n == 0) return q;
      *w = *w * kPow10[n] + digitsValue(v, n);
      q += n;
      if (n < 8) return q;
    }
  }
  for (; q < end && isDigit(*q); ++q) *w = *w * 10 + uint64_t(*q - '0');
  return q;
}

// The decimal number [-]D+[.D+][(e|E)[+|-]D+] at p with at most 19 significant digits:
// its value in *v, correctly rounded as fast_float gives it (Clinger's exact fast path
// when the digits fit in 53 bits and the power of ten is exact, fast_float's
// Eisel-Lemire step on the same mantissa and exponent otherwise), and its end. nullptr
// for any other form, more digits, an infinite result or fast_float's slow cases: the
// caller's general path reads those. Assumes the round-to-nearest mode (as the rest
// of the program).
inline const char* scanDecimal(const char* p, const char* end, double* v) {
  static constexpr double kExact10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                          1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const char* q = p;
  const bool negative = q < end && *q == '-';
  q += negative;
  const char* const first = q;
  uint64_t w = 0;
  q = scanDigits(q, end, &w);
  if (q == first) return nullptr;
  long long digits = q - first;
  long long exponent = 0;
  if (q < end && *q == '.') {
    const char* f = ++q;
    q = scanDigits(q, end, &w);
    if (q == f) return nullptr;
    digits += q - f;
    exponent = -(long long)(q - f);
  }
  if (q < end && (*q == 'e' || *q == 'E')) {
    ++q;
    const bool minus = q < end && *q == '-';
    if (q < end && (*q == '-' || *q == '+')) ++q;
    const char* e0 = q;
    long long x = 0;
    for (; q < end && isDigit(*q) && q - e0 < 6; ++q) x = x * 10 + (*q - '0');
    if (q == e0 || (q < end && isDigit(*q))) return nullptr;
    exponent += minus ? -x : x;
  }
  if (digits > 19) {  // leading zeros do not count (as in fast_float)
    for (const char* z = first; z < q && (*z == '0' || *z == '.'); ++z) digits -= *z == '0';
    if (digits > 19) return nullptr;
  }
  if (exponent >= -22 && exponent <= 22 && w <= (uint64_t(1) << 53)) {
    double d = double(w);
    d = exponent < 0 ? d / kExact10[-exponent] : d * kExact10[exponent];
    *v = negative ? -d : d;
    return q;
  }
  const fast_float::adjusted_mantissa am =
      fast_float::compute_float<fast_float::binary_format<double>>(int64_t(exponent), w);
  if (am.power2 < 0 || am.power2 >= fast_float::binary_format<double>::infinite_power()) return nullptr;
  fast_float::to_float(negative, am, *v);
  return q;
}

}  // namespace io_detail
}  // namespace anisomesh
