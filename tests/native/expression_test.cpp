#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "anisomesh/core/error.h"
#include "anisomesh/geometry/expression.h"

using namespace anisomesh;

namespace {

using Fn = std::function<double(double, double)>;

struct Case {
  std::string text;
  Fn f;
  double lo, hi;  // sampling box for both u and v
};

// Every function and operator, with arguments kept inside their domains.
std::vector<Case> cases() {
  return {
      {"u + v", [](double u, double v) { return u + v; }, -2, 2},
      {"u - 2*v", [](double u, double v) { return u - 2 * v; }, -2, 2},
      {"u*v*v", [](double u, double v) { return u * v * v; }, -2, 2},
      {"u/(2+v)", [](double u, double v) { return u / (2 + v); }, -1, 1},
      {"-u^3 + v^2", [](double u, double v) { return -u * u * u + v * v; }, -2, 2},
      {"(1+u*u)^(0.5*v)", [](double u, double v) { return std::pow(1 + u * u, 0.5 * v); }, -2, 2},
      {"pow(2+u, v)", [](double u, double v) { return std::pow(2 + u, v); }, -1, 1},
      {"2^(u*v)", [](double u, double v) { return std::pow(2.0, u * v); }, -1, 1},
      {"(u-3)^3", [](double u, double) { return (u - 3) * (u - 3) * (u - 3); }, -2, 2},
      {"sin(u*v)", [](double u, double v) { return std::sin(u * v); }, -2, 2},
      {"cos(u+2*v)", [](double u, double v) { return std::cos(u + 2 * v); }, -2, 2},
      {"tan(0.3*u*v)", [](double u, double v) { return std::tan(0.3 * u * v); }, -2, 2},
      {"asin(0.4*sin(u+v))", [](double u, double v) { return std::asin(0.4 * std::sin(u + v)); }, -2, 2},
      {"acos(0.4*cos(u*v))", [](double u, double v) { return std::acos(0.4 * std::cos(u * v)); }, -2, 2},
      {"atan(u*v)", [](double u, double v) { return std::atan(u * v); }, -2, 2},
      {"atan2(v, u+3)", [](double u, double v) { return std::atan2(v, u + 3); }, -2, 2},
      {"atan2(u*v, 1 - v)", [](double u, double v) { return std::atan2(u * v, 1 - v); }, -0.5, 0.5},
      {"sinh(u-v)", [](double u, double v) { return std::sinh(u - v); }, -2, 2},
      {"cosh(u*v)", [](double u, double v) { return std::cosh(u * v); }, -1, 1},
      {"tanh(u+v*v)", [](double u, double v) { return std::tanh(u + v * v); }, -1, 1},
      {"exp(-u*u - v)", [](double u, double v) { return std::exp(-u * u - v); }, -2, 2},
      {"log(3 + u*v)", [](double u, double v) { return std::log(3 + u * v); }, -1, 1},
      {"sqrt(1 + u^2 + v^4)", [](double u, double v) { return std::sqrt(1 + u * u + v * v * v * v); }, -2, 2},
      {"abs(u - 5) * v", [](double u, double v) { return std::abs(u - 5) * v; }, -2, 2},
      {"min(u*v, 10) + max(v, -10)", [](double u, double v) { return std::min(u * v, 10.0) + std::max(v, -10.0); }, -2,
       2},
      {"pi*u + e*v", [](double u, double v) { return M_PI * u + std::exp(1.0) * v; }, -2, 2},
      {"1.5*exp(-0.001*(u^2+v^2))*sin(2*u)*cos(0.2*v)",
       [](double u, double v) {
         return 1.5 * std::exp(-0.001 * (u * u + v * v)) * std::sin(2 * u) * std::cos(0.2 * v);
       },
       -10, 10},
  };
}

double rel(double a, double b) { return std::abs(a - b) / std::max(1.0, std::max(std::abs(a), std::abs(b))); }

}  // namespace

TEST(Expression, ValuesMatchHandWrittenFunctions) {
  std::mt19937 rng(7);
  for (const auto& c : cases()) {
    const Expression e = Expression::parse(c.text);
    std::uniform_real_distribution<double> d(c.lo, c.hi);
    for (int i = 0; i < 50; ++i) {
      const double u = d(rng), v = d(rng);
      EXPECT_LT(rel(e.value(u, v), c.f(u, v)), 1e-13) << c.text << " at " << u << ", " << v;
      EXPECT_LT(rel(e.evaluate(u, v).f, c.f(u, v)), 1e-13) << c.text;
    }
  }
}

