// The text formats' fast scanners (native/src/io/number_scan.h) give the values of the
// general path: every double as strtod (correctly rounded) reads it, every element index
// as written, on long sections (read by the parallel line records) of random and
// adversarial numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "anisomesh/core/error.h"
#include "anisomesh/io/medit.h"

using namespace anisomesh;

namespace {

// A decimal string: random digits (1 to 24 of them, runs of zeros and nines often), a
// point at a random place, sometimes a sign and an exponent; or a double printed with
// 15 to 17 digits; or a value near a rounding boundary.
std::string randomNumber(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, 9);
  std::string s;
  const int kind = int(rng() % 4);
  if (rng() % 3 == 0) s += '-';
  if (kind == 0) {
    // A double printed with 15, 16 or 17 significant digits (%.17g: the writers' form).
    double v;
    const uint64_t bits = rng() & 0x7FEFFFFFFFFFFFFFULL;  // finite
    std::memcpy(&v, &bits, 8);
    if (rng() % 2) v = std::ldexp(double(rng() >> 11), -int(rng() % 120));  // mesh-like magnitudes
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", 15 + int(rng() % 3), v);
    return s + buf;
  }
  if (kind == 1) {
    // 2^53 + 1 and neighbours, halfway cases between doubles, times a power of ten.
    const uint64_t base = (uint64_t(1) << 53) + (rng() % 8);
    std::string digits = std::to_string(base);
    if (rng() % 2) digits += "5" + std::string(rng() % 3, '0');
    const int point = int(rng() % (digits.size() + 1));
    s += point == 0 ? "0." + digits
                    : digits.substr(0, size_t(point)) +
                          (size_t(point) < digits.size() ? "." + digits.substr(size_t(point)) : "");
    if (rng() % 2) s += "e" + std::to_string(int(rng() % 60) - 30);
    return s;
  }
  const int n = 1 + int(rng() % 24);
  std::string digits;
  for (int i = 0; i < n; ++i) {
    const int r = int(rng() % 10);
    digits += char('0' + (r < 3 ? 0 : r < 5 ? 9 : pick(rng)));
  }
  const int point = int(rng() % (n + 1));
  if (point == 0 || point == n || rng() % 4 == 0)
    s += digits;
  else
    s += digits.substr(0, size_t(point)) + "." + digits.substr(size_t(point));
  if (kind == 3)
    s += std::string(rng() % 2 ? "e" : "E") + (rng() % 2 ? "-" : rng() % 2 ? "+" : "") + std::to_string(rng() % 330);
  return s;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST(IoNumberScan, SolValuesAreStrtodsOnMillionsOfRandomNumbers) {
  std::mt19937_64 rng(20261207);
  constexpr int kVertices = 400000;  // 1.2 million numbers per round
  for (int round = 0; round < 2; ++round) {
    std::vector<std::string> words;
    std::string text = "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n" + std::to_string(kVertices) + "\n1 3\n";
    for (int i = 0; i < kVertices * 3; ++i) {
      std::string w = randomNumber(rng);
      const double v = std::strtod(w.c_str(), nullptr);
      if (std::isinf(v)) w = "1";  // an overflow is a parse error, not a value
      words.push_back(w);
      text += w;
      text += (i % 3 == 2) ? "\n" : (rng() % 8 ? " " : " \t ");
    }
    text += "End\n";
    const SolData sol = parseSol(text);
    ASSERT_EQ(sol.values.size(), words.size());
    size_t wrong = 0;
    for (size_t i = 0; i < words.size(); ++i) {
      const double want = std::strtod(words[i].c_str(), nullptr);
      if (!sameBits(sol.values[i], want) && wrong++ < 10)
        ADD_FAILURE() << "'" << words[i] << "' read as " << sol.values[i] << ", strtod gives " << want;
    }
    EXPECT_EQ(wrong, 0u);
  }
}

TEST(IoNumberScan, ElementIndicesOfEveryWidth) {
  // Indices written with 1 to 9 characters (leading zeros), blanks of several kinds:
  // each triangle reads as written. (A record the fast scan refuses sends the whole
  // section to the token-by-token reading, which would hide it: the indices stay in
  // 1..kVertices under most wrong readings, so a wrong value shows.)
  std::mt19937_64 rng(7);
  constexpr int kVertices = 200000, kTriangles = 40000;  // (a wrong index is mostly in range)
  std::string text = "MeshVersionFormatted 2\nDimension 2\nVertices\n" + std::to_string(kVertices) + "\n";
  for (int i = 0; i < kVertices; ++i) text += std::to_string(i) + " 0 0\n";
  text += "Triangles\n" + std::to_string(kTriangles) + "\n";
  std::vector<std::array<int, 3>> want;
  std::vector<int> refs;
  for (int t = 0; t < kTriangles; ++t) {
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      tri[k] = int(rng() % kVertices);
      const std::string v = std::to_string(tri[k] + 1);
      text += std::string(rng() % 4, '0') + v;
      text += rng() % 5 ? " " : rng() % 2 ? "\t" : "  ";
    }
    const int ref = int(rng() % 100000000);
    text += std::to_string(ref) + (rng() % 7 ? "\n" : " \r\n");
    want.push_back(tri);
    refs.push_back(ref);
  }
  text += "End\n";
  const Mesh m = parseMedit(text);
  EXPECT_EQ(m.triangles, want);
  EXPECT_EQ(m.triangleRefs, refs);
  // A vertex index with a letter after its digits is refused (the first triangle's line).
  const size_t first = text.find('\n', text.find("Triangles\n") + 10) + 1;
  const std::string bad = text.substr(0, first) + "1 2 3x 0" + text.substr(text.find('\n', first));
  try {
    parseMedit(bad);
    FAIL() << "accepted 3x as a vertex index";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("line " + std::to_string(kVertices + 7) + ":"), std::string::npos) << e.what();
  }
}
