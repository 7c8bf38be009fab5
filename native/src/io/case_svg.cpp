// The .svg picture of a case run (shared by the CLI and the WebAssembly bindings).
#include "anisomesh/io/case_svg.h"

#include "anisomesh/io/svg.h"
#include "anisomesh/pipeline/mesh_statistics.h"

namespace anisomesh {

std::string caseRunSvg(const CaseRun& run, const CaseSvgOptions& options) {
  const Mesh& mesh = run.mesh;
  SvgOptions o;
  o.width = 900;
  o.strokeWidth = 0.3;
  if (run.finalSpace)
    o.elementValues = elementQualities(mesh, *run.finalSpace);
  else if (run.elementQuality.size() == size_t(mesh.elementCount()) && run.glyphs.empty())
    o.elementValues = run.elementQuality;  // (plain elements under control-space glyphs)
  o.view3d = mesh.dimension == 3 && !options.uv;
  o.azimuth = options.azimuth;
  o.elevation = options.elevation;
  for (const auto& g : run.glyphs) {
    o.overlay.emplace_back();
    if (o.view3d)
      o.overlay.back() = g.xyz;
    else
      for (const Vec2& p : g.uv) o.overlay.back().emplace_back(p.x(), p.y(), 0.0);
  }
  return writeSvg(mesh, o);
}

}  // namespace anisomesh
