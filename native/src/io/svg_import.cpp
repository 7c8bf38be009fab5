#include "anisomesh/io/svg_import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "anisomesh/core/error.h"
#include "anisomesh/core/types.h"
#include "anisomesh/geometry/domain.h"

namespace anisomesh {
namespace {

// One piece of a contour: a line (2 points) or a cubic Bezier (4 points).
struct PathPiece {
  std::vector<Vec2> p;
};

struct Subpath {
  std::vector<PathPiece> pieces;
  bool closed = false;
  std::string where;  // element and subpath, for messages
};

[[noreturn]] void parseError(const std::string& where, const std::string& what) {
  throw Error(ErrorCode::ParseError, "SVG " + where + ": " + what);
}

// The value of attribute `name` in the element text `tag` (between < and >), or "" when absent.
bool attribute(const std::string& tag, const std::string& name, std::string* out) {
  size_t i = 0;
  while ((i = tag.find(name, i)) != std::string::npos) {
    const bool startOk = i > 0 && std::isspace(static_cast<unsigned char>(tag[i - 1]));
    size_t j = i + name.size();
    while (j < tag.size() && std::isspace(static_cast<unsigned char>(tag[j]))) ++j;
    if (startOk && j < tag.size() && tag[j] == '=') {
      ++j;
      while (j < tag.size() && std::isspace(static_cast<unsigned char>(tag[j]))) ++j;
      if (j < tag.size() && (tag[j] == '"' || tag[j] == '\'')) {
        const size_t end = tag.find(tag[j], j + 1);
        if (end == std::string::npos) return false;
        *out = tag.substr(j + 1, end - j - 1);
        return true;
      }
    }
    i += name.size();
  }
  return false;
}

// Path data scanner: numbers (with exponents, ".5.5" as two numbers) and arc flags.
class Scanner {
 public:
  Scanner(const std::string& s, std::string where) : s_(s), where_(std::move(where)) {}
  void skip() {
    while (i_ < s_.size() && (std::isspace(static_cast<unsigned char>(s_[i_])) || s_[i_] == ',')) ++i_;
  }
  bool done() {
    skip();
    return i_ >= s_.size();
  }
  bool numberNext() {
    skip();
    if (i_ >= s_.size()) return false;
    const char c = s_[i_];
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  }
  char command() {
    skip();
    return s_[i_++];
  }
  double number() {
    skip();
    if (!numberNext()) parseError(where_, "expected a number at column " + std::to_string(i_ + 1));
    size_t j = i_;
    if (s_[j] == '-' || s_[j] == '+') ++j;
    bool dot = false;
    while (j < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[j])) || (s_[j] == '.' && !dot))) {
      if (s_[j] == '.') dot = true;
      ++j;
    }
    if (j < s_.size() && (s_[j] == 'e' || s_[j] == 'E')) {
      size_t k = j + 1;
      if (k < s_.size() && (s_[k] == '-' || s_[k] == '+')) ++k;
      if (k < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k]))) {
        j = k;
        while (j < s_.size() && std::isdigit(static_cast<unsigned char>(s_[j]))) ++j;
      }
    }
    const std::string text = s_.substr(i_, j - i_);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
      parseError(where_, "bad number '" + text + "' at column " + std::to_string(i_ + 1));
    i_ = j;
    return v;
  }
  // An arc flag: a single 0 or 1 (may be written without separators).
  bool flag() {
    skip();
    if (i_ >= s_.size() || (s_[i_] != '0' && s_[i_] != '1'))
      parseError(where_, "expected an arc flag 0 or 1 at column " + std::to_string(i_ + 1));
    return s_[i_++] == '1';
  }

 private:
  const std::string& s_;
  std::string where_;
  size_t i_ = 0;
};

// An affine map x -> a x + t (SVG's transform attribute; nested groups compose).
struct Affine {
  Mat2 a = Mat2::Identity();
  Vec2 t = Vec2::Zero();
  Vec2 operator()(const Vec2& p) const { return a * p + t; }
  Affine then(const Affine& inner) const { return {a * inner.a, a * inner.t + t}; }  // this after inner
};

