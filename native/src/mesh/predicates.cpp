// Adaptive predicates: evaluate in doubles with a forward error bound; when the result
// is within the bound, recompute exactly with floating-point expansions (sums of
// non-overlapping doubles, each operation error-free). Written for anisomesh.
#include "anisomesh/mesh/predicates.h"

#include <cmath>

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
// (zeros dropped). h must not alias e or f and hold elen + flen entries; g is the merge
// buffer (elen + flen entries).
int expansionSum(int elen, const double* e, int flen, const double* f, double* h, double* g) {
  // Merge by magnitude, then one pass of error-free additions.
  int i = 0, j = 0, k = 0;
  while (i < elen && j < flen) g[k++] = (std::fabs(e[i]) < std::fabs(f[j])) ? e[i++] : f[j++];
  while (i < elen) g[k++] = e[i++];
  while (j < flen) g[k++] = f[j++];
  if (k == 0) return 0;
  int hlen = 0;
  double q = g[0];
  for (int m = 1; m < k; ++m) {
    double qn, hh;
    twoSum(q, g[m], qn, hh);
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

// An expansion of at most N components on the stack: the exact stage, taken by a few per
// cent of the in-circle tests of a mesh with co-circular points, allocates nothing.
template <int N>
struct Expansion {
  int n = 0;
  double v[N];
};

// out = e * f (out's capacity at least 2 |e| |f|).
template <int R, int A, int B>
void multiply(const Expansion<A>& e, const Expansion<B>& f, Expansion<R>& out) {
  static_assert(R >= 2 * A * B, "product capacity");
  double part[2 * A], sum[R], merge[R];
  out.n = 0;
  for (int k = 0; k < f.n; ++k) {
    const int plen = scaleExpansion(e.n, e.v, f.v[k], part);
    const int n = expansionSum(out.n, out.v, plen, part, sum, merge);
    for (int i = 0; i < n; ++i) out.v[i] = sum[i];
    out.n = n;
  }
}

// out = e + f (out's capacity at least |e| + |f|).
template <int R, int A, int B>
void add(const Expansion<A>& e, const Expansion<B>& f, Expansion<R>& out) {
  static_assert(R >= A + B, "sum capacity");
  double merge[R];
  out.n = expansionSum(e.n, e.v, f.n, f.v, out.v, merge);
}

// e = -e.
template <int N>
Expansion<N>& negate(Expansion<N>& e) {
  for (int i = 0; i < e.n; ++i) e.v[i] = -e.v[i];
  return e;
}

Expansion<2> diff2(double a, double b) {
  Expansion<2> r;
  double x, y;
  twoDiff(a, b, x, y);
  if (y == 0.0) {
    r.n = 1;
    r.v[0] = x;
  } else {
    r.n = 2;
    r.v[0] = y;
    r.v[1] = x;
  }
  return r;
}

double orient2dExact(const double* a, const double* b, const double* c) {
  // det = ax*by - ax*cy - cx*by - ay*bx + ay*cx + cy*bx (the cx*cy terms cancel).
  const double terms[6][2] = {{a[0], b[1]}, {-a[0], c[1]}, {-c[0], b[1]}, {-a[1], b[0]}, {a[1], c[0]}, {c[1], b[0]}};
  double acc[16], tmp[16], merge[16];
  int len = 0;
  for (const auto& t : terms) {
    double p[2];
    twoProduct(t[0], t[1], p[1], p[0]);
    const int n = expansionSum(len, acc, 2, p, tmp, merge);
    for (int i = 0; i < n; ++i) acc[i] = tmp[i];
    len = n;
  }
  return top(len, acc);
}

double incircleExact(const double* a, const double* b, const double* c, const double* d) {
  const auto adx = diff2(a[0], d[0]), ady = diff2(a[1], d[1]);
  const auto bdx = diff2(b[0], d[0]), bdy = diff2(b[1], d[1]);
  const auto cdx = diff2(c[0], d[0]), cdy = diff2(c[1], d[1]);
  Expansion<8> p, q;
  Expansion<16> bc, ca, ab, alift, blift, clift;
  multiply(bdx, cdy, p), multiply(bdy, cdx, q), add(p, negate(q), bc);
  multiply(cdx, ady, p), multiply(cdy, adx, q), add(p, negate(q), ca);
  multiply(adx, bdy, p), multiply(ady, bdx, q), add(p, negate(q), ab);
  multiply(adx, adx, p), multiply(ady, ady, q), add(p, q, alift);
  multiply(bdx, bdx, p), multiply(bdy, bdy, q), add(p, q, blift);
  multiply(cdx, cdx, p), multiply(cdy, cdy, q), add(p, q, clift);
  Expansion<512> ta, tb, tc;
  multiply(alift, bc, ta), multiply(blift, ca, tb), multiply(clift, ab, tc);
  Expansion<1024> tab;
  Expansion<1536> det;
  add(ta, tb, tab), add(tab, tc, det);
  return top(det.n, det.v);
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
