#pragma once
// Internal to geometry/expression*.cpp: facts about the bytecode shared by the evaluators.
#include "anisomesh/geometry/expression.h"

namespace anisomesh {
namespace expression_ops {

// Two operands (the others take one, or none for the leaves).
inline bool isBinary(Expression::Op op) {
  switch (op) {
    case Expression::Op::Add:
    case Expression::Op::Sub:
    case Expression::Op::Mul:
    case Expression::Op::Div:
    case Expression::Op::Pow:
    case Expression::Op::Atan2:
    case Expression::Op::Min:
    case Expression::Op::Max:
      return true;
    default:
      return false;
  }
}

}  // namespace expression_ops
}  // namespace anisomesh
