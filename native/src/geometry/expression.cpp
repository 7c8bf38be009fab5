#include "anisomesh/geometry/expression.h"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <utility>

#include "anisomesh/core/error.h"
#include "anisomesh/core/portable_math.h"
#include "expression_ops.h"

namespace anisomesh {

using Op = Expression::Op;
using expression_ops::isBinary;

namespace {

struct FunctionInfo {
  const char* name;
  Op op;
  int arity;
};

// "pow" shares the Pow opcode with the '^' operator.
constexpr std::array<FunctionInfo, 17> kFunctions{{
    {"sin", Op::Sin, 1},
    {"cos", Op::Cos, 1},
    {"tan", Op::Tan, 1},
    {"asin", Op::Asin, 1},
    {"acos", Op::Acos, 1},
    {"atan", Op::Atan, 1},
    {"atan2", Op::Atan2, 2},
    {"sinh", Op::Sinh, 1},
    {"cosh", Op::Cosh, 1},
    {"tanh", Op::Tanh, 1},
    {"exp", Op::Exp, 1},
    {"log", Op::Log, 1},
    {"sqrt", Op::Sqrt, 1},
    {"abs", Op::Abs, 1},
    {"pow", Op::Pow, 2},
    {"min", Op::Min, 2},
    {"max", Op::Max, 2},
}};

const FunctionInfo* findFunction(const std::string& name) {
  for (const auto& f : kFunctions)
    if (name == f.name) return &f;
  return nullptr;
}

// Scalar semantics of every unary or binary opcode (shared by value() and constant folding).
double applyScalar(Op op, double a, double b) {
  switch (op) {
    case Op::Neg:
      return -a;
    case Op::Add:
      return a + b;
    case Op::Sub:
      return a - b;
    case Op::Mul:
      return a * b;
    case Op::Div:
      return a / b;
    case Op::Pow:
    case Op::PowConst:
      return pm::pow(a, b);
    case Op::Sin:
      return pm::sin(a);
    case Op::Cos:
      return pm::cos(a);
    case Op::Tan:
      return pm::tan(a);
    case Op::Asin:
      return pm::asin(a);
    case Op::Acos:
      return pm::acos(a);
    case Op::Atan:
      return pm::atan(a);
    case Op::Atan2:
      return pm::atan2(a, b);
    case Op::Sinh:
      return pm::sinh(a);
    case Op::Cosh:
      return pm::cosh(a);
    case Op::Tanh:
      return pm::tanh(a);
    case Op::Exp:
      return pm::exp(a);
    case Op::Log:
      return pm::log(a);
    case Op::Sqrt:
      return std::sqrt(a);
    case Op::Abs:
      return std::abs(a);
    case Op::Min:
      return a <= b ? a : b;
    case Op::Max:
      return a >= b ? a : b;
    default:
      return 0.0;  // leaves (Const, U, V, Param) never reach here
  }
}

// --- second-order dual arithmetic ------------------------------------------------

// The evaluation stack's slots: Dual2 without default member initializers, so the
// kMaxStack slots on the call stack are not zeroed on every call (most formulas use a few).
struct D {
  double f, fu, fv, fuu, fuv, fvv;
};

// g(a) with g' = g1, g'' = g2: gradient g1 grad a, Hessian g1 H_a + g2 grad a grad a^T.
inline D chain1(const D& a, double g, double g1, double g2) {
  D r;
  r.f = g;
  r.fu = g1 * a.fu;
  r.fv = g1 * a.fv;
  r.fuu = g1 * a.fuu + g2 * a.fu * a.fu;
  r.fuv = g1 * a.fuv + g2 * a.fu * a.fv;
  r.fvv = g1 * a.fvv + g2 * a.fv * a.fv;
  return r;
}

// g(a, b) from its partial derivatives up to second order.
inline D chain2(const D& a, const D& b, double g, double ga, double gb, double gaa, double gab, double gbb) {
  D r;
  r.f = g;
  r.fu = ga * a.fu + gb * b.fu;
  r.fv = ga * a.fv + gb * b.fv;
  r.fuu = ga * a.fuu + gb * b.fuu + gaa * a.fu * a.fu + 2.0 * gab * a.fu * b.fu + gbb * b.fu * b.fu;
  r.fuv = ga * a.fuv + gb * b.fuv + gaa * a.fu * a.fv + gab * (a.fu * b.fv + a.fv * b.fu) + gbb * b.fu * b.fv;
  r.fvv = ga * a.fvv + gb * b.fvv + gaa * a.fv * a.fv + 2.0 * gab * a.fv * b.fv + gbb * b.fv * b.fv;
  return r;
}

inline bool isConstantDual(const D& a) {
  return a.fu == 0.0 && a.fv == 0.0 && a.fuu == 0.0 && a.fuv == 0.0 && a.fvv == 0.0;
}

// a^c for a constant exponent: defined for negative a when c is an integer.
inline D powConst(const D& a, double c) {
  if (c == 2.0) return chain1(a, a.f * a.f, 2.0 * a.f, 2.0);
  const double g1 = c == 0.0 ? 0.0 : c * pm::pow(a.f, c - 1.0);
  const double g2 = (c == 0.0 || c == 1.0) ? 0.0 : c * (c - 1.0) * pm::pow(a.f, c - 2.0);
  return chain1(a, pm::pow(a.f, c), g1, g2);
}

// a^b in general: through exp(b log a), so it needs a > 0 unless b or a is constant.
inline D powDual(const D& a, const D& b) {
  const double f = pm::pow(a.f, b.f);  // as value() computes '^' (powConst squares for 2)
  if (isConstantDual(b)) {
    D r = powConst(a, b.f);
    r.f = f;
    return r;
  }
  const double la = pm::log(a.f);
  if (isConstantDual(a)) return chain1(b, f, f * la, f * la * la);
  const double p1 = pm::pow(a.f, b.f - 1.0);
  return chain2(a, b, f, b.f * p1, f * la, b.f * (b.f - 1.0) * pm::pow(a.f, b.f - 2.0), p1 * (1.0 + b.f * la),
                f * la * la);
}

inline D unaryDual(Op op, const D& a) {
  const double x = a.f;
  switch (op) {
    case Op::Neg:
      return chain1(a, -x, -1.0, 0.0);
    case Op::Sin: {
      double s, c;
      pm::sincos(x, s, c);
      return chain1(a, s, c, -s);
    }
    case Op::Cos: {
      double s, c;
      pm::sincos(x, s, c);
      return chain1(a, c, -s, -c);
    }
    case Op::Tan: {
      const double t = pm::tan(x), g1 = 1.0 + t * t;
      return chain1(a, t, g1, 2.0 * t * g1);
    }
    case Op::Asin: {
      const double g1 = 1.0 / std::sqrt(1.0 - x * x);
      return chain1(a, pm::asin(x), g1, x * g1 * g1 * g1);
    }
    case Op::Acos: {
      const double g1 = 1.0 / std::sqrt(1.0 - x * x);
      return chain1(a, pm::acos(x), -g1, -x * g1 * g1 * g1);
    }
    case Op::Atan: {
      const double g1 = 1.0 / (1.0 + x * x);
      return chain1(a, pm::atan(x), g1, -2.0 * x * g1 * g1);
    }
    case Op::Sinh:
      return chain1(a, pm::sinh(x), pm::cosh(x), pm::sinh(x));
    case Op::Cosh:
      return chain1(a, pm::cosh(x), pm::sinh(x), pm::cosh(x));
    case Op::Tanh: {
      const double t = pm::tanh(x), g1 = 1.0 - t * t;
      return chain1(a, t, g1, -2.0 * t * g1);
    }
    case Op::Exp: {
      const double e = pm::exp(x);
      return chain1(a, e, e, e);
    }
    case Op::Log:
      return chain1(a, pm::log(x), 1.0 / x, -1.0 / (x * x));
    case Op::Sqrt: {
      const double s = std::sqrt(x);
      return chain1(a, s, 0.5 / s, -0.25 / (s * x));
    }
    case Op::Abs:
      return chain1(a, std::abs(x), x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0), 0.0);
    default:
      return a;
  }
}

inline D binaryDual(Op op, const D& a, const D& b) {
  switch (op) {
    case Op::Add:
      return chain2(a, b, a.f + b.f, 1.0, 1.0, 0.0, 0.0, 0.0);
    case Op::Sub:
      return chain2(a, b, a.f - b.f, 1.0, -1.0, 0.0, 0.0, 0.0);
    case Op::Mul:
      return chain2(a, b, a.f * b.f, b.f, a.f, 0.0, 1.0, 0.0);
    case Op::Div: {
      const double ib = 1.0 / b.f;  // the value part is the quotient itself, as in value()
      return chain2(a, b, a.f / b.f, ib, -a.f * ib * ib, 0.0, -ib * ib, 2.0 * a.f * ib * ib * ib);
    }
    case Op::Pow:
      return powDual(a, b);
    case Op::Atan2: {
      const double y = a.f, x = b.f, r2 = x * x + y * y, ir4 = 1.0 / (r2 * r2);
      return chain2(a, b, pm::atan2(y, x), x / r2, -y / r2, -2.0 * x * y * ir4, (y * y - x * x) * ir4,
                    2.0 * x * y * ir4);
    }
    case Op::Min:
      return a.f <= b.f ? a : b;
    case Op::Max:
      return a.f >= b.f ? a : b;
    default:
      return a;
  }
}

}  // namespace