// The transform attribute's list: matrix, translate, scale, rotate (about a point), skewX, skewY.
Affine parseTransform(const std::string& text, const std::string& where) {
  Affine m;
  size_t i = 0;
  const double deg = M_PI / 180.0;
  for (;;) {
    while (i < text.size() && (std::isspace(static_cast<unsigned char>(text[i])) || text[i] == ',')) ++i;
    if (i >= text.size()) return m;
    size_t j = i;
    while (j < text.size() && std::isalpha(static_cast<unsigned char>(text[j]))) ++j;
    const std::string name = text.substr(i, j - i);
    while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    const size_t close = j < text.size() && text[j] == '(' ? text.find(')', j) : std::string::npos;
    if (name.empty() || close == std::string::npos)
      parseError(where, "transform: expected name(numbers) at column " + std::to_string(i + 1));
    const std::string args = text.substr(j + 1, close - j - 1);
    std::string scanWhere = where;
    scanWhere += " transform ";
    scanWhere += name;
    Scanner sc(args, scanWhere);
    std::vector<double> v;
    while (!sc.done()) v.push_back(sc.number());
    auto need = [&](size_t lo, size_t hi) {
      if (v.size() < lo || v.size() > hi)
        parseError(where, "transform " + name + ": expected " + std::to_string(lo) +
                              (hi > lo ? " to " + std::to_string(hi) : "") + " numbers, got " +
                              std::to_string(v.size()));
    };
    Affine f;
    if (name == "matrix") {
      need(6, 6);
      f.a << v[0], v[2], v[1], v[3];
      f.t = Vec2(v[4], v[5]);
    } else if (name == "translate") {
      need(1, 2);
      f.t = Vec2(v[0], v.size() > 1 ? v[1] : 0.0);
    } else if (name == "scale") {
      need(1, 2);
      f.a = Vec2(v[0], v.size() > 1 ? v[1] : v[0]).asDiagonal();
    } else if (name == "rotate") {
      if (v.size() != 1) need(3, 3);
      const double c = std::cos(v[0] * deg), sn = std::sin(v[0] * deg);
      f.a << c, -sn, sn, c;
      if (v.size() == 3) f.t = Vec2(v[1], v[2]) - f.a * Vec2(v[1], v[2]);  // about (cx, cy)
    } else if (name == "skewX") {
      need(1, 1);
      f.a(0, 1) = std::tan(v[0] * deg);
    } else if (name == "skewY") {
      need(1, 1);
      f.a(1, 0) = std::tan(v[0] * deg);
    } else {
      parseError(where, "transform: unknown function '" + name + "'");
    }
    if (!f.a.allFinite() || !f.t.allFinite() || !(std::abs(f.a.determinant()) > 0.0))
      parseError(where, "transform " + name + ": not an invertible map");
    m = m.then(f);  // the list applies right to left: m(f(x))
    i = close + 1;
  }
}

PathPiece line(const Vec2& a, const Vec2& b) { return {{a, b}}; }
PathPiece cubic(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) { return {{a, b, c, d}}; }

