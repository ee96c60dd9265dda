#pragma once

// The output of `fleetmap bench vectorize`: Markdown tables with a summary row each (vertices and
// time; bytes per fleet tile against the grid's per-tile baselines, bench/bytes; the whole map's
// bytes as files, round trip and one-tile update; where the vertices go), the issues' targets
// marked met or missed, and the same figures as JSON and CSV.

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "bench/vectorize/vectorize_bench.hpp"

namespace fleetmap::bench {

struct BenchTarget {
  std::string name;    // "vertices <= 0.6 x OpenCV, summed"
  std::string actual;  // "0.88"
  bool met = false;
};

// The targets of the vector-map issue, judged on `rows` (ours = kDefault).
std::vector<BenchTarget> EvaluateVectorizeTargets(const std::vector<VectorizeBenchRow>& rows);

void PrintVectorizeBenchTables(const std::vector<VectorizeBenchRow>& rows, std::ostream& out);
void PrintVectorizeTargets(const std::vector<BenchTarget>& targets, std::ostream& out);

nlohmann::ordered_json VectorizeBenchJson(const std::vector<VectorizeBenchRow>& rows,
                                          const std::vector<BenchTarget>& targets,
                                          const VectorizeBenchOptions& options);
// One line per map, with a header line.
std::string VectorizeBenchCsv(const std::vector<VectorizeBenchRow>& rows);

}  // namespace fleetmap::bench