// --- compiler ----------------------------------------------------------------------

// Recursive-descent parser emitting postfix code straight into the Expression, with
// constant folding at emission time (a single Const instruction is always a whole operand).
class ExpressionCompiler {
 public:
  ExpressionCompiler(Expression& out, const std::string& text, std::string uName = "u", std::string vName = "v")
      : e_(out), s_(text), uName_(std::move(uName)), vName_(std::move(vName)) {}

  void run() {
    skipSpace();
    if (pos_ >= s_.size()) fail("empty expression");
    parseExpr();
    skipSpace();
    if (pos_ < s_.size())
      failAt(pos_, "unexpected " + describeHere(), ", expected an operator or the end of the formula");
  }

 private:
  static constexpr int kMaxNesting = 100;  // keeps the recursion shallow under wasm's small stack

  Expression& e_;
  const std::string& s_;
  std::string uName_, vName_;
  size_t pos_ = 0;
  int depth_ = 0;
  int nesting_ = 0;

  [[noreturn]] void fail(const std::string& what) const { throw Error(ErrorCode::ParseError, e_.name_ + ": " + what); }
  // "<head> at column N<tail>", column 1-based.
  [[noreturn]] void failAt(size_t at, const std::string& head, const std::string& tail = "") const {
    fail(head + " at column " + std::to_string(at + 1) + tail);
  }

