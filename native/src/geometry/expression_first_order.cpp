// Expression::evaluateFirst(): the value and gradient of a compiled formula, on
// first-order dual numbers (the gradient parts of the second-order rules of
// expression.cpp, term for term, so f, fu, fv have the bits evaluate() gives them).
#include <cmath>

#include "anisomesh/core/portable_math.h"
#include "anisomesh/geometry/expression.h"
#include "expression_ops.h"

namespace anisomesh {

using Op = Expression::Op;
using expression_ops::isBinary;

namespace {

// a^b with a non-constant b is not here: powDual() in expression.cpp branches on the
// second derivatives, so such formulas go through evaluate().

struct D1 {
  double f, fu, fv;
};

inline D1 chain1First(const D1& a, double g, double g1) { return D1{g, g1 * a.fu, g1 * a.fv}; }

inline D1 chain2First(const D1& a, const D1& b, double g, double ga, double gb) {
  return D1{g, ga * a.fu + gb * b.fu, ga * a.fv + gb * b.fv};
}

inline D1 powConstFirst(const D1& a, double c) {
  if (c == 2.0) return chain1First(a, a.f * a.f, 2.0 * a.f);
  const double g1 = c == 0.0 ? 0.0 : c * pm::pow(a.f, c - 1.0);
  return chain1First(a, pm::pow(a.f, c), g1);
}

inline D1 unaryFirst(Op op, const D1& a) {
  const double x = a.f;
  switch (op) {
    case Op::Neg:
      return chain1First(a, -x, -1.0);
    case Op::Sin: {
      double s, c;
      pm::sincos(x, s, c);
      return chain1First(a, s, c);
    }
    case Op::Cos: {
      double s, c;
      pm::sincos(x, s, c);
      return chain1First(a, c, -s);
    }
    case Op::Tan: {
      const double t = pm::tan(x), g1 = 1.0 + t * t;
      return chain1First(a, t, g1);
    }
    case Op::Asin: {
      const double g1 = 1.0 / std::sqrt(1.0 - x * x);
      return chain1First(a, pm::asin(x), g1);
    }
    case Op::Acos: {
      const double g1 = 1.0 / std::sqrt(1.0 - x * x);
      return chain1First(a, pm::acos(x), -g1);
    }
    case Op::Atan: {
      const double g1 = 1.0 / (1.0 + x * x);
      return chain1First(a, pm::atan(x), g1);
    }
    case Op::Sinh:
      return chain1First(a, pm::sinh(x), pm::cosh(x));
    case Op::Cosh:
      return chain1First(a, pm::cosh(x), pm::sinh(x));
    case Op::Tanh: {
      const double t = pm::tanh(x), g1 = 1.0 - t * t;
      return chain1First(a, t, g1);
    }
    case Op::Exp: {
      const double e = pm::exp(x);
      return chain1First(a, e, e);
    }
    case Op::Log:
      return chain1First(a, pm::log(x), 1.0 / x);
    case Op::Sqrt: {
      const double s = std::sqrt(x);
      return chain1First(a, s, 0.5 / s);
    }
    case Op::Abs:
      return chain1First(a, std::abs(x), x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0));
    default:
      return a;
  }
}

inline D1 binaryFirst(Op op, const D1& a, const D1& b) {
  switch (op) {
    case Op::Add:
      return chain2First(a, b, a.f + b.f, 1.0, 1.0);
    case Op::Sub:
      return chain2First(a, b, a.f - b.f, 1.0, -1.0);
    case Op::Mul:
      return chain2First(a, b, a.f * b.f, b.f, a.f);
    case Op::Div: {
      const double ib = 1.0 / b.f;
      return chain2First(a, b, a.f / b.f, ib, -a.f * ib * ib);
    }
    case Op::Atan2: {
      const double y = a.f, x = b.f, r2 = x * x + y * y;
      return chain2First(a, b, pm::atan2(y, x), x / r2, -y / r2);
    }
    case Op::Min:
      return a.f <= b.f ? a : b;
    case Op::Max:
      return a.f >= b.f ? a : b;
    default:
      return a;  // Pow never reaches here (see hasPow_)
  }
}

}  // namespace

Dual1 Expression::evaluateFirst(double u, double v) const {
  if (hasPow_) {
    const Dual2 r = evaluate(u, v);
    return Dual1{r.f, r.fu, r.fv};
  }
  D1 stack[kMaxStack];
  int top = -1;
  for (const Instr& in : code_) {
    switch (in.op) {
      case Op::Const:
        stack[++top] = D1{constants_[in.arg], 0, 0};
        break;
      case Op::U:
        stack[++top] = D1{u, 1, 0};
        break;
      case Op::V:
        stack[++top] = D1{v, 0, 1};
        break;
      case Op::Param:
        stack[++top] = D1{paramValues_[in.arg], 0, 0};
        break;
      case Op::PowConst:
        stack[top] = powConstFirst(stack[top], constants_[in.arg]);
        break;
      default:
        if (isBinary(in.op)) {
          stack[top - 1] = binaryFirst(in.op, stack[top - 1], stack[top]);
          --top;
        } else {
          stack[top] = unaryFirst(in.op, stack[top]);
        }
    }
  }
  return Dual1{stack[0].f, stack[0].fu, stack[0].fv};
}

}  // namespace anisomesh
