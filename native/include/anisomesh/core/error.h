#pragma once
// Typed errors of the core. Every bad input is reported by throwing anisomesh::Error
// with a code (stable, machine readable, also used across the wasm boundary) and a
// message naming what is wrong.
#include <new>
#include <stdexcept>
#include <string>

namespace anisomesh {

enum class ErrorCode {
  InvalidArgument,          // a parameter out of its range (negative radius, dr < 1, ...)
  InvalidMetric,            // NaN/infinite entries, zero or negative sizes, non-SPD tensor
  InvalidDomain,            // empty or inverted box, source outside in a place that matters
  OpenContour,              // a contour chain whose ends do not meet
  SelfIntersectingContour,  // contour segments that cross
  HoleOutsideDomain,        // a hole not strictly inside the outer contour, or overlapping holes
  ZeroLengthCurve,          // a segment or curve of zero length
  InvalidSurface,           // degenerate parameterization, bad expression
  ElementBudgetExceeded,    // the requested mesh would exceed the element budget
  ParseError,               // malformed file or JSON
  IoError,                  // a file that cannot be read or written
  Cancelled,                // a long run stopped on request
  OutOfMemory,              // an allocation failed (the message names the stage)
  Internal,                 // a bug: an invariant of the core did not hold
};

// Stable upper-case name of a code, e.g. "INVALID_METRIC".
const char* errorCodeName(ErrorCode code);

// The one exception type the core throws for bad input.
class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ErrorCode code() const { return code_; }

 private:
  ErrorCode code_;
};

// Throws Error(code, message) when cond is false.
inline void require(bool cond, ErrorCode code, const std::string& message) {
  if (!cond) throw Error(code, message);
}

}  // namespace anisomesh

namespace anisomesh {

// Runs f; an allocation failure inside (std::bad_alloc, or std::length_error from a
// container asked for more than it can hold) becomes Error(OutOfMemory) naming the stage.
template <class F>
auto withStage(const char* stage, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::OutOfMemory, std::string("out of memory during ") + stage);
  } catch (const std::length_error&) {
    throw Error(ErrorCode::OutOfMemory,
                std::string("out of memory during ") + stage + " (a container outgrew its limit)");
  }
}

}  // namespace anisomesh