// The SVG elliptical arc from p0 to p1 (endpoint form, SVG 1.1 F.6.5) as cubic pieces of <= 90 degrees.
void appendArc(std::vector<PathPiece>& out, Vec2 p0, double rx, double ry, double phiDeg, bool large, bool sweep,
               Vec2 p1) {
  if ((p1 - p0).norm() == 0.0) return;
  rx = std::abs(rx), ry = std::abs(ry);
  if (rx == 0.0 || ry == 0.0) {
    out.push_back(line(p0, p1));
    return;
  }
  const double phi = phiDeg * M_PI / 180.0, c = std::cos(phi), s = std::sin(phi);
  const Vec2 d = 0.5 * (p0 - p1);
  const Vec2 q(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
  const double lambda = q.x() * q.x() / (rx * rx) + q.y() * q.y() / (ry * ry);
  if (lambda > 1.0) rx *= std::sqrt(lambda), ry *= std::sqrt(lambda);
  const double num = rx * rx * ry * ry - rx * rx * q.y() * q.y() - ry * ry * q.x() * q.x();
  const double den = rx * rx * q.y() * q.y() + ry * ry * q.x() * q.x();
  double k = std::sqrt(std::max(0.0, num / den));
  if (large == sweep) k = -k;
  const Vec2 cq(k * rx * q.y() / ry, -k * ry * q.x() / rx);
  const Vec2 center(c * cq.x() - s * cq.y() + 0.5 * (p0.x() + p1.x()),
                    s * cq.x() + c * cq.y() + 0.5 * (p0.y() + p1.y()));
  auto angle = [](const Vec2& u, const Vec2& v) { return std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v)); };
  const Vec2 u((q.x() - cq.x()) / rx, (q.y() - cq.y()) / ry), v((-q.x() - cq.x()) / rx, (-q.y() - cq.y()) / ry);
  const double theta = angle(Vec2(1, 0), u);
  double delta = angle(u, v);
  if (!sweep && delta > 0) delta -= 2 * M_PI;
  if (sweep && delta < 0) delta += 2 * M_PI;
  // (|delta| <= 2 pi: at most 4 pieces; decided in double, so that a NaN angle gives 1
  // piece instead of an out-of-range int conversion)
  const double pieces = std::ceil(std::abs(delta) / (M_PI / 2) - 1e-9);
  const int n = pieces > 1.0 ? (pieces < 4.0 ? static_cast<int>(pieces) : 4) : 1;
  const double step = delta / n, kappa = 4.0 / 3.0 * std::tan(step / 4);
  auto at = [&](double t) {
    return Vec2(center.x() + rx * c * std::cos(t) - ry * s * std::sin(t),
                center.y() + rx * s * std::cos(t) + ry * c * std::sin(t));
  };
  auto tangent = [&](double t) {
    return Vec2(-rx * c * std::sin(t) - ry * s * std::cos(t), -rx * s * std::sin(t) + ry * c * std::cos(t));
  };
  Vec2 a = p0;
  for (int i = 0; i < n; ++i) {
    const double t0 = theta + i * step, t1 = t0 + step;
    const Vec2 b = i + 1 == n ? p1 : at(t1);
    out.push_back(cubic(a, a + kappa * tangent(t0), b - kappa * tangent(t1), b));
    a = b;
  }
}

