#include "anisomesh/io/control_space_export.h"

#include <fstream>
#include <sstream>

#include "anisomesh/controlspace/quadtree_control_space.h"
#include "anisomesh/core/error.h"

namespace anisomesh {
namespace {

nlohmann::json metricJson(const Vec2& p, const Metric& m) {
  const Mat2 t = m.tensor();
  const MetricSizes s = m.sizes();
  return {{"p", {p.x(), p.y()}}, {"m", {t(0, 0), t(0, 1), t(1, 1)}}, {"alpha", s.alpha}, {"h1", s.h1}, {"h2", s.h2}};
}

nlohmann::json boundsJson(const Box2& b) { return {{"lo", {b.lo.x(), b.lo.y()}}, {"hi", {b.hi.x(), b.hi.y()}}}; }

}  // namespace

nlohmann::json controlSpaceToJson(const AdaptiveControlSpace& cs) {
  nlohmann::json j;
  j["kind"] = cs.kindName();
  j["bounds"] = boundsJson(cs.bounds());
  nlohmann::json nodes = nlohmann::json::array();
  for (int i = 0; i < cs.nodeCount(); ++i) {
    nlohmann::json n = metricJson(cs.nodePosition(i), cs.nodeMetric(i));
    n["free"] = cs.nodeIsFree(i);
    nodes.push_back(std::move(n));
  }
  j["nodes"] = std::move(nodes);
  j["cells"] = cs.elementNodes();
  if (const auto* qt = dynamic_cast<const QuadtreeControlSpace*>(&cs)) {
    nlohmann::json boxes = nlohmann::json::array(), levels = nlohmann::json::array();
    for (int c : qt->leaves()) {
      const Box2 b = qt->cellBox(c);
      boxes.push_back({b.lo.x(), b.lo.y(), b.hi.x(), b.hi.y()});
      levels.push_back(qt->cellLevel(c));
    }
    j["boxes"] = std::move(boxes);
    j["levels"] = std::move(levels);
  }
  return j;
}

std::string controlSpaceToVtk(const AdaptiveControlSpace& cs) {
  std::ostringstream os;
  os.precision(17);
  const int n = cs.nodeCount();
  const auto cells = cs.elementNodes();
  os << "# vtk DataFile Version 3.0\nanisomesh control space (" << cs.kindName() << ")\nASCII\n"
     << "DATASET UNSTRUCTURED_GRID\nPOINTS " << n << " double\n";
  for (int i = 0; i < n; ++i) os << cs.nodePosition(i).x() << ' ' << cs.nodePosition(i).y() << " 0\n";
  size_t size = 0;
  for (const auto& c : cells) size += c.size() + 1;
  os << "CELLS " << cells.size() << ' ' << size << '\n';
  for (const auto& c : cells) {
    os << c.size();
    for (int v : c) os << ' ' << v;
    os << '\n';
  }
  os << "CELL_TYPES " << cells.size() << '\n';
  for (const auto& c : cells) os << (c.size() == 4 ? 9 : 5) << '\n';
  os << "POINT_DATA " << n << "\nTENSORS metric double\n";
  for (int i = 0; i < n; ++i) {
    const Mat2 t = cs.nodeMetric(i).tensor();
    os << t(0, 0) << ' ' << t(0, 1) << " 0\n" << t(1, 0) << ' ' << t(1, 1) << " 0\n0 0 0\n";
  }
  const char* names[3] = {"h1", "h2", "alpha"};
  for (int k = 0; k < 3; ++k) {
    os << "SCALARS " << names[k] << " double 1\nLOOKUP_TABLE default\n";
    for (int i = 0; i < n; ++i) {
      const MetricSizes s = cs.nodeMetric(i).sizes();
      os << (k == 0 ? s.h1 : k == 1 ? s.h2 : s.alpha) << '\n';
    }
  }
  return os.str();
}

void writeControlSpaceVtk(const AdaptiveControlSpace& cs, const std::string& path) {
  std::ofstream f(path);
  require(static_cast<bool>(f), ErrorCode::IoError, "cannot open " + path + " for writing");
  f << controlSpaceToVtk(cs);
  require(static_cast<bool>(f), ErrorCode::IoError, "cannot write " + path);
}

nlohmann::json sampledControlSpaceToJson(const ControlSpace& cs, int nx, int ny) {
  require(nx >= 1 && ny >= 1, ErrorCode::InvalidArgument, "sampling grid needs nx, ny >= 1");
  const Box2 b = cs.bounds();
  nlohmann::json j;
  j["bounds"] = boundsJson(b);
  j["nx"] = nx;
  j["ny"] = ny;
  nlohmann::json samples = nlohmann::json::array();
  for (int jy = 0; jy < ny; ++jy)
    for (int ix = 0; ix < nx; ++ix) {
      const Vec2 p(b.lo.x() + (ix + 0.5) * b.size().x() / nx, b.lo.y() + (jy + 0.5) * b.size().y() / ny);
      samples.push_back(metricJson(p, cs.metricAt(p)));
    }
  j["samples"] = std::move(samples);
  return j;
}

}  // namespace anisomesh
