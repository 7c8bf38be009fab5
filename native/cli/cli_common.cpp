// Shared pieces of the anisomesh command line (see cli.h).
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "anisomesh/core/error.h"
#include "anisomesh/io/case_vtu.h"
#include "anisomesh/io/file_io.h"
#include "anisomesh/io/mesh_formats.h"
#include "cli.h"

namespace anisomesh::cli {

const char* Args::value(const std::string& option) {
  if (i_ >= argc_) throw UsageError{option + " expects a value"};
  return argv_[i_++];
}

double parseSignedNumber(const std::string& option, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v) || std::fabs(v) > 1e300)
    throw UsageError{option + " expects a number, got '" + text + "'"};
  return v;
}

double parseNumber(const std::string& option, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(v >= 0) || v > 1e300)
    throw UsageError{option + " expects a nonnegative number, got '" + text + "'"};
  return v;
}

long long parseCount(const std::string& option, const char* text) {
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || v <= 0 || errno == ERANGE)
    throw UsageError{option + " expects a positive integer, got '" + text + "'"};
  return v;
}

void parseView(const std::string& option, const std::string& v, CaseSvgOptions& svg) {
  char* end = nullptr;
  const double az = std::strtod(v.c_str(), &end);
  if (end == v.c_str() || *end != ',')
    throw UsageError{option + " expects AZIMUTH,ELEVATION in degrees, got '" + v + "'"};
  const char* rest = end + 1;
  const double el = std::strtod(rest, &end);
  if (end == rest || *end != '\0' || !std::isfinite(az) || !std::isfinite(el))
    throw UsageError{option + " expects AZIMUTH,ELEVATION in degrees, got '" + v + "'"};
  svg.azimuth = az * 0.017453292519943295;
  svg.elevation = el * 0.017453292519943295;
}

bool isSvg(const std::string& path) { return fileExtension(path) == "svg"; }

bool isVtu(const std::string& path) { return fileExtension(path) == "vtu"; }

void requireOutput(const std::string& out) {
  if (out.empty()) throw UsageError{"missing -o OUT"};
  if (isSvg(out) || isVtu(out)) return;
  try {
    meshFormatFromPath(out);
  } catch (const Error& e) {
    throw UsageError{std::string(e.what()) + " (or .vtu, .svg)"};
  }
}

void writeOutput(const std::string& path, const CaseRun& run, const CaseSvgOptions& svg) {
  if (isVtu(path)) return writeTextFileAtomic(path, caseRunVtu(run));
  if (!isSvg(path)) return writeMeshFile(path, run.mesh);
  writeTextFileAtomic(path, caseRunSvg(run, svg));
}

std::function<bool(double)> progressPrinter(int verbosity) {
  if (verbosity < 1) return {};
  return [last = -1](double fraction) mutable {
    const int percent = static_cast<int>(std::floor(100 * fraction));
    if (percent >= last + 10 || (percent == 100 && last != 100)) {
      std::cerr << "anisomesh: " << percent << "%\n";
      last = percent;
    }
    return true;
  };
}

bool parseBudgetOption(const std::string& a, Args& args, std::int64_t* maxElements, std::int64_t* maxControlNodes) {
  if (a == "--max-elements")
    *maxElements = parseCount(a, args.value(a));
  else if (a == "--max-control-nodes")
    *maxControlNodes = parseCount(a, args.value(a));
  else if (a == "--max-input-bytes")
    setDefaultMaxInputBytes(parseCount(a, args.value(a)));
  else
    return false;
  return true;
}

}  // namespace anisomesh::cli
