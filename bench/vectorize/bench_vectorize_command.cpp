#include "bench/vectorize/bench_vectorize_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "bench/bytes/grid_tile_bytes.hpp"
#include "bench/bytes/tile_compression.hpp"
#include "bench/report/bench_command.hpp"
#include "bench/report/map_files.hpp"
#include "bench/vectorize/vectorize_bench_report.hpp"
#include "cli/inputs/command_inputs.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"

namespace fleetmap::bench {
namespace {

// The dictionary baseline's dictionaries: for each map, one trained on the grid tiles of the
// other maps, never on its own (a fleet ships its dictionary before it maps a new building).
// Empty, with the reason on `err`, when they cannot be trained (one map, too few tiles): then no
// map is measured against a dictionary, so that the sums compare like with like.
std::map<std::string, ZstdDictionary> LeaveOneOutDictionaries(const std::vector<std::string>& files,
                                                              const VectorizeBenchOptions& options,
                                                              std::ostream& err) {
  std::map<std::string, std::vector<std::vector<uint8_t>>> samples;
  for (const std::string& file : files) {
    StatusOr<grid::LoadedMap> loaded = cli::LoadGridInput(file, options.max_cells);
    if (!loaded.ok() || !cli::CheckAxisAligned(file, loaded->grid).ok()) continue;  // named later
    StatusOr<std::vector<std::vector<uint8_t>>> tiles =
        GridTileSamples(loaded->grid, Transform2::Identity(), options.tile_size);
    if (tiles.ok()) samples[file] = std::move(tiles).value();
  }
  std::map<std::string, ZstdDictionary> dictionaries;
  for (const auto& [file, own] : samples) {
    std::vector<std::vector<uint8_t>> others;
    for (const auto& [other, tiles] : samples) {
      if (other != file) others.insert(others.end(), tiles.begin(), tiles.end());
    }
    err << "training the grid dictionary for " << std::filesystem::path(file).stem().string()
        << " on " << others.size() << " tiles of the other maps\n";
    StatusOr<ZstdDictionary> dictionary = ZstdDictionary::Train(others);
    if (!dictionary.ok()) {
      err << "no dictionary baseline: " << dictionary.status().message() << "\n";
      return {};
    }
    dictionaries.emplace(file, std::move(dictionary).value());
  }
  return dictionaries;
}

}  // namespace

int RunBenchVectorize(const BenchVectorizeCommandOptions& options, std::ostream& out,
                      std::ostream& err) {
  auto fail = [&err](const std::string& message) {
    err << "fleetmap bench vectorize: " << message << "\n";
    return cli::kExitBadInput;
  };
  if (options.bench.runs < kMinBenchRuns) {
    return fail("--runs must be >= " + std::to_string(kMinBenchRuns) + ", got " +
                std::to_string(options.bench.runs));
  }
  if (Status s = cli::CheckPositiveFinite("--tile-size", options.bench.tile_size); !s.ok()) {
    return fail(s.message());
  }
  StatusOr<std::vector<std::string>> files = MapFilesIn(options.maps_dir);
  if (!files.ok()) return fail(files.status().message());
  // One thread: the comparison is per core, and OpenCV would otherwise use its pool.
  cv::setNumThreads(1);

  // A map that cannot be measured (unreadable, corrupt, too large) is named and skipped: the
  // others are still measured and reported, and the exit code says that one was not.
  const std::map<std::string, ZstdDictionary> dictionaries =
      LeaveOneOutDictionaries(*files, options.bench, err);
  std::vector<VectorizeBenchRow> rows;
  size_t skipped = 0;
  for (const std::string& file : *files) {
    err << "measuring " << file << "\n";
    VectorizeBenchOptions bench = options.bench;
    const auto dictionary = dictionaries.find(file);
    bench.grid_dictionary = dictionary == dictionaries.end() ? nullptr : &dictionary->second;
    StatusOr<VectorizeBenchRow> row = MeasureVectorizeBench(file, bench);
    if (!row.ok()) {
      fail(row.status().message() + " (skipped)");
      ++skipped;
      continue;
    }
    rows.push_back(std::move(row).value());
  }
  if (rows.empty()) return fail(options.maps_dir + ": no map could be measured");
  const std::vector<BenchTarget> targets = EvaluateVectorizeTargets(rows);
  PrintVectorizeBenchTables(rows, out);
  PrintVectorizeTargets(targets, out);
  if (!options.json_path.empty()) {
    const std::string json = VectorizeBenchJson(rows, targets, options.bench).dump(2) + "\n";
    if (Status s = WriteFileAtomically(options.json_path, json); !s.ok()) return fail(s.message());
  }
  if (!options.csv_path.empty()) {
    if (Status s = WriteFileAtomically(options.csv_path, VectorizeBenchCsv(rows)); !s.ok()) {
      return fail(s.message());
    }
  }
  out.flush();
  if (skipped > 0) {
    return fail(std::to_string(skipped) + " of " + std::to_string(files->size()) +
                " maps skipped, see above");
  }
  return out ? cli::kExitOk : cli::kExitBadInput;
}

void AddBenchVectorizeCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<BenchVectorizeCommandOptions>();
  CLI::App* cmd = BenchCommand(app)->add_subcommand(
      "vectorize", "Ours and the paper's vectorizer against OpenCV on every map of a directory");
  cmd->add_option("--maps", options->maps_dir, "Directory of map_server YAML files")->required();
  cmd->add_option("--json", options->json_path, "Write the figures as JSON here");
  cmd->add_option("--csv", options->csv_path, "Write the figures as CSV here");
  cmd->add_option("--runs", options->bench.runs, "Timings are medians of N runs (N >= 5)")
      ->capture_default_str();
  cmd->add_option("--tile-size", options->bench.tile_size, "Tile side in metres")
      ->capture_default_str();
  cmd->add_option("--max-cells", options->bench.max_cells, "Refuse grids with more cells")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("!--no-line-refit", options->bench.line_refit,
                "Vectorize without moving centre lines off the cell centres");
  cmd->callback(
      [options, exit_code]() { *exit_code = RunBenchVectorize(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::bench