  void skipSpace() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  bool peek(char c) {
    skipSpace();
    return pos_ < s_.size() && s_[pos_] == c;
  }
  std::string describeHere() const {
    if (pos_ >= s_.size()) return "end of formula";
    const char c = s_[pos_];
    const bool token =
        std::isalnum(static_cast<unsigned char>(c)) || std::string("+-*/^(),._").find(c) != std::string::npos;
    return std::string(token ? "'" : "character '") + c + "'";
  }

  void enter() {
    if (++nesting_ > kMaxNesting) failAt(pos_, "formula nested too deeply");
  }
  void leave() { --nesting_; }

  // --- emission with stack-depth tracking and constant folding ---
  void emit(Op op, std::int32_t arg = 0) { e_.code_.push_back({op, arg}); }
  void push(Op op, std::int32_t arg = 0) {
    emit(op, arg);
    if (++depth_ > Expression::kMaxStack) failAt(pos_, "formula too large (evaluation stack exceeds 64)");
  }
  void pushConst(double c) {
    e_.constants_.push_back(c);
    push(Op::Const, static_cast<std::int32_t>(e_.constants_.size() - 1));
  }
  bool lastIsConst(size_t back) const {
    const auto& code = e_.code_;
    return code.size() > back && code[code.size() - 1 - back].op == Op::Const;
  }
  double constAt(size_t back) const { return e_.constants_[e_.code_[e_.code_.size() - 1 - back].arg]; }
  void replaceTopConsts(size_t count, double value) {
    // The folded constants are the most recent ones: drop their slots too.
    for (size_t i = 0; i < count; ++i) {
      e_.code_.pop_back();
      e_.constants_.pop_back();
    }
    e_.constants_.push_back(value);
    e_.code_.push_back({Op::Const, static_cast<std::int32_t>(e_.constants_.size() - 1)});
  }
  void emitUnary(Op op) {
    if (lastIsConst(0)) {
      replaceTopConsts(1, applyScalar(op, constAt(0), 0.0));
      return;
    }
    emit(op);
  }
  void emitBinary(Op op) {
    --depth_;
    if (lastIsConst(0) && lastIsConst(1)) {
      replaceTopConsts(2, applyScalar(op, constAt(1), constAt(0)));
      return;
    }
    if (op == Op::Pow && lastIsConst(0)) {  // exponent known: a^c works for negative a
      const std::int32_t idx = e_.code_.back().arg;
      e_.code_.pop_back();
      emit(Op::PowConst, idx);
      return;
    }
    if (op == Op::Pow) e_.hasPow_ = true;
    emit(op);
  }

