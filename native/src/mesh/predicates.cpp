// Adaptive predicates: evaluate in doubles with a forward error bound; when the result
// is within the bound, recompute exactly with floating-point expansions (sums of
// non-overlapping doubles, each operation error-free). Written for anisomesh.
#include "anisomesh/mesh/predicates.h"

#include <cmath>
#include <vector>

namespace anisomesh {
namespace {

constexpr double kEps = 1.1102230246251565e-16;  // 2^-53, half an ulp of 1
constexpr double kOrientBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kInCircleBound = (10.0 + 96.0 * kEps) * kEps;
constexpr double kSplitter = 134217729.0;  // 2^27 + 1, for Dekker's split

// x + y = a + b exactly, x = fl(a + b).
inline void twoSum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  const double br = b - bv;
  const double ar = a - av;
  y = ar + br;
}

// x + y = a - b exactly.
inline void twoDiff(double a, double b, double& x, double& y) {
  x = a - b;
  const double bv = a - x;
  const double av = x + bv;
  const double br = bv - b;
  const double ar = a - av;
  y = ar + br;
}

// a = hi + lo with hi, lo of at most 26 significant bits each.
inline void split(double a, double& hi, double& lo) {
  const double c = kSplitter * a;
  const double big = c - a;
  hi = c - big;
  lo = a - hi;
}

// x + y = a * b exactly (Dekker); every partial product is exact, so FMA contraction
// by the compiler cannot change the result.
inline void twoProduct(double a, double b, double& x, double& y) {
  x = a * b;
  double ahi, alo, bhi, blo;
  split(a, ahi, alo);
  split(b, bhi, blo);
  const double e1 = x - ahi * bhi;
  const double e2 = e1 - alo * bhi;
  const double e3 = e2 - ahi * blo;
  y = alo * blo - e3;
}

// h = e + f for expansions sorted by increasing magnitude; returns the length of h
// (zeros dropped). h must not alias e or f and hold elen + flen entries.
int expansionSum(int elen, const double* e, int flen, const double* f, double* h) {
  // Merge by magnitude, then one pass of error-free additions.
  std::vector<double> g;
  double gs[64];
  double* gp = gs;
  if (elen + flen > 64) {
    g.resize(elen + flen);
    gp = g.data();
  }
  int i = 0, j = 0, k = 0;
  while (i < elen && j < flen) gp[k++] = (std::fabs(e[i]) < std::fabs(f[j])) ? e[i++] : f[j++];
  while (i < elen) gp[k++] = e[i++];
  while (j < flen) gp[k++] = f[j++];
  if (k == 0) return 0;
  int hlen = 0;
  double q = gp[0];
  for (int m = 1; m < k; ++m) {
    double qn, hh;
    twoSum(q, gp[m], qn, hh);
    q = qn;
    if (hh != 0.0) h[hlen++] = hh;
  }
  if (q != 0.0 || hlen == 0) h[hlen++] = q;
  return hlen;
}

// h = b * e; h holds 2 * elen entries; returns the length (zeros dropped).
int scaleExpansion(int elen, const double* e, double b, double* h) {
  int hlen = 0;
  double q, hh;
  twoProduct(e[0], b, q, hh);
  if (hh != 0.0) h[hlen++] = hh;
  for (int i = 1; i < elen; ++i) {
    double t1, t0, sum;
    twoProduct(e[i], b, t1, t0);
    twoSum(q, t0, sum, hh);
    if (hh != 0.0) h[hlen++] = hh;
    twoSum(t1, sum, q, hh);
    if (hh != 0.0) h[hlen++] = hh;
  }
  if (q != 0.0 || hlen == 0) h[hlen++] = q;
  return hlen;
}

// Sign-carrying most significant component of an expansion.
inline double top(int len, const double* e) { return len > 0 ? e[len - 1] : 0.0; }

// Expansion product e * f into a vector.
std::vector<double> multiply(const std::vector<double>& e, const std::vector<double>& f) {
  std::vector<double> acc, tmp, part(2 * e.size());
  for (double fi : f) {
    const int plen = scaleExpansion(static_cast<int>(e.size()), e.data(), fi, part.data());
    tmp.resize(acc.size() + plen);
    const int n = expansionSum(static_cast<int>(acc.size()), acc.data(), plen, part.data(), tmp.data());
    tmp.resize(n);
    acc.swap(tmp);
  }
  return acc;
}

std::vector<double> add(const std::vector<double>& e, const std::vector<double>& f) {
  std::vector<double> h(e.size() + f.size());
  h.resize(expansionSum(static_cast<int>(e.size()), e.data(), static_cast<int>(f.size()), f.data(), h.data()));
  return h;
}

std::vector<double> negate(std::vector<double> e) {
  for (double& x : e) x = -x;
  return e;
}

std::vector<double> diff2(double a, double b) {
  double x, y;
  twoDiff(a, b, x, y);
  if (y == 0.0) return {x};
  return {y, x};
}

double orient2dExact(const double* a, const double* b, const double* c) {
  // det = ax*by - ax*cy - cx*by - ay*bx + ay*cx + cy*bx (the cx*cy terms cancel).
  const double terms[6][2] = {{a[0], b[1]}, {-a[0], c[1]}, {-c[0], b[1]}, {-a[1], b[0]}, {a[1], c[0]}, {c[1], b[0]}};
  double acc[16], tmp[16];
  int len = 0;
  for (const auto& t : terms) {
    double p[2];
    twoProduct(t[0], t[1], p[1], p[0]);
    const int n = expansionSum(len, acc, 2, p, tmp);
    for (int i = 0; i < n; ++i) acc[i] = tmp[i];
    len = n;
  }
  return top(len, acc);
}

double incircleExact(const double* a, const double* b, const double* c, const double* d) {
  const auto adx = diff2(a[0], d[0]), ady = diff2(a[1], d[1]);
  const auto bdx = diff2(b[0], d[0]), bdy = diff2(b[1], d[1]);
  const auto cdx = diff2(c[0], d[0]), cdy = diff2(c[1], d[1]);
  const auto bc = add(multiply(bdx, cdy), negate(multiply(bdy, cdx)));
  const auto ca = add(multiply(cdx, ady), negate(multiply(cdy, adx)));
  const auto ab = add(multiply(adx, bdy), negate(multiply(ady, bdx)));
  const auto alift = add(multiply(adx, adx), multiply(ady, ady));
  const auto blift = add(multiply(bdx, bdx), multiply(bdy, bdy));
  const auto clift = add(multiply(cdx, cdx), multiply(cdy, cdy));
  const auto det = add(add(multiply(alift, bc), multiply(blift, ca)), multiply(clift, ab));
  return top(static_cast<int>(det.size()), det.data());
}

}  // namespace

double orient2d(const double* a, const double* b, const double* c) {
  const double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  const double detright = (a[1] - c[1]) * (b[0] - c[0]);
  const double det = detleft - detright;
  const double bound = kOrientBound * (std::fabs(detleft) + std::fabs(detright));
  if (det > bound || -det > bound) return det;
  return orient2dExact(a, b, c);
}

double incircle(const double* a, const double* b, const double* c, const double* d) {
  const double adx = a[0] - d[0], ady = a[1] - d[1];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double alift = adx * adx + ady * ady;
  const double blift = bdx * bdx + bdy * bdy;
  const double clift = cdx * cdx + cdy * cdy;
  const double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  const double bound = kInCircleBound * permanent;
  if (det > bound || -det > bound) return det;
  return incircleExact(a, b, c, d);
}

double orient2dNaive(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (a.x() - c.x()) * (b.y() - c.y()) - (a.y() - c.y()) * (b.x() - c.x());
}

double incircleNaive(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y();
  return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) + (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
         (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}

}  // namespace anisomesh
