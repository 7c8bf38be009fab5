#include "anisomesh/io/svg.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

#include <Eigen/Geometry>

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"

namespace anisomesh {
namespace {

Vec2 planar(const Mesh& mesh, int i) {
  if (!mesh.params.empty()) return mesh.params[i];
  return mesh.points[i].head<2>();
}

// Colour ramp for values in [0, 1]: red (0) through yellow to green (1), as r, g, b.
std::array<double, 3> rampRgb(double t) {
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  return {255 * std::min(1.0, 2.0 * (1.0 - t)), 200 * std::min(1.0, 2.0 * t), 64.0};
}

// "#rrggbb" of r, g, b scaled by shade (each channel rounded and clamped to [0, 255]).
std::string hex(const std::array<double, 3>& c, double shade = 1.0) {
  char buf[16];
  int v[3];
  for (int k = 0; k < 3; ++k) v[k] = static_cast<int>(std::lround(std::clamp(c[size_t(k)] * shade, 0.0, 255.0)));
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", v[0], v[1], v[2]);
  return buf;
}

// Orthographic camera: screen right, screen up and towards-the-viewer axes.
struct Camera {
  Vec3 right, up, toViewer;
  Camera(double azimuth, double elevation) {
    toViewer = Vec3(pm::cos(elevation) * pm::cos(azimuth), pm::cos(elevation) * pm::sin(azimuth), pm::sin(elevation));
    right = Vec3(-pm::sin(azimuth), pm::cos(azimuth), 0.0);
    up = toViewer.cross(right);
  }
  Vec2 project(const Vec3& p) const { return Vec2(right.dot(p), up.dot(p)); }
};

}  // namespace

std::string writeSvg(const Mesh& mesh, const SvgOptions& options) {
  require(options.width > 0, ErrorCode::InvalidArgument, "SVG width must be positive");
  require(options.elementValues.empty() || options.elementValues.size() == mesh.triangles.size() + mesh.quads.size(),
          ErrorCode::InvalidArgument, "SVG element values: one value per element expected");
  const Camera cam(options.azimuth, options.elevation);
  auto plane = [&](const Vec3& p) { return options.view3d ? cam.project(p) : Vec2(p.head<2>()); };
  auto at = [&](int i) { return options.view3d ? cam.project(mesh.points[size_t(i)]) : planar(mesh, i); };
  Box2 box{Vec2::Constant(1e300), Vec2::Constant(-1e300)};
  for (int i = 0; i < mesh.vertexCount(); ++i) {
    box.lo = box.lo.cwiseMin(at(i));
    box.hi = box.hi.cwiseMax(at(i));
  }
  for (const auto& line : options.overlay)
    for (const Vec3& p : line) {
      box.lo = box.lo.cwiseMin(plane(p));
      box.hi = box.hi.cwiseMax(plane(p));
    }
  if (!(box.lo.x() <= box.hi.x())) box = Box2{Vec2(0, 0), Vec2(1, 1)};
  const double span = std::max(box.size().x(), 1e-300);
  const double scale = (options.width - 20) / span;
  const int height = static_cast<int>(std::ceil(box.size().y() * scale)) + 20;
  // y grows downwards in SVG: flip so the picture reads like the plane.
  auto toPixels = [&](const Vec2& p) {
    return Vec2(10 + (p.x() - box.lo.x()) * scale, 10 + (box.hi.y() - p.y()) * scale);
  };
  std::ostringstream os;
  os.precision(options.view3d ? 5 : 6);
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << options.width << "\" height=\"" << height
     << "\" viewBox=\"0 0 " << options.width << " " << height << "\">\n";
  os << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  os << "<g stroke=\"#1b3a5c\" stroke-width=\"" << options.strokeWidth << "\" stroke-linejoin=\"round\">\n";
  const std::array<double, 3> plain =
      options.view3d ? std::array<double, 3>{170, 200, 230} : std::array<double, 3>{0xdf, 0xe9, 0xf3};
  // Light from the viewer's upper right; shade = 0.35 + 0.65 |n . l| (two-sided).
  const Vec3 light = (cam.toViewer + 0.6 * cam.up + 0.3 * cam.right).normalized();
  auto element = [&](const int* v, int n, size_t index) {
    os << "<polygon points=\"";
    for (int k = 0; k < n; ++k) {
      const Vec2 p = toPixels(at(v[k]));
      os << (k ? " " : "") << p.x() << "," << p.y();
    }
    const std::array<double, 3> base = options.elementValues.empty() ? plain : rampRgb(options.elementValues[index]);
    double shade = 1.0;
    if (options.view3d) {
      const Vec3& a = mesh.points[size_t(v[0])];
      const Vec3 nrm =
          n == 3 ? (mesh.points[size_t(v[1])] - a).cross(mesh.points[size_t(v[2])] - a)
                 : (mesh.points[size_t(v[2])] - a).cross(mesh.points[size_t(v[3])] - mesh.points[size_t(v[1])]);
      const double len = nrm.norm();
      shade = 0.35 + 0.65 * (len > 0 ? std::abs(nrm.dot(light)) / len : 1.0);
    }
    os << "\" fill=\"" << hex(base, shade) << "\"/>\n";
  };
  // Elements: triangles then quads (the index of elementValues); in 3D painted farthest first.
  const size_t nt = mesh.triangles.size(), ne = nt + mesh.quads.size();
  std::vector<size_t> order(ne);
  std::iota(order.begin(), order.end(), size_t(0));
  auto verts = [&](size_t e, int* n) {
    *n = e < nt ? 3 : 4;
    return e < nt ? mesh.triangles[e].data() : mesh.quads[e - nt].data();
  };
  if (options.view3d) {
    std::vector<double> depth(ne);
    for (size_t e = 0; e < ne; ++e) {
      int n;
      const int* v = verts(e, &n);
      double d = 0.0;
      for (int k = 0; k < n; ++k) d += cam.toViewer.dot(mesh.points[size_t(v[k])]);
      depth[e] = d / n;
    }
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return depth[a] < depth[b]; });
  }
  for (size_t e : order) {
    int n;
    const int* v = verts(e, &n);
    element(v, n, e);
  }
  os << "</g>\n";
  if (options.drawBoundary && !mesh.edges.empty()) {
    os << "<g stroke=\"black\" stroke-width=\"" << 2.5 * options.strokeWidth << "\">\n";
    for (const auto& e : mesh.edges) {
      const Vec2 a = toPixels(at(e[0])), b = toPixels(at(e[1]));
      os << "<line x1=\"" << a.x() << "\" y1=\"" << a.y() << "\" x2=\"" << b.x() << "\" y2=\"" << b.y() << "\"/>\n";
    }
    os << "</g>\n";
  }
  if (!options.overlay.empty()) {
    os << "<g stroke=\"#b0203a\" stroke-width=\"" << 2.0 * options.strokeWidth << "\" fill=\"none\">\n";
    os.precision(4);
    for (const auto& line : options.overlay) {
      if (line.size() < 2) continue;
      os << "<polygon points=\"";
      for (size_t k = 0; k < line.size(); ++k) {
        const Vec2 p = toPixels(plane(line[k]));
        os << (k ? " " : "") << p.x() << "," << p.y();
      }
      os << "\"/>\n";
    }
    os << "</g>\n";
  }
  os << "</svg>\n";
  return os.str();
}

}  // namespace anisomesh