  // --- grammar ---
  void parseExpr() {
    enter();
    parseTerm();
    while (true) {
      if (peek('+')) {
        ++pos_;
        parseTerm();
        emitBinary(Op::Add);
      } else if (peek('-')) {
        ++pos_;
        parseTerm();
        emitBinary(Op::Sub);
      } else {
        break;
      }
    }
    leave();
  }

  void parseTerm() {
    parseUnary();
    while (true) {
      if (peek('*')) {
        ++pos_;
        parseUnary();
        emitBinary(Op::Mul);
      } else if (peek('/')) {
        ++pos_;
        parseUnary();
        emitBinary(Op::Div);
      } else {
        break;
      }
    }
  }

  void parseUnary() {
    if (peek('-')) {
      ++pos_;
      enter();
      parseUnary();
      leave();
      emitUnary(Op::Neg);
    } else if (peek('+')) {
      ++pos_;
      enter();
      parseUnary();
      leave();
    } else {
      parsePower();
    }
  }

  void parsePower() {
    parsePrimary();
    if (peek('^')) {
      ++pos_;
      enter();
      parseUnary();  // right-associative, and 2^-1 is allowed
      leave();
      emitBinary(Op::Pow);
    }
  }

  void parsePrimary() {
    skipSpace();
    if (pos_ >= s_.size()) failAt(pos_, "unexpected end of formula", ", expected a number, a name, '-' or '('");
    const char c = s_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      parseNumber();
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      parseName();
    } else if (c == '(') {
      const size_t open = pos_++;
      parseExpr();
      if (!peek(')')) {
        if (pos_ >= s_.size()) failAt(pos_, "missing ')'", " to close the '(' at column " + std::to_string(open + 1));
        failAt(pos_, "unexpected " + describeHere(), ", expected ')' or an operator");
      }
      ++pos_;
    } else if (c == ')' || c == '*' || c == '/' || c == '^' || c == ',' || c == '+' || c == '-') {
      failAt(pos_, "unexpected " + describeHere(), ", expected a number, a name, '-' or '('");
    } else {
      failAt(pos_, "unexpected " + describeHere());
    }
  }

  void parseNumber() {
    const size_t start = pos_;
    auto digits = [&] {
      size_t n = 0;
      while (pos_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_, ++n;
      return n;
    };
    size_t n = digits();
    if (pos_ < s_.size() && s_[pos_] == '.') {
      ++pos_;
      n += digits();
    }
    bool ok = n > 0;
    if (ok && pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
      // An exponent only if digits follow: "2e" alone is malformed, not 2 * e.
      ++pos_;
      if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
      ok = digits() > 0;
    }
    if (!ok || (pos_ < s_.size() && (std::isalpha(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '.'))) {
      while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '.')) ++pos_;
      failAt(start, "malformed number '" + s_.substr(start, pos_ - start) + "'");
    }
    const std::string lexeme = s_.substr(start, pos_ - start);
    pushConst(std::strtod(lexeme.c_str(), nullptr));
  }

  void parseName() {
    const size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_')) ++pos_;
    const std::string name = s_.substr(start, pos_ - start);
    if (peek('(')) {
      const FunctionInfo* f = findFunction(name);
      if (!f) failAt(start, "unknown function '" + name + "'");
      ++pos_;
      int args = 0;
      if (!peek(')')) {
        while (true) {
          parseExpr();
          ++args;
          if (peek(',')) {
            ++pos_;
            continue;
          }
          if (peek(')')) break;
          if (pos_ >= s_.size()) failAt(pos_, "missing ')'", " to close the call of '" + name + "'");
          failAt(pos_, "unexpected " + describeHere(), ", expected ',' or ')'");
        }
      }
      ++pos_;
      if (args != f->arity)
        failAt(start, "function '" + name + "' takes " + std::to_string(f->arity) + " argument" +
                          (f->arity > 1 ? "s" : "") + ", got " + std::to_string(args));
      if (f->arity == 1)
        emitUnary(f->op);
      else
        emitBinary(f->op);
      return;
    }
    if (findFunction(name)) failAt(start, "'" + name + "' is a function", ", expected '(' after it");
    if (name == uName_) return push(Op::U);
    if (name == vName_) return push(Op::V);
    if (name == "pi") return pushConst(3.14159265358979323846);
    if (name == "e") return pushConst(pm::exp(1.0));
    for (size_t i = 0; i < e_.paramNames_.size(); ++i)
      if (e_.paramNames_[i] == name) return push(Op::Param, static_cast<std::int32_t>(i));
    std::string known = uName_ + ", " + vName_ + ", pi, e";
    for (const auto& p : e_.paramNames_) known += ", " + p;
    failAt(start, "unknown variable '" + name + "'", " (known: " + known + ")");
  }
};

