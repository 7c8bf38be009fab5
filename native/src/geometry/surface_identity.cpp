// Surface::identity() of every surface kind and Expression::identity(): exact texts of
// what defines a surface, so that work depending only on the surface can be reused
// (e.g. the curvature part of a patch's control space while a source is dragged).
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <string>

#include "anisomesh/core/number_text.h"
#include "anisomesh/geometry/expression.h"
#include "anisomesh/geometry/surface.h"

namespace anisomesh {

namespace {

void appendVec(std::string& out, const Vec3& v) {
  for (int k = 0; k < 3; ++k) appendDoubleBits(out, v[k]);
}

// Length-prefixed, so that no text can imitate a field boundary.
void appendText(std::string& out, const std::string& t) {
  out += std::to_string(t.size());
  out += ':';
  out += t;
  out += ' ';
}

std::string head(const char* kind, const Surface& s) {
  std::string out = kind;
  out += ' ';
  appendText(out, s.name());
  appendDoubleBits(out, s.domain().lo.x());
  appendDoubleBits(out, s.domain().lo.y());
  appendDoubleBits(out, s.domain().hi.x());
  appendDoubleBits(out, s.domain().hi.y());
  return out;
}

}  // namespace

std::string Expression::identity() const {
  std::string out;
  appendText(out, name_);
  appendText(out, text_);
  out += std::to_string(code_.size()) + ' ';
  for (const Instr& in : code_) out += std::to_string(int(in.op)) + ',' + std::to_string(in.arg) + ' ';
  out += std::to_string(constants_.size()) + ' ';
  for (double c : constants_) appendDoubleBits(out, c);
  out += std::to_string(paramValues_.size()) + ' ';
  for (size_t i = 0; i < paramValues_.size(); ++i) {
    appendText(out, paramNames_[i]);
    appendDoubleBits(out, paramValues_[i]);
  }
  return out;
}

std::string PlaneSurface::identity() const {
  std::string out = head("plane", *this);
  appendVec(out, o_);
  appendVec(out, a1_);
  appendVec(out, a2_);
  return out;
}

std::string HeightFieldSurface::identity() const {
  std::string out = head("heightfield", *this);
  appendText(out, f_.identity());
  return out;
}

std::string CylinderSurface::identity() const {
  std::string out = head("cylinder", *this);
  appendDoubleBits(out, r_);
  appendVec(out, c_);
  return out;
}

std::string SphereSurface::identity() const {
  std::string out = head("sphere", *this);
  appendDoubleBits(out, r_);
  appendVec(out, c_);
  return out;
}

std::string TorusSurface::identity() const {
  std::string out = head("torus", *this);
  appendDoubleBits(out, R_);
  appendDoubleBits(out, r_);
  appendVec(out, c_);
  return out;
}

std::string BezierPatchSurface::identity() const {
  std::string out = head("bezier", *this);
  for (const auto& row : cp_)
    for (const Vec3& p : row) appendVec(out, p);
  return out;
}

std::string BSplinePatchSurface::identity() const {
  std::string out = head("bspline", *this);
  out += std::to_string(p_) + ' ' + std::to_string(q_) + ' ' + std::to_string(cp_.size()) + ' ';
  for (const auto& row : cp_) {
    out += std::to_string(row.size()) + ' ';
    for (const Vec3& p : row) appendVec(out, p);
  }
  return out;
}

std::string ExpressionSurface::identity() const {
  std::string out = head("expression", *this);
  for (const Expression& f : f_) appendText(out, f.identity());
  return out;
}

}  // namespace anisomesh
