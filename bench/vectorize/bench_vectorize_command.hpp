#pragma once

// `fleetmap bench vectorize --maps DIR [--json F] [--csv F] [--runs N]`: for every *.yaml in DIR,
// ours (kDefault) and the paper's method against OpenCV findContours + approxPolyDP: time,
// vertices, constraints, bytes, round trip and one-tile updates (vectorize_bench.hpp). Prints
// Markdown tables and the targets met / missed; writes JSON / CSV on request.

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>

#include "bench/vectorize/vectorize_bench.hpp"

namespace fleetmap::bench {

struct BenchVectorizeCommandOptions {
  std::string maps_dir;
  std::string json_path;
  std::string csv_path;
  VectorizeBenchOptions bench;
};

inline constexpr int kMinBenchRuns = 5;

int RunBenchVectorize(const BenchVectorizeCommandOptions& options, std::ostream& out,
                      std::ostream& err);

// Registers `vectorize` under `bench` (see BenchCommand).
void AddBenchVectorizeCommand(CLI::App& app, int* exit_code);

}  // namespace fleetmap::bench