// --- Expression ----------------------------------------------------------------------

Expression::Expression() : text_("0"), code_{{Op::Const, 0}}, constants_{0.0} {}

Expression Expression::parse(const std::string& text, const ExpressionOptions& options) {
  Expression e;
  e.text_ = text;
  e.name_ = options.name;
  e.code_.clear();
  e.constants_.clear();
  for (const auto& [name, value] : options.parameters) {
    bool ident = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_');
    for (char c : name) ident = ident && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
    require(
        ident && name != options.uName && name != options.vName && name != "pi" && name != "e" && !findFunction(name),
        ErrorCode::InvalidArgument, options.name + ": parameter name '" + name + "' is not a free identifier");
    e.paramNames_.push_back(name);
    e.paramValues_.push_back(value);
  }
  ExpressionCompiler(e, text, options.uName, options.vName).run();
  return e;
}

void Expression::setParameter(const std::string& name, double value) {
  for (size_t i = 0; i < paramNames_.size(); ++i)
    if (paramNames_[i] == name) {
      paramValues_[i] = value;
      return;
    }
  throw Error(ErrorCode::InvalidArgument, name_ + ": no parameter named '" + name + "'");
}

double Expression::parameter(const std::string& name) const {
  for (size_t i = 0; i < paramNames_.size(); ++i)
    if (paramNames_[i] == name) return paramValues_[i];
  throw Error(ErrorCode::InvalidArgument, name_ + ": no parameter named '" + name + "'");
}

bool Expression::isConstant() const {
  for (const auto& in : code_)
    if (in.op == Op::U || in.op == Op::V) return false;
  return true;
}

double Expression::value(double u, double v) const {
  double stack[kMaxStack];
  int top = -1;
  for (const Instr& in : code_) {
    switch (in.op) {
      case Op::Const:
        stack[++top] = constants_[in.arg];
        break;
      case Op::U:
        stack[++top] = u;
        break;
      case Op::V:
        stack[++top] = v;
        break;
      case Op::Param:
        stack[++top] = paramValues_[in.arg];
        break;
      case Op::PowConst: {
        const double c = constants_[in.arg];
        stack[top] = c == 2.0 ? stack[top] * stack[top] : pm::pow(stack[top], c);
        break;
      }
      // The arithmetic and the common functions in line (applyScalar() is not inlined).
      case Op::Add:
        stack[top - 1] += stack[top];
        --top;
        break;
      case Op::Sub:
        stack[top - 1] -= stack[top];
        --top;
        break;
      case Op::Mul:
        stack[top - 1] *= stack[top];
        --top;
        break;
      case Op::Div:
        stack[top - 1] /= stack[top];
        --top;
        break;
      case Op::Neg:
        stack[top] = -stack[top];
        break;
      case Op::Sin:
        stack[top] = pm::sin(stack[top]);
        break;
      case Op::Cos:
        stack[top] = pm::cos(stack[top]);
        break;
      case Op::Exp:
        stack[top] = pm::exp(stack[top]);
        break;
      default:
        if (isBinary(in.op)) {
          stack[top - 1] = applyScalar(in.op, stack[top - 1], stack[top]);
          --top;
        } else {
          stack[top] = applyScalar(in.op, stack[top], 0.0);
        }
    }
  }
  return stack[0];
}

Dual2 Expression::evaluate(double u, double v) const {
  D stack[kMaxStack];
  int top = -1;
  for (const Instr& in : code_) {
    switch (in.op) {
      case Op::Const:
        stack[++top] = D{constants_[in.arg], 0, 0, 0, 0, 0};
        break;
      case Op::U:
        stack[++top] = D{u, 1, 0, 0, 0, 0};
        break;
      case Op::V:
        stack[++top] = D{v, 0, 1, 0, 0, 0};
        break;
      case Op::Param:
        stack[++top] = D{paramValues_[in.arg], 0, 0, 0, 0, 0};
        break;
      case Op::PowConst:
        stack[top] = powConst(stack[top], constants_[in.arg]);
        break;
      default:
        if (isBinary(in.op)) {
          stack[top - 1] = binaryDual(in.op, stack[top - 1], stack[top]);
          --top;
        } else {
          stack[top] = unaryDual(in.op, stack[top]);
        }
    }
  }
  const D& r = stack[0];
  return Dual2{r.f, r.fu, r.fv, r.fuu, r.fuv, r.fvv};
}

}  // namespace anisomesh