TEST(Expression, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(11);
  for (const auto& c : cases()) {
    const Expression e = Expression::parse(c.text);
    std::uniform_real_distribution<double> d(c.lo, c.hi);
    for (int i = 0; i < 50; ++i) {
      const double u = d(rng), v = d(rng), h = 1e-5;
      const Dual2 r = e.evaluate(u, v);
      // First derivatives against central differences of the hand-written function.
      EXPECT_LT(rel(r.fu, (c.f(u + h, v) - c.f(u - h, v)) / (2 * h)), 1e-6) << c.text;
      EXPECT_LT(rel(r.fv, (c.f(u, v + h) - c.f(u, v - h)) / (2 * h)), 1e-6) << c.text;
      // Second derivatives: central differences of the (exact) first derivatives...
      const Dual2 pu = e.evaluate(u + h, v), mu = e.evaluate(u - h, v);
      const Dual2 pv = e.evaluate(u, v + h), mv = e.evaluate(u, v - h);
      EXPECT_LT(rel(r.fuu, (pu.fu - mu.fu) / (2 * h)), 1e-6) << c.text;
      EXPECT_LT(rel(r.fuv, (pv.fu - mv.fu) / (2 * h)), 1e-6) << c.text;
      EXPECT_LT(rel(r.fuv, (pu.fv - mu.fv) / (2 * h)), 1e-6) << c.text;
      EXPECT_LT(rel(r.fvv, (pv.fv - mv.fv) / (2 * h)), 1e-6) << c.text;
      // ...and second differences of the hand-written values.
      const double k = 1e-4, f0 = c.f(u, v);
      EXPECT_LT(rel(r.fuu, (c.f(u + k, v) - 2 * f0 + c.f(u - k, v)) / (k * k)), 2e-4) << c.text;
      EXPECT_LT(rel(r.fvv, (c.f(u, v + k) - 2 * f0 + c.f(u, v - k)) / (k * k)), 2e-4) << c.text;
      EXPECT_LT(
          rel(r.fuv, (c.f(u + k, v + k) - c.f(u + k, v - k) - c.f(u - k, v + k) + c.f(u - k, v - k)) / (4 * k * k)),
          2e-4)
          << c.text;
    }
  }
}

TEST(Expression, DerivativesMatchHandWrittenFormulas) {
  const Expression e = Expression::parse("sin(u*v)");
  const double u = 0.7, v = -1.3, w = u * v;
  const Dual2 r = e.evaluate(u, v);
  EXPECT_NEAR(r.fu, v * std::cos(w), 1e-15);
  EXPECT_NEAR(r.fv, u * std::cos(w), 1e-15);
  EXPECT_NEAR(r.fuu, -v * v * std::sin(w), 1e-15);
  EXPECT_NEAR(r.fuv, std::cos(w) - w * std::sin(w), 1e-15);
  EXPECT_NEAR(r.fvv, -u * u * std::sin(w), 1e-15);

  const Dual2 a = Expression::parse("atan2(v, u)").evaluate(u, v);
  const double r2 = u * u + v * v;
  EXPECT_NEAR(a.fu, -v / r2, 1e-15);
  EXPECT_NEAR(a.fv, u / r2, 1e-15);
  EXPECT_NEAR(a.fuu, 2 * u * v / (r2 * r2), 1e-14);
  EXPECT_NEAR(a.fvv, -2 * u * v / (r2 * r2), 1e-14);
  EXPECT_NEAR(a.fuv, (v * v - u * u) / (r2 * r2), 1e-14);

  // a^c with a negative base and an integer exponent is differentiable.
  const Dual2 p = Expression::parse("u^3").evaluate(-2, 0);
  EXPECT_DOUBLE_EQ(p.f, -8);
  EXPECT_DOUBLE_EQ(p.fu, 12);
  EXPECT_DOUBLE_EQ(p.fuu, -12);
  const Dual2 q = Expression::parse("u^2 + v^1 + v^0").evaluate(0, 0);
  EXPECT_DOUBLE_EQ(q.fuu, 2);
  EXPECT_DOUBLE_EQ(q.fv, 1);
  EXPECT_DOUBLE_EQ(q.fvv, 0);
}

TEST(Expression, PrecedenceAndAssociativity) {
  auto val = [](const std::string& s, double u = 0, double v = 0) { return Expression::parse(s).value(u, v); };
  EXPECT_EQ(val("-2^2"), -4);
  EXPECT_EQ(val("2^3^2"), 512);
  EXPECT_EQ(val("2*3+4"), 10);
  EXPECT_EQ(val("2+3*4"), 14);
  EXPECT_EQ(val("(2+3)*4"), 20);
  EXPECT_EQ(val("8/4/2"), 1);
  EXPECT_EQ(val("2-3-4"), -5);
  EXPECT_EQ(val("2^-1"), 0.5);
  EXPECT_EQ(val("-u^2", 3), -9);
  EXPECT_EQ(val("--u", 3), 3);
  EXPECT_EQ(val("+u", 3), 3);
  EXPECT_EQ(val("1e-3"), 1e-3);
  EXPECT_EQ(val("2.5E+2"), 250);
  EXPECT_EQ(val(".5 + 1."), 1.5);
  EXPECT_EQ(val(" u * v ", 2, 5), 10);
  EXPECT_NEAR(val("2*e"), 2 * std::exp(1.0), 1e-15);
  EXPECT_NEAR(val("cos(pi)"), -1, 1e-15);
  EXPECT_EQ(val("max(u, v) - min(u, v)", 2, 5), 3);
}