// The subpaths of path data d.
std::vector<Subpath> parsePathData(const std::string& d, const std::string& where) {
  Scanner sc(d, where);
  std::vector<Subpath> out;
  Vec2 cur = Vec2::Zero(), start = Vec2::Zero(), lastCtrl = Vec2::Zero();
  char prev = 0, cmd = 0;
  auto current = [&]() -> Subpath& {
    if (out.empty() || out.back().closed)
      out.push_back({{}, false, where + " subpath " + std::to_string(out.size() + 1)}), start = cur;
    return out.back();
  };
  while (!sc.done()) {
    if (!sc.numberNext()) {
      cmd = sc.command();
      if (!std::strchr("MmLlHhVvCcSsQqTtAaZz", cmd))
        parseError(where, std::string("unknown path command '") + cmd + "'");
    } else if (cmd == 0) {
      parseError(where, "path data must start with a command (M)");
    } else if (cmd == 'M') {
      cmd = 'L';  // further pairs after M are lines
    } else if (cmd == 'm') {
      cmd = 'l';
    } else if (cmd == 'Z' || cmd == 'z') {
      parseError(where, "a number after Z");
    }
    const bool rel = std::islower(static_cast<unsigned char>(cmd));
    const Vec2 o = rel ? cur : Vec2(Vec2::Zero());
    auto pt = [&]() -> Vec2 {
      const double x = sc.number(), y = sc.number();
      return Vec2(x + o.x(), y + o.y());
    };
    // The reflection of the last control point for S and T (the current point when the
    // previous command was not of the same family).
    auto reflected = [&](const char* family) -> Vec2 {
      if (prev && std::strchr(family, prev)) return Vec2(2 * cur - lastCtrl);
      return cur;
    };
    const char up = char(std::toupper(static_cast<unsigned char>(cmd)));
    if (up == 'M') {
      cur = pt();
      out.push_back({{}, false, where + " subpath " + std::to_string(out.size() + 1)});
      start = cur;
    } else if (up == 'Z') {
      Subpath& sp = current();
      if ((cur - start).norm() > 0) sp.pieces.push_back(line(cur, start));
      sp.closed = true;
      cur = start;
    } else if (up == 'L' || up == 'H' || up == 'V') {
      Vec2 p = cur;
      if (up == 'L') p = pt();
      if (up == 'H') p.x() = sc.number() + (rel ? cur.x() : 0.0);
      if (up == 'V') p.y() = sc.number() + (rel ? cur.y() : 0.0);
      if ((p - cur).norm() > 0) current().pieces.push_back(line(cur, p));
      cur = p;
    } else if (up == 'C' || up == 'S') {
      const bool smooth = up == 'S';
      const Vec2 c1 = smooth ? reflected("CcSs") : pt();
      const Vec2 c2 = pt(), p = pt();
      current().pieces.push_back(cubic(cur, c1, c2, p));
      lastCtrl = c2, cur = p;
    } else if (up == 'Q' || up == 'T') {
      const Vec2 q = up == 'T' ? reflected("QqTt") : pt();
      const Vec2 p = pt();
      current().pieces.push_back(cubic(cur, cur + 2.0 / 3.0 * (q - cur), p + 2.0 / 3.0 * (q - p), p));
      lastCtrl = q, cur = p;
    } else if (up == 'A') {
      const double rx = sc.number(), ry = sc.number(), phi = sc.number();
      const bool large = sc.flag(), sweep = sc.flag();
      const Vec2 p = pt();
      appendArc(current().pieces, cur, rx, ry, phi, large, sweep, p);
      cur = p;
    }
    prev = cmd;
  }
  return out;
}

double numberAttr(const std::string& tag, const char* name, const std::string& where, double fallback) {
  std::string v;
  if (!attribute(tag, name, &v)) return fallback;
  Scanner sc(v, where + " " + name);
  const double x = sc.number();
  return x;
}

