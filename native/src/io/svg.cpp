#include "anisomesh/io/svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {

Vec2 planar(const Mesh& mesh, int i) {
  if (!mesh.params.empty()) return mesh.params[i];
  return mesh.points[i].head<2>();
}

// Colour ramp for values in [0, 1]: red (0) through yellow to green (1).
std::string ramp(double t) {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  const int r = static_cast<int>(std::lround(255 * std::min(1.0, 2.0 * (1.0 - t))));
  const int g = static_cast<int>(std::lround(200 * std::min(1.0, 2.0 * t)));
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%02x%02x40", r, g);
  return buf;
}

}  // namespace

std::string writeSvg(const Mesh& mesh, const SvgOptions& options) {
  require(options.width > 0, ErrorCode::InvalidArgument, "SVG width must be positive");
  require(options.elementValues.empty() ||
              options.elementValues.size() == mesh.triangles.size() + mesh.quads.size(),
          ErrorCode::InvalidArgument, "SVG element values: one value per element expected");
  Box2 box{Vec2::Constant(1e300), Vec2::Constant(-1e300)};
  for (int i = 0; i < mesh.vertexCount(); ++i) {
    box.lo = box.lo.cwiseMin(planar(mesh, i));
    box.hi = box.hi.cwiseMax(planar(mesh, i));
  }
  if (mesh.vertexCount() == 0) box = Box2{Vec2(0, 0), Vec2(1, 1)};
  const double span = std::max(box.size().x(), 1e-300);
  const double scale = (options.width - 20) / span;
  const int height = static_cast<int>(std::ceil(box.size().y() * scale)) + 20;
  // y grows downwards in SVG: flip so the picture reads like the plane.
  auto px = [&](int i) {
    const Vec2 p = planar(mesh, i);
    return Vec2(10 + (p.x() - box.lo.x()) * scale, 10 + (box.hi.y() - p.y()) * scale);
  };
  std::ostringstream os;
  os.precision(6);
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << options.width << "\" height=\"" << height
     << "\" viewBox=\"0 0 " << options.width << " " << height << "\">\n";
  os << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  os << "<g stroke=\"#1b3a5c\" stroke-width=\"" << options.strokeWidth << "\" stroke-linejoin=\"round\">\n";
  auto element = [&](const int* v, int n, size_t index) {
    os << "<polygon points=\"";
    for (int k = 0; k < n; ++k) {
      const Vec2 p = px(v[k]);
      os << (k ? " " : "") << p.x() << "," << p.y();
    }
    os << "\" fill=\"" << (options.elementValues.empty() ? std::string("#dfe9f3") : ramp(options.elementValues[index]))
       << "\"/>\n";
  };
  size_t index = 0;
  for (const auto& t : mesh.triangles) element(t.data(), 3, index++);
  for (const auto& q : mesh.quads) element(q.data(), 4, index++);
  os << "</g>\n";
  if (options.drawBoundary && !mesh.edges.empty()) {
    os << "<g stroke=\"black\" stroke-width=\"" << 2.5 * options.strokeWidth << "\">\n";
    for (const auto& e : mesh.edges) {
      const Vec2 a = px(e[0]), b = px(e[1]);
      os << "<line x1=\"" << a.x() << "\" y1=\"" << a.y() << "\" x2=\"" << b.x() << "\" y2=\"" << b.y() << "\"/>\n";
    }
    os << "</g>\n";
  }
  os << "</svg>\n";
  return os.str();
}

}  // namespace anisomesh
