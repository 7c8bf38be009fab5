// anisomesh command-line interface (native).
#include <cstring>
#include <iostream>
#include <string>

#include "anisomesh/anisomesh.h"

namespace {

int usage(std::ostream& os, int code) {
  os << "usage: anisomesh <command> [options]\n"
        "commands:\n"
        "  metric ALPHA H1 H2        print the metric tensor for sizes (h1, h2) at angle ALPHA (radians)\n"
        "  --version                 print the version\n";
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage(std::cerr, 2);
  const std::string cmd = argv[1];
  try {
    if (cmd == "--version") {
      std::cout << "anisomesh 0.1.0\n";
      return 0;
    }
    if (cmd == "--help" || cmd == "-h") return usage(std::cout, 0);
    if (cmd == "metric") {
      if (argc != 5) return usage(std::cerr, 2);
      const auto m = anisomesh::Metric::fromSizes(std::stod(argv[2]), std::stod(argv[3]), std::stod(argv[4]));
      const auto t = m.tensor();
      std::cout << "{\"m11\":" << t(0, 0) << ",\"m12\":" << t(0, 1) << ",\"m22\":" << t(1, 1) << "}\n";
      return 0;
    }
    std::cerr << "anisomesh: unknown command '" << cmd << "'\n";
    return usage(std::cerr, 2);
  } catch (const anisomesh::Error& e) {
    std::cerr << "anisomesh: error " << anisomesh::errorCodeName(e.code()) << ": " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "anisomesh: error: " << e.what() << "\n";
    return 1;
  }
}
