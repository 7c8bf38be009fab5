#pragma once
// User-typed formulas in the parameters (u, v), e.g. the paper's surface p2:
//   1.5*exp(-0.001*(u^2+v^2))*sin(2*u)*cos(0.2*v)
// Grammar (usual precedence; '^' is right-associative and binds tighter than unary
// minus, so -2^2 = -4 and 2^3^2 = 512):
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?
//   primary := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
// Numbers: 2, 2.5, .5, 1e-3. Names: u, v, the constants pi and e, named parameters
// given in ExpressionOptions, and the functions sin cos tan asin acos atan atan2 sinh
// cosh tanh exp log sqrt abs pow min max.
//
// A formula is compiled once into postfix bytecode (constants folded) and evaluated
// with forward-mode automatic differentiation on second-order dual numbers, so the
// gradient and Hessian in (u, v) are exact (up to rounding), not finite differences.
// Evaluation uses a fixed-size stack on the call stack: no allocation, thread-safe,
// deterministic. Conventions: a^c with a constant exponent c works for negative a
// (integer c); a^b with b depending on (u, v) goes through exp(b log a) and needs a > 0;
// abs, min and max take the derivatives of the selected branch (abs'(0) = 0, ties pick
// the first argument). Domain errors (sqrt(-1), log(0), 1/0) give NaN or infinity,
// which callers such as the surfaces report as InvalidSurface.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace anisomesh {

// Value, gradient and Hessian of a function of (u, v) at one point.
struct Dual2 {
  double f = 0.0;                          // value
  double fu = 0.0, fv = 0.0;               // first derivatives
  double fuu = 0.0, fuv = 0.0, fvv = 0.0;  // second derivatives
};

// Value and gradient only.
struct Dual1 {
  double f = 0.0;             // value
  double fu = 0.0, fv = 0.0;  // first derivatives
};

struct ExpressionOptions {
  // Name used as the prefix of error messages, e.g. "x(u,v)" gives "x(u,v): unknown variable 'w'".
  std::string name = "expression";
  // Named parameters usable in the formula, with their initial values (names must not
  // clash with u, v, pi, e or a function name).
  std::map<std::string, double> parameters;
  // Names of the two variables (e.g. "x", "y" for planar metric formulas).
  std::string uName = "u";
  std::string vName = "v";
};

// A compiled formula f(u, v). Copyable value type.
class Expression {
 public:
  // The constant 0.
  Expression();

  // Parses and compiles text; throws Error(ParseError) naming the column (1-based) and what was expected.
  static Expression parse(const std::string& text, const ExpressionOptions& options = {});

  // f(u, v) only (cheapest path).
  double value(double u, double v) const;
  // f(u, v) with exact first and second derivatives.
  Dual2 evaluate(double u, double v) const;
  // f(u, v) with its first derivatives: the same bits as evaluate()'s f, fu, fv, at about
  // half the cost (no second-order terms). Non-finite second derivatives go unnoticed.
  Dual1 evaluateFirst(double u, double v) const;

  // Changes the value of a named parameter; throws InvalidArgument if the name was not declared.
  void setParameter(const std::string& name, double value);
  // The current value of a named parameter; throws InvalidArgument if the name was not declared.
  double parameter(const std::string& name) const;

  // The source text as given.
  const std::string& text() const { return text_; }
  // The name used in error messages.
  const std::string& name() const { return name_; }
  // True when the formula does not depend on u or v (after constant folding).
  bool isConstant() const;
  // The compiled program, its constants and parameter values as exact bits, the text and
  // the name: equal identities evaluate to the same bits (and the same messages).
  std::string identity() const;
  // Number of bytecode instructions (for tests and diagnostics).
  size_t instructionCount() const { return code_.size(); }

  // Deepest evaluation stack the compiler accepts (deeper formulas are a ParseError).
  static constexpr int kMaxStack = 64;

  // Bytecode operations (public for the compiler in expression.cpp).
  enum class Op : std::uint8_t {
    Const,
    U,
    V,
    Param,
    Neg,
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    PowConst,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Atan2,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Log,
    Sqrt,
    Abs,
    Min,
    Max,
  };
  struct Instr {
    Op op;
    std::int32_t arg;  // index into constants (Const, PowConst) or parameters (Param)
  };

 private:
  friend class ExpressionCompiler;
  std::string text_;
  std::string name_;
  std::vector<Instr> code_;
  std::vector<double> constants_;
  std::vector<std::string> paramNames_;
  std::vector<double> paramValues_;
  bool hasPow_ = false;  // a^b with b not a constant: evaluateFirst() goes through evaluate()
};

}  // namespace anisomesh
