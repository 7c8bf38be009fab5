// VTK XML .vtu of a case run with metric, size, quality and edge-length fields (see case_vtu.h).
#include "anisomesh/io/case_vtu.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "anisomesh/mesh/quality.h"
#include "tokens.h"

namespace anisomesh {
namespace {

using io_detail::appendNumber;  // the Medit writers' %.17g

// A DataArray of numbers, components values per item.
void appendArray(std::string* out, const char* type, const char* name, int components, const std::vector<double>& v) {
  *out += "        <DataArray type=\"";
  *out += type;
  *out += "\" Name=\"";
  *out += name;
  *out += "\" NumberOfComponents=\"" + std::to_string(components) + "\" format=\"ascii\">\n";
  for (size_t i = 0; i < v.size(); ++i) {
    appendNumber(out, v[i]);
    out->push_back((i + 1) % size_t(components) == 0 ? '\n' : ' ');
  }
  *out += "        </DataArray>\n";
}

std::vector<double> asDouble(const std::vector<int>& v, size_t n) {
  std::vector<double> out(n, 0.0);
  for (size_t i = 0; i < std::min(n, v.size()); ++i) out[i] = v[i];
  return out;
}

}  // namespace

std::string caseRunVtu(const CaseRun& run) {
  const Mesh& mesh = run.mesh;
  const size_t nv = mesh.points.size(), nt = mesh.triangles.size(), nq = mesh.quads.size(), ne = mesh.edges.size();
  const size_t cells = ne + nt + nq;  // boundary edges (VTK lines), triangles, quads
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"" +
      std::to_string(nv) + "\" NumberOfCells=\"" + std::to_string(cells) + "\">\n";

  // Point data.
  out += "      <PointData Scalars=\"ref\">\n";
  appendArray(&out, "Int32", "ref", 1, asDouble(mesh.pointRefs, nv));
  ElementMeasures items;
  const bool planarMeasures = run.finalSpace != nullptr;
  if (planarMeasures) {
    measureQuality(mesh, *run.finalSpace, &items);
    std::vector<double> tensor, sizes;
    tensor.reserve(9 * nv);
    sizes.reserve(2 * nv);
    for (size_t i = 0; i < nv; ++i) {
      const Vec2 p = i < mesh.params.size() ? mesh.params[i] : Vec2(mesh.points[i].x(), mesh.points[i].y());
      const Metric m = run.finalSpace->metricAt(p);
      const Mat2 t = m.tensor();
      tensor.insert(tensor.end(), {t(0, 0), t(0, 1), 0.0, t(1, 0), t(1, 1), 0.0, 0.0, 0.0, 0.0});
      const MetricSizes s = m.sizes();
      sizes.insert(sizes.end(), {s.h1, s.h2});
    }
    appendArray(&out, "Float64", "metric", 9, tensor);
    appendArray(&out, "Float64", "requestedSize", 2, sizes);
  }
  out += "      </PointData>\n";

  // Cell data: lines first (no quality), then triangles and quads.
  out += "      <CellData Scalars=\"ref\">\n";
  std::vector<double> refs = asDouble(mesh.edgeRefs, ne);
  const std::vector<double> tr = asDouble(mesh.triangleRefs, nt), qr = asDouble(mesh.quadRefs, nq);
  refs.insert(refs.end(), tr.begin(), tr.end());
  refs.insert(refs.end(), qr.begin(), qr.end());
  appendArray(&out, "Int32", "ref", 1, refs);
  const std::vector<double>& quality = planarMeasures ? items.quality : run.elementQuality;
  const double nan = -1.0;  // boundary-edge cells have no quality (VTK ASCII readers reject "nan")
  if (quality.size() == nt + nq) {
    std::vector<double> q(ne, nan);
    q.insert(q.end(), quality.begin(), quality.end());
    appendArray(&out, "Float64", "quality", 1, q);
  }
  if (planarMeasures) {
    std::map<std::pair<int, int>, double> length;
    for (size_t e = 0; e < items.edges.size(); ++e)
      length[{items.edges[e][0], items.edges[e][1]}] = items.edgeLength[e];
    auto edgeLength = [&](int a, int b) {
      const auto it = length.find({std::min(a, b), std::max(a, b)});
      return it == length.end() ? nan : it->second;  // (boundary edges are element edges)
    };
    std::vector<double> lo, hi;
    auto add = [&](const int* v, int k) {
      double mn = std::numeric_limits<double>::infinity(), mx = -mn;
      for (int i = 0; i < k; ++i) {
        const double l = edgeLength(v[i], v[(i + 1) % k]);
        mn = std::min(mn, l);
        mx = std::max(mx, l);
      }
      lo.push_back(mn);
      hi.push_back(mx);
    };
    for (const auto& e : mesh.edges) add(e.data(), 2);
    for (const auto& t : mesh.triangles) add(t.data(), 3);
    for (const auto& q : mesh.quads) add(q.data(), 4);
    appendArray(&out, "Float64", "edgeLengthMin", 1, lo);
    appendArray(&out, "Float64", "edgeLengthMax", 1, hi);
  }
  out += "      </CellData>\n";

  // Geometry and topology.
  out += "      <Points>\n";
  std::vector<double> xyz;
  xyz.reserve(3 * nv);
  for (const Vec3& p : mesh.points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  appendArray(&out, "Float64", "Points", 3, xyz);
  out += "      </Points>\n      <Cells>\n";
  out += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  std::vector<long long> offsets;
  long long offset = 0;
  auto cell = [&](const int* v, int k) {
    for (int i = 0; i < k; ++i) out += std::to_string(v[i]) + (i + 1 < k ? " " : "\n");
    offsets.push_back(offset += k);
  };
  for (const auto& e : mesh.edges) cell(e.data(), 2);
  for (const auto& t : mesh.triangles) cell(t.data(), 3);
  for (const auto& q : mesh.quads) cell(q.data(), 4);
  out += "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (long long o : offsets) out += std::to_string(o) + "\n";
  out += "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (size_t i = 0; i < ne; ++i) out += "3\n";
  for (size_t i = 0; i < nt; ++i) out += "5\n";
  for (size_t i = 0; i < nq; ++i) out += "9\n";
  out += "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

}  // namespace anisomesh