// Closed subpaths of the shapes in the document, in document order, in the document's
// coordinates (the transforms of their groups and their own applied).
std::vector<Subpath> shapes(const std::string& svg) {
  std::vector<Subpath> all;
  size_t i = 0;
  int count = 0;
  std::vector<Affine> groups{Affine{}};  // the transform of each open container element
  while ((i = svg.find('<', i)) != std::string::npos) {
    const size_t end = svg.find('>', i);
    if (end == std::string::npos) break;
    const std::string tag = svg.substr(i + 1, end - i - 1);
    i = end + 1;
    if (!tag.empty() && tag[0] == '/') {  // a closing tag: its container's transform ends
      size_t n = 1;
      while (n < tag.size() && (std::isalnum(static_cast<unsigned char>(tag[n])) || tag[n] == ':')) ++n;
      const std::string closing = tag.substr(1, n - 1);
      if ((closing == "g" || closing == "svg" || closing == "a") && groups.size() > 1) groups.pop_back();
      continue;
    }
    size_t n = 0;
    while (n < tag.size() && (std::isalnum(static_cast<unsigned char>(tag[n])) || tag[n] == ':')) ++n;
    const std::string name = tag.substr(0, n);
    const std::string where = "<" + name + "> #" + std::to_string(++count);
    std::string transformText;
    const Affine own = attribute(tag, "transform", &transformText) ? parseTransform(transformText, where) : Affine{};
    const Affine toDocument = groups.back().then(own);
    const bool selfClosing = !tag.empty() && tag.back() == '/';
    if (name == "g" || name == "a" || name == "svg") {
      if (!selfClosing) groups.push_back(toDocument);
      continue;
    }
    const size_t first = all.size();
    std::string d;
    if (name == "path") {
      if (!attribute(tag, "d", &d)) continue;
    } else if (name == "polygon") {
      if (!attribute(tag, "points", &d)) continue;
      d.insert(0, "M ");
      d += " Z";
    } else if (name == "rect") {
      const double x = numberAttr(tag, "x", where, 0), y = numberAttr(tag, "y", where, 0);
      const double w = numberAttr(tag, "width", where, 0), h = numberAttr(tag, "height", where, 0);
      if (!(w > 0 && h > 0)) parseError(where, "width and height must be positive");
      // Rounded corners: rx or ry alone sets both; each at most half its side (SVG 2).
      double rx = numberAttr(tag, "rx", where, -1), ry = numberAttr(tag, "ry", where, -1);
      if (rx < 0) rx = ry;
      if (ry < 0) ry = rx;
      rx = std::min(std::max(rx, 0.0), 0.5 * w), ry = std::min(std::max(ry, 0.0), 0.5 * h);
      Subpath sp{{}, true, where};
      const Vec2 o(x, y);
      if (rx > 0 && ry > 0) {
        const Vec2 c[4] = {o + Vec2(w - rx, 0), o + Vec2(w, h - ry), o + Vec2(rx, h), o + Vec2(0, ry)};
        const Vec2 e[4] = {o + Vec2(w, ry), o + Vec2(w - rx, h), o + Vec2(0, h - ry), o + Vec2(rx, 0)};
        for (int k = 0; k < 4; ++k) {
          const Vec2 from = e[(k + 3) % 4];
          if ((c[k] - from).norm() > 0) sp.pieces.push_back(line(from, c[k]));
          appendArc(sp.pieces, c[k], rx, ry, 0, false, true, e[k]);
        }
      } else {
        const Vec2 c[4] = {o, o + Vec2(w, 0), o + Vec2(w, h), o + Vec2(0, h)};
        for (int k = 0; k < 4; ++k) sp.pieces.push_back(line(c[k], c[(k + 1) % 4]));
      }
      all.push_back(std::move(sp));
    } else if (name == "circle" || name == "ellipse") {
      const double cx = numberAttr(tag, "cx", where, 0), cy = numberAttr(tag, "cy", where, 0);
      const double rx = name == "circle" ? numberAttr(tag, "r", where, 0) : numberAttr(tag, "rx", where, 0);
      const double ry = name == "circle" ? rx : numberAttr(tag, "ry", where, 0);
      if (!(rx > 0 && ry > 0)) parseError(where, "radius must be positive");
      Subpath sp{{}, true, where};
      const Vec2 a(cx + rx, cy), b(cx - rx, cy);
      appendArc(sp.pieces, a, rx, ry, 0, false, true, b);
      appendArc(sp.pieces, b, rx, ry, 0, false, true, a);
      all.push_back(std::move(sp));
    } else {
      continue;
    }
    if (!d.empty())
      for (Subpath& sp : parsePathData(d, where))
        if (!sp.pieces.empty()) all.push_back(std::move(sp));
    // Lines and cubic Beziers map to lines and cubic Beziers: their points are mapped.
    for (size_t k = first; k < all.size(); ++k)
      for (PathPiece& pc : all[k].pieces)
        for (Vec2& p : pc.p) p = toDocument(p);
  }
  return all;
}

nlohmann::json pointJson(const Vec2& p) { return nlohmann::json::array({p.x(), p.y()}); }

}  // namespace

