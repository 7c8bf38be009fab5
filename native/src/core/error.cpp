#include "anisomesh/core/error.h"

namespace anisomesh {

const char* errorCodeName(ErrorCode code) {
  switch (code) {
    case ErrorCode::InvalidArgument:
      return "INVALID_ARGUMENT";
    case ErrorCode::InvalidMetric:
      return "INVALID_METRIC";
    case ErrorCode::InvalidDomain:
      return "INVALID_DOMAIN";
    case ErrorCode::OpenContour:
      return "OPEN_CONTOUR";
    case ErrorCode::SelfIntersectingContour:
      return "SELF_INTERSECTING_CONTOUR";
    case ErrorCode::HoleOutsideDomain:
      return "HOLE_OUTSIDE_DOMAIN";
    case ErrorCode::ZeroLengthCurve:
      return "ZERO_LENGTH_CURVE";
    case ErrorCode::InvalidSurface:
      return "INVALID_SURFACE";
    case ErrorCode::ElementBudgetExceeded:
      return "ELEMENT_BUDGET_EXCEEDED";
    case ErrorCode::ParseError:
      return "PARSE_ERROR";
    case ErrorCode::IoError:
      return "IO_ERROR";
    case ErrorCode::Cancelled:
      return "CANCELLED";
    case ErrorCode::OutOfMemory:
      return "OUT_OF_MEMORY";
    case ErrorCode::Internal:
      return "INTERNAL";
  }
  return "INTERNAL";
}

}  // namespace anisomesh
