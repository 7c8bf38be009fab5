// anisomesh metric ALPHA H1 H2: prints the metric tensor of sizes at an angle.
#include <iostream>
#include <nlohmann/json.hpp>

#include "anisomesh/metric/metric.h"
#include "cli.h"

namespace anisomesh::cli {

namespace {

int runMetric(Args& args) {
  std::vector<double> v;
  const char* names[] = {"ALPHA", "H1", "H2"};
  while (!args.done()) {
    const std::string a = args.next();
    if (v.size() == 3) throw UsageError{"unexpected argument '" + a + "'"};
    v.push_back(parseSignedNumber(names[v.size()], a.c_str()));
  }
  if (v.size() != 3) throw UsageError{"metric expects ALPHA H1 H2"};
  const Mat2 t = Metric::fromSizes(v[0], v[1], v[2]).tensor();
  nlohmann::ordered_json out;
  out["m11"] = t(0, 0);
  out["m12"] = t(0, 1);
  out["m22"] = t(1, 1);
  std::cout << out.dump() << "\n";
  return 0;
}

}  // namespace

Command metricCommand() {
  return {"metric", "  metric ALPHA H1 H2        print the metric tensor for sizes (h1, h2) at angle ALPHA (radians)\n",
          runMetric};
}

}  // namespace anisomesh::cli