nlohmann::json domainJsonFromSvg(const std::string& svgText, const SvgImportOptions& options) {
  require(std::isfinite(options.size) && options.size > 0, ErrorCode::InvalidArgument,
          "SVG import: size must be positive, got " + std::to_string(options.size));
  std::vector<Subpath> paths = shapes(svgText);
  require(!paths.empty(), ErrorCode::InvalidDomain, "SVG: no closed shape (path, polygon, rect, circle, ellipse)");
  Box2 box{Vec2::Constant(std::numeric_limits<double>::infinity()),
           Vec2::Constant(-std::numeric_limits<double>::infinity())};
  for (const Subpath& sp : paths)
    for (const PathPiece& pc : sp.pieces)
      for (const Vec2& p : pc.p) box.lo = box.lo.cwiseMin(p), box.hi = box.hi.cwiseMax(p);
  const double extent = box.size().maxCoeff();
  require(extent > 0, ErrorCode::InvalidDomain, "SVG: the shapes have no extent");
  for (Subpath& sp : paths) {
    const Vec2 a = sp.pieces.front().p.front(), b = sp.pieces.back().p.back();
    if (!sp.closed && (a - b).norm() > options.closeTolerance * extent)
      throw Error(ErrorCode::OpenContour, "SVG " + sp.where + " is not closed (no Z and its ends do not meet)");
    sp.pieces.back().p.back() = a;  // exactly closed
  }
  // Scale: the box's lower corner to (0, 0), the larger side to options.size (y flipped).
  const double k = options.size / extent;
  auto map = [&](const Vec2& p) {
    return Vec2((p.x() - box.lo.x()) * k, options.flipY ? (box.hi.y() - p.y()) * k : (p.y() - box.lo.y()) * k);
  };
  std::vector<std::vector<Vec2>> polygons;
  for (Subpath& sp : paths) {
    std::vector<Vec2> poly;
    for (PathPiece& pc : sp.pieces) {
      for (Vec2& p : pc.p) p = map(p);
      if (pc.p.size() == 2) {
        poly.push_back(pc.p[0]);
      } else {
        for (int j = 0; j < 8; ++j) {
          const double t = j / 8.0, s = 1 - t;
          poly.push_back(s * s * s * pc.p[0] + 3 * s * s * t * pc.p[1] + 3 * s * t * t * pc.p[2] + t * t * t * pc.p[3]);
        }
      }
    }
    polygons.push_back(std::move(poly));
  }
  // Nesting depth: how many other contours contain a point of each (its first vertex).
  const size_t n = paths.size();
  std::vector<int> depth(n, 0), parent(n, -1);
  for (size_t a = 0; a < n; ++a)
    for (size_t b = 0; b < n; ++b)
      if (a != b && pointInPolygon(polygons[b], polygons[a][0])) {
        ++depth[a];
        if (parent[a] < 0 || std::abs(signedArea(polygons[b])) < std::abs(signedArea(polygons[size_t(parent[a])])))
          parent[a] = int(b);
      }
  std::vector<size_t> outer;
  for (size_t a = 0; a < n; ++a)
    if (depth[a] == 0) outer.push_back(a);
  require(outer.size() == 1, ErrorCode::InvalidDomain,
          "SVG: " + std::to_string(outer.size()) +
              " outermost closed shapes; a domain has one outer contour (draw the others inside it as holes)");
  for (size_t a = 0; a < n; ++a)
    if (depth[a] > 1)
      throw Error(ErrorCode::InvalidDomain, "SVG " + paths[a].where + " lies inside a hole (" +
                                                paths[size_t(parent[a])].where + "): a domain has one level of holes");
  auto contourJson = [&](const Subpath& sp) {
    nlohmann::json curves = nlohmann::json::array();
    for (const PathPiece& pc : sp.pieces) {
      if (pc.p.size() == 2)
        curves.push_back({{"type", "line"}, {"p1", pointJson(pc.p[0])}, {"p2", pointJson(pc.p[1])}});
      else {
        nlohmann::json pts = nlohmann::json::array();
        for (const Vec2& p : pc.p) pts.push_back(pointJson(p));
        curves.push_back({{"type", "bezier"}, {"points", pts}});
      }
    }
    return curves;
  };
  nlohmann::json domain;
  domain["outer"] = contourJson(paths[outer[0]]);
  domain["holes"] = nlohmann::json::array();
  for (size_t a = 0; a < n; ++a)
    if (depth[a] == 1) domain["holes"].push_back(contourJson(paths[a]));
  return domain;
}

}  // namespace anisomesh