TEST(Expression, ConstantsAreFolded) {
  const Expression c = Expression::parse("2*3 + sin(0) - -4");
  EXPECT_EQ(c.instructionCount(), 1u);
  EXPECT_TRUE(c.isConstant());
  EXPECT_EQ(c.value(0, 0), 10);
  const Expression p = Expression::parse("1.5*exp(-0.001*(u^2+v^2))*sin(2*u)*cos(0.2*v)");
  EXPECT_FALSE(p.isConstant());
  EXPECT_LE(p.instructionCount(), 20u);
}

TEST(Expression, ErrorsNameColumnAndExpectation) {
  struct Bad {
    std::string text, expected;
  };
  const std::vector<Bad> bad = {
      {"sin(u))", "x(u,v): unexpected ')' at column 7"},
      {")", "unexpected ')' at column 1, expected a number"},
      {"sinn(u)", "unknown function 'sinn' at column 1"},
      {"u + w", "unknown variable 'w' at column 5"},
      {"u +", "unexpected end of formula at column 4"},
      {"(u + v", "missing ')' at column 7 to close the '(' at column 1"},
      {"min(u, v", "missing ')' at column 9 to close the call of 'min'"},
      {"atan2(u)", "function 'atan2' takes 2 arguments, got 1 at column 1"},
      {"sin(u, v)", "function 'sin' takes 1 argument, got 2 at column 1"},
      {"1e+ * u", "malformed number '1e+' at column 1"},
      {"u*1.2.3", "malformed number '1.2.3' at column 3"},
      {"2u", "malformed number '2u' at column 1"},
      {"u # v", "unexpected character '#' at column 3"},
      {"u * * v", "unexpected '*' at column 5, expected a number"},
      {"sin + u", "'sin' is a function at column 1, expected '(' after it"},
      {"u v", "unexpected 'v' at column 3, expected an operator"},
      {"", "x(u,v): empty expression"},
      {"   ", "empty expression"},
      {std::string(150, '(') + "u" + std::string(150, ')'), "nested too deeply"},
  };
  for (const auto& b : bad) {
    try {
      Expression::parse(b.text, ExpressionOptions{"x(u,v)", {}});
      ADD_FAILURE() << "no error for '" << b.text << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::ParseError) << b.text;
      EXPECT_NE(std::string(e.what()).find(b.expected), std::string::npos)
          << "'" << b.text << "' gave: " << e.what() << "\nexpected to contain: " << b.expected;
    }
  }
}

TEST(Expression, StackLimitIsAParseError) {
  // Right-nested sums need one stack slot per level.
  std::string s;
  for (int i = 0; i < 70; ++i) s += "u+(";
  s += "u";
  for (int i = 0; i < 70; ++i) s += ")";
  try {
    Expression::parse(s);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::ParseError);
  }
  // A long flat sum evaluates on a shallow stack.
  std::string flat = "u";
  for (int i = 0; i < 500; ++i) flat += "+u";
  EXPECT_EQ(Expression::parse(flat).value(1, 0), 501);
}

TEST(Expression, NamedParameters) {
  Expression e = Expression::parse("a*sin(u) + b0", ExpressionOptions{"f", {{"a", 2.0}, {"b0", 1.0}}});
  EXPECT_NEAR(e.value(0.5, 0), 2 * std::sin(0.5) + 1, 1e-15);
  e.setParameter("a", 3.0);
  EXPECT_EQ(e.parameter("a"), 3.0);
  EXPECT_NEAR(e.evaluate(0.5, 0).fu, 3 * std::cos(0.5), 1e-15);
  EXPECT_THROW(e.setParameter("c", 1.0), Error);
  try {
    Expression::parse("sin(u)", ExpressionOptions{"f", {{"sin", 1.0}}});
    ADD_FAILURE();
  } catch (const Error& err) {
    EXPECT_EQ(err.code(), ErrorCode::InvalidArgument);
  }
  try {
    Expression::parse("a + c", ExpressionOptions{"f", {{"a", 1.0}}});
    ADD_FAILURE();
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("unknown variable 'c' at column 5 (known: u, v, pi, e, a)"),
              std::string::npos)
        << err.what();
  }
}

TEST(Expression, EvaluationIsDeterministicAndCopyable) {
  // Evaluation keeps its stack on the call stack (no allocation, no shared state),
  // so repeated evaluation and copies give bit-identical results.
  const Expression e = Expression::parse("1.5*exp(-0.001*(u^2+v^2))*sin(2*u)*cos(0.2*v)");
  const Expression copy = e;
  for (int i = 0; i < 10; ++i) {
    const double u = -9 + 1.7 * i, v = 4 - 0.9 * i;
    const Dual2 a = e.evaluate(u, v), b = copy.evaluate(u, v), c = e.evaluate(u, v);
    EXPECT_EQ(a.f, b.f);
    EXPECT_EQ(a.fuv, b.fuv);
    EXPECT_EQ(a.fvv, c.fvv);
    EXPECT_EQ(a.f, e.value(u, v));
  }
  EXPECT_EQ(Expression().value(1, 2), 0);
}

TEST(Expression, DomainErrorsGiveNaNForTheCallerToReport) {
  const Expression e = Expression::parse("sqrt(u)");
  EXPECT_TRUE(std::isnan(e.value(-1, 0)));
  EXPECT_TRUE(std::isnan(e.evaluate(-1, 0).f));
  EXPECT_TRUE(std::isinf(Expression::parse("1/u").value(0, 0)));
}

// value() and the value part of evaluate() do the same operations, so they give the same
// double (the fuzz target allows 1e-9): a quotient taken as a * (1 / b), or '^' by a
// constant taken as a product, differed in the last bit and, under cancellation, in
// every bit (tests/fuzz/regressions/expression_fuzz/division_value_part*).
TEST(Expression, ValueAndTheDualValuePartAreTheSameDouble) {
  ExpressionOptions o;
  o.parameters = {{"a", 0.5}};
  for (const char* text :
       {"-v-v/-u^41^---u^1^-----808^----808^--v", "a+tan(-u-3^5^v^5/u*4)+e", "u / 3 - u * (1 / 3)",
        "(u + v) / (u - v) - 1", "pow(u, v) / v", "u ^ (v - v + 2) - u * u", "sin(u) / cos(v) ^ 3"}) {
    const Expression e = Expression::parse(text, o);
    const double points[][2] = {{0.3, -0.7}, {10.0, 3.0}, {1e-8, 1e8}, {0.7, 0.1}};
    for (const auto& p : points) {
      const double a = e.value(p[0], p[1]), b = e.evaluate(p[0], p[1]).f;
      if (std::isnan(a) && std::isnan(b)) continue;
      EXPECT_EQ(a, b) << text << " at (" << p[0] << ", " << p[1] << ")";
    }
  }
}

namespace {
std::uint64_t expressionBitsOf(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
}  // namespace

// evaluateFirst() takes the gradient parts of evaluate()'s rules term for term: the same
// bits for f, fu, fv (NaN for NaN), for every function and operator, with and without a
// non-constant exponent (which goes through evaluate()), inside and outside the domains.
TEST(Expression, FirstOrderEvaluationHasTheBitsOfTheSecondOrderOne) {
  std::mt19937_64 rng(7);
  std::vector<std::string> texts;
  for (const Case& c : cases()) texts.push_back(c.text);
  texts.insert(texts.end(), {"sqrt(u)", "log(u*v)", "u^1.5", "asin(2*u)", "1/(u-v)", "abs(u)*v", "u^0 + v^1"});
  for (const std::string& text : texts) {
    const Expression e = Expression::parse(text);
    std::uniform_real_distribution<double> d(-3.0, 3.0);
    for (int k = 0; k < 200; ++k) {
      const double u = k == 0 ? 0.0 : d(rng), v = k == 0 ? 0.0 : d(rng);
      const Dual2 a = e.evaluate(u, v);
      const Dual1 b = e.evaluateFirst(u, v);
      for (const auto& [x, y] : {std::pair{a.f, b.f}, std::pair{a.fu, b.fu}, std::pair{a.fv, b.fv}}) {
        if (std::isnan(x) && std::isnan(y)) continue;
        ASSERT_EQ(expressionBitsOf(x), expressionBitsOf(y)) << text << " at (" << u << ", " << v << ")";
      }
    }
  }
}

// identity(): equal for the same formula and parameters, different when either changes.
TEST(Expression, IdentityNamesProgramAndParameters) {
  ExpressionOptions o;
  o.parameters = {{"a", 0.5}};
  Expression e = Expression::parse("a*sin(u) + v", o);
  EXPECT_EQ(e.identity(), Expression::parse("a*sin(u) + v", o).identity());
  EXPECT_NE(e.identity(), Expression::parse("a*sin(u) + u", o).identity());
  const std::string before = e.identity();
  e.setParameter("a", 0.25);
  EXPECT_NE(e.identity(), before);
  EXPECT_NE(Expression::parse("0.1").identity(), Expression::parse("0.10000000000000002").identity());
}
