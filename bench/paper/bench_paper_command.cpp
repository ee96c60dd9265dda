#include "bench/paper/bench_paper_command.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <thread>

#include "bench/bytes/tile_bytes_table.hpp"
#include "bench/paper/paper_experiment.hpp"
#include "bench/report/bar_chart.hpp"
#include "bench/report/bench_command.hpp"
#include "bench/report/report_format.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/progress_line.hpp"
#include "common/sim/terrain_generator.hpp"

namespace fleetmap::bench {
namespace {

constexpr double kKilo = 1024.0;  // KB in the report are KiB

std::string Kb(size_t bytes) { return Fixed(bytes / kKilo, 1); }

std::string Ratio(size_t a, size_t b) {
  return Fixed(static_cast<double>(a) / std::max<size_t>(1, b), 1);
}

std::string Pct(const std::optional<double>& value) {
  return value ? Fixed(*value, 2) : std::string("n/a");
}

std::string Name(const PaperTerrainResult& r) {
  return std::string(sim::TerrainKindName(r.kind)) + " " + Fixed(r.size, 0) + " m";
}

// A progress bar on one ProgressLine (rewritten in place on a terminal, a line every 10 s in a
// log); nothing when disabled.
class ProgressBar {
 public:
  ProgressBar(std::ostream& err, int total, bool enabled, bool terminal) : total_(total) {
    if (enabled) line_.emplace(err, ProgressLineOptions{.terminal = terminal});
  }

  void Show(int done, const std::string& what) {
    if (!line_) return;
    constexpr int kWidth = 30;
    const int filled = total_ > 0 ? done * kWidth / total_ : kWidth;
    line_->Update("[" + std::string(filled, '#') + std::string(kWidth - filled, '.') + "] " +
                  std::to_string(done) + "/" + std::to_string(total_) + " " + what);
  }
  void Finish() {
    if (line_) line_->Finish();
  }

 private:
  int total_;
  std::optional<ProgressLine> line_;
};

std::string ResultsCsv(const std::vector<PaperTerrainResult>& results) {
  std::ostringstream csv;
  csv << "kind,size_m,seed,width,height,scans,distance_m,explored,observed_free,"
         "P,PZ,P_zstd,P_png,V,VZ,V_zstd,V_obst,VZ_obst,V_obst_zstd,V_obst_one_tile,V_truth,"
         "vertices,"
         "segments";
  for (const char* map : {"grid", "vgrid", "vtruth"}) {
    for (const char* metric : {"ms", "cc", "pc", "opdf", "updf"}) {
      csv << "," << metric << "_" << map;
    }
  }
  csv << ",ms_gained";
  for (const char* from : {"free", "occ", "unk"}) {
    for (const char* to : {"free", "occ", "unk"}) {
      if (std::string(from) != to) csv << ",ms_lost_" << from << "_to_" << to;
    }
  }
  csv << ",seconds_explore,seconds_vectorize,seconds_total," << TileBytesCsvHeader() << "\n";
  auto opt = [](const std::optional<double>& v) { return v ? Fixed(*v, 4) : std::string(); };
  for (const PaperTerrainResult& r : results) {
    csv << sim::TerrainKindName(r.kind) << "," << Fixed(r.size, 0) << "," << r.seed << ","
        << r.width << "," << r.height << "," << r.scans << "," << Fixed(r.distance, 1) << ","
        << (r.explored ? 1 : 0) << "," << Fixed(r.observed_free, 4) << "," << r.grid.raw << ","
        << r.grid.gzip << "," << r.grid.zstd << "," << r.grid_png << "," << r.vmap.raw << ","
        << r.vmap.gzip << "," << r.vmap.zstd << "," << r.vmap_obstacles.raw << ","
        << r.vmap_obstacles.gzip << "," << r.vmap_obstacles.zstd << "," << r.vmap_obstacles_one_tile
        << "," << r.truth_vmap << "," << r.vertices << "," << r.segments;
    for (const metrics::QualityScores* q : {&r.robot, &r.robot_vector, &r.truth_vector}) {
      csv << "," << opt(q->map_score) << "," << opt(q->cross_correlation) << ","
          << opt(q->pearson_occupied) << "," << opt(q->occupied_picture_distance) << ","
          << opt(q->unoccupied_picture_distance);
    }
    csv << "," << r.gained;
    for (int from = 0; from < 3; ++from) {
      for (int to = 0; to < 3; ++to) {
        if (from != to) csv << "," << r.lost[from][to];
      }
    }
    csv << "," << Fixed(r.seconds_explore, 2) << "," << Fixed(r.seconds_vectorize, 3) << ","
        << Fixed(r.seconds_total, 2);
    for (const std::string& field : TileBytesCsvFields(r.tile_bytes)) csv << "," << field;
    csv << "\n";
  }
  return csv.str();
}

std::vector<std::optional<double>> Scores(const metrics::QualityScores& q) {
  return {q.map_score, q.cross_correlation, q.pearson_occupied, q.occupied_picture_distance,
          q.unoccupied_picture_distance};
}

// Largest drop (a - b) over the results for one metric index.
double WorstDrop(const std::vector<PaperTerrainResult>& results, int metric) {
  double worst = 0.0;
  for (const PaperTerrainResult& r : results) {
    const auto a = Scores(r.robot)[metric];
    const auto b = Scores(r.robot_vector)[metric];
    if (a && b) worst = std::max(worst, *a - *b);
  }
  return worst;
}

double MinScore(const std::vector<PaperTerrainResult>& results, int metric, bool vector) {
  double lowest = 100.0;
  for (const PaperTerrainResult& r : results) {
    const auto v = Scores(vector ? r.robot_vector : r.robot)[metric];
    if (v) lowest = std::min(lowest, *v);
  }
  return lowest;
}

std::string Report(const BenchPaperOptions& options, const std::vector<PaperTerrainResult>& results,
                   double seconds) {
  std::ostringstream md;
  md << "# The Vector Maps paper's experiment on simulated terrains\n\n"
     << "Command: `fleetmap bench paper --out " << options.out_dir << " --seed " << options.seed
     << " --sizes ";
  for (size_t i = 0; i < options.sizes.size(); ++i) {
    md << (i ? "," : "") << Fixed(options.sizes[i], 0);
  }
  md << "`  \nMachine: " << MachineDescription() << ", Release build.  \n"
     << "Wall time: " << Fixed(seconds, 1) << " s for " << results.size() << " terrains.  \n"
     << "Resolution " << options.resolution << " m; laser " << options.laser_fov_deg << " deg, "
     << options.laser_step_deg << " deg steps, " << options.laser_range << " m; SLAM error model "
     << (options.slam_error ? "on" : "off") << (options.line_refit ? "" : "; line refit off")
     << ". KB = 1024 bytes.\n\n"
     << "P: robot grid, one byte per cell; PZ: gzip -9 of P; V: .vmap bytes "
        "(EncodeVmap(VectorizeTiled(robot grid)), obstacles and free space); VZ: gzip -9 of V; V "
        "obst, "
        "VZ obst: the same tiles without their free-space polygons (obstacles only, like the "
        "paper's vector map); V obst one tile: obstacles only with the whole terrain as one tile, "
        "one file like the paper's (10 m tiles are what the fleet sends: per-tile headers and "
        "seams); zstd: level 19. Per fleet tile (the honest baselines): the robot grid cut into "
        "the fleet's 10 m tiles (all-unknown tiles left out, as the vector wire leaves them), "
        "each tile alone as a map_msgs/OccupancyGridUpdate sample (patch CDR) or its cells "
        "compressed alone (zstd -3, zstd -19, LZ4 block), against V's tiles as the VectorTile "
        "samples an agent publishes (vector tiles). Quality "
        "metrics (ALGORITHMS.md 1.1, %) against the ground truth of (a) the robot grid, (b) the "
        "vector map of the robot grid rasterized back, (c) the vector map of the ground truth "
        "rasterized back.\n\n";

  md << "## Sizes\n\n| terrain | cells | scans | driven m | explored | observed free | P KB | PZ "
        "KB "
        "| P zstd KB | V KB | VZ KB | V zstd KB | V obst KB | VZ obst KB | P / V | P / V obst | PZ "
        "/ VZ "
        "| PZ / VZ obst | vertices | time s |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const PaperTerrainResult& r : results) {
    md << "| " << Name(r) << " | " << r.width << " x " << r.height << " | " << r.scans << " | "
       << Fixed(r.distance, 0) << " | " << (r.explored ? "yes" : "budget") << " | "
       << Fixed(100.0 * r.observed_free, 1) << " % | " << Kb(r.grid.raw) << " | " << Kb(r.grid.gzip)
       << " | " << Kb(r.grid.zstd) << " | " << Kb(r.vmap.raw) << " | " << Kb(r.vmap.gzip) << " | "
       << Kb(r.vmap.zstd) << " | " << Kb(r.vmap_obstacles.raw) << " | " << Kb(r.vmap_obstacles.gzip)
       << " | " << Ratio(r.grid.raw, r.vmap.raw) << " | " << Ratio(r.grid.raw, r.vmap_obstacles.raw)
       << " | " << Ratio(r.grid.gzip, r.vmap.gzip) << " | "
       << Ratio(r.grid.gzip, r.vmap_obstacles.gzip) << " | " << r.vertices << " | "
       << Fixed(r.seconds_total, 1) << " |\n";
  }
  md << "\nAverages per size (the paper's Fig. 4a; paper at 80 m: P 2532.4 KB, V 39.2 KB, 65x, "
        "obstacles only in one file: compare P / V obst one tile):\n\n"
     << "| size | P KB | PZ KB | V KB | VZ KB | V obst KB | VZ obst KB | V obst one tile KB | "
        "P / V | P / V obst | P / V obst one tile | PZ / VZ | PZ / VZ obst | "
        "grid tiles zstd -19 KB | vector tiles KB | vector tiles / smallest tile baseline |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (double size : options.sizes) {
    double p = 0, pz = 0, v = 0, vz = 0, vo = 0, vzo = 0, vo1 = 0;
    TileBytesComparison tiles;
    int n = 0;
    for (const PaperTerrainResult& r : results) {
      if (r.size != size) continue;
      p += r.grid.raw;
      pz += r.grid.gzip;
      v += r.vmap.raw;
      vz += r.vmap.gzip;
      vo += r.vmap_obstacles.raw;
      vzo += r.vmap_obstacles.gzip;
      vo1 += r.vmap_obstacles_one_tile;
      tiles += r.tile_bytes;
      ++n;
    }
    if (n == 0) continue;
    auto ratio = [](double a, double b) { return Fixed(b > 0 ? a / b : 0.0, 1); };
    md << "| " << Fixed(size, 0) << " m | " << Fixed(p / n / kKilo, 1) << " | "
       << Fixed(pz / n / kKilo, 1) << " | " << Fixed(v / n / kKilo, 1) << " | "
       << Fixed(vz / n / kKilo, 1) << " | " << Fixed(vo / n / kKilo, 1) << " | "
       << Fixed(vzo / n / kKilo, 1) << " | " << Fixed(vo1 / n / kKilo, 1) << " | " << ratio(p, v)
       << " | " << ratio(p, vo) << " | " << ratio(p, vo1) << " | " << ratio(pz, vz) << " | "
       << ratio(pz, vzo) << " | "
       << Fixed(static_cast<double>(tiles.grid.bytes.zstd19) / n / kKilo, 1) << " | "
       << Fixed(static_cast<double>(tiles.vector.payload) / n / kKilo, 1) << " | "
       << Fixed(tiles.RatioToSmallest().ratio, 2) << " (" << tiles.RatioToSmallest().baseline
       << ") |\n";
  }

  md << "\n### Bytes per fleet tile, each tile alone (the honest baselines)\n\n"
     << "P and PZ compress the whole grid in one piece, which no wire sends: the fleet sends "
        "10 m tiles. The same tiles of the robot grid, each alone, against V's tiles:\n\n";
  std::vector<NamedComparison> tile_rows;
  for (const PaperTerrainResult& r : results) tile_rows.push_back({Name(r), r.tile_bytes});
  if (!tile_rows.empty()) PrintTileBytesTable(tile_rows, "terrain", md);

  md << "\n## Quality (%): (a) grid / (b) vector of grid / (c) vector of truth\n\n"
     << "| terrain | MS | CC | PC | OPDF | UPDF |\n|---|---|---|---|---|---|\n";
  for (const PaperTerrainResult& r : results) {
    md << "| " << Name(r);
    const auto a = Scores(r.robot), b = Scores(r.robot_vector), c = Scores(r.truth_vector);
    for (int m = 0; m < 5; ++m) {
      md << " | " << Pct(a[m]) << " / " << Pct(b[m]) << " / " << Pct(c[m]);
    }
    md << " |\n";
  }
  md << "\nLowest robot-grid score: MS " << Fixed(MinScore(results, 0, false), 2) << ", OPDF "
     << Fixed(MinScore(results, 3, false), 2) << ", UPDF " << Fixed(MinScore(results, 4, false), 2)
     << ". Lowest vector-of-grid score: MS " << Fixed(MinScore(results, 0, true), 2) << ", OPDF "
     << Fixed(MinScore(results, 3, true), 2) << ", UPDF " << Fixed(MinScore(results, 4, true), 2)
     << ".  \nLargest loss by vectorizing (a - b, percentage points): MS "
     << Fixed(WorstDrop(results, 0), 2) << ", CC " << Fixed(WorstDrop(results, 1), 2) << ", PC "
     << Fixed(WorstDrop(results, 2), 2) << ", OPDF " << Fixed(WorstDrop(results, 3), 2) << ", UPDF "
     << Fixed(WorstDrop(results, 4), 2) << ".\n\n"
     << "MS by vectorizing, in cells: lost = the robot grid equals the truth and its vector map "
        "does not, by (grid state -> rasterized state); gained = the reverse. MS(a) - MS(b) = "
        "100 * (lost - gained) / cells.\n\n"
     << "| terrain | MS a - b | gained | lost | occ -> free | occ -> unk | free -> occ | "
        "free -> unk | unk -> occ | unk -> free |\n|---|---|---|---|---|---|---|---|---|---|\n";
  // grid::CellState order: kFree, kOccupied, kUnknown.
  constexpr int kF = 0, kO = 1, kU = 2;
  for (const PaperTerrainResult& r : results) {
    int64_t lost = 0;
    for (const auto& row : r.lost) {
      for (const int64_t count : row) lost += count;
    }
    const auto ms_a = r.robot.map_score, ms_b = r.robot_vector.map_score;
    md << "| " << Name(r) << " | " << (ms_a && ms_b ? Fixed(*ms_a - *ms_b, 2) : "n/a") << " | "
       << r.gained << " | " << lost << " | " << r.lost[kO][kF] << " | " << r.lost[kO][kU] << " | "
       << r.lost[kF][kO] << " | " << r.lost[kF][kU] << " | " << r.lost[kU][kO] << " | "
       << r.lost[kU][kF] << " |\n";
  }
  md << "\nCharts: sizes.png, quality_<kind>_<size>.png. Maps: maps/<kind>_<size>_{truth,robot,"
        "robot_vector,truth_vector}.png and the robot map as maps/<kind>_<size>_robot.yaml.\n";
  return md.str();
}

Status WriteCharts(const BenchPaperOptions& options,
                   const std::vector<PaperTerrainResult>& results) {
  BarChart sizes;
  sizes.title = "Map sizes, average over the terrain kinds (log scale)";
  sizes.y_label = "KB";
  sizes.series = {"P", "PZ", "V", "VZ"};
  sizes.log_scale = true;
  for (double size : options.sizes) {
    double p = 0, pz = 0, v = 0, vz = 0;
    int n = 0;
    for (const PaperTerrainResult& r : results) {
      if (r.size != size) continue;
      p += r.grid.raw, pz += r.grid.gzip, v += r.vmap.raw, vz += r.vmap.gzip, ++n;
    }
    if (n == 0) continue;
    sizes.groups.push_back(Fixed(size, 0) + " m");
    sizes.values.push_back({p / n / kKilo, pz / n / kKilo, v / n / kKilo, vz / n / kKilo});
  }
  FLEETMAP_RETURN_IF_ERROR(WriteBarChartPng(sizes, options.out_dir + "/sizes.png"));
  for (const PaperTerrainResult& r : results) {
    BarChart quality;
    quality.title = "Quality vs ground truth: " + Name(r);
    quality.y_label = "%";
    quality.series = {"grid", "vector(grid)", "vector(truth)"};
    quality.groups = {"MS", "CC", "PC", "OPDF", "UPDF"};
    quality.y_max = 100.0;
    const auto a = Scores(r.robot), b = Scores(r.robot_vector), c = Scores(r.truth_vector);
    for (int m = 0; m < 5; ++m) quality.values.push_back({a[m], b[m], c[m]});
    FLEETMAP_RETURN_IF_ERROR(WriteBarChartPng(
        quality, options.out_dir + "/quality_" + std::string(sim::TerrainKindName(r.kind)) + "_" +
                     Fixed(r.size, 0) + ".png"));
  }
  return Status::Ok();
}

}  // namespace

int RunBenchPaper(const BenchPaperOptions& options, std::ostream& out, std::ostream& err) {
  const std::string prefix = "fleetmap bench paper: ";
  std::vector<sim::TerrainKind> kinds;
  for (const std::string& name : options.kinds) {
    const std::optional<sim::TerrainKind> kind = sim::TerrainKindFromName(name);
    if (!kind) {
      err << prefix << "--kinds: '" << name << "' is unknown: use maze, office or unstructured\n";
      return cli::kExitBadInput;
    }
    kinds.push_back(*kind);
  }
  if (options.sizes.empty()) {
    err << prefix << "--sizes: give at least one size\n";
    return cli::kExitBadInput;
  }
  for (double size : options.sizes) {
    if (!(size >= sim::kMinTerrainSize && size <= sim::kMaxTerrainSize)) {
      err << prefix << "--sizes: " << size << " m is out of bounds: sizes must be in ["
          << sim::kMinTerrainSize << ", " << sim::kMaxTerrainSize << "] m\n";
      return cli::kExitBadInput;
    }
  }
  if (!(options.resolution > 0.0) || !std::isfinite(options.resolution)) {
    err << prefix << "--resolution: " << options.resolution << " m is invalid: it must be > 0\n";
    return cli::kExitBadInput;
  }
  if (!(options.laser_fov_deg > 0.0 && options.laser_fov_deg <= 360.0)) {
    err << prefix << "--laser-fov: " << options.laser_fov_deg
        << " deg gives a laser with no rays: it must be in (0, 360]\n";
    return cli::kExitBadInput;
  }
  if (!(options.laser_step_deg > 0.0) || !std::isfinite(options.laser_step_deg)) {
    err << prefix << "--laser-step: " << options.laser_step_deg
        << " deg gives a laser with no rays: it must be > 0\n";
    return cli::kExitBadInput;
  }
  PaperTerrainOptions base;
  base.resolution = options.resolution;
  base.exploration.laser.field_of_view = options.laser_fov_deg * std::numbers::pi / 180.0;
  base.exploration.laser.angular_step = options.laser_step_deg * std::numbers::pi / 180.0;
  base.exploration.laser.max_range = options.laser_range;
  base.exploration.error.enabled = options.slam_error;
  base.line_refit = options.line_refit;
  if (const auto check = sim::ExplorationSimulator::Create(base.exploration); !check.ok()) {
    err << prefix << "--laser-range / --laser-step: " << check.status().message() << "\n";
    return cli::kExitBadInput;
  }
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir + "/maps", ec);
  if (ec) {
    err << prefix << "--out: " << options.out_dir
        << ": cannot create the directory: " << ec.message() << "\n";
    return cli::kExitBadInput;
  }

  const auto start = std::chrono::steady_clock::now();
  const int total = static_cast<int>(options.sizes.size() * kinds.size());
  ProgressBar bar(err, total, options.progress, options.err_is_terminal);
  std::vector<PaperTerrainResult> results;
  for (double size : options.sizes) {
    for (sim::TerrainKind kind : kinds) {
      PaperTerrainOptions terrain = base;
      terrain.kind = kind;
      terrain.size = size;
      terrain.seed = options.seed;
      terrain.image_dir = options.out_dir + "/maps";
      const std::string name =
          std::string(sim::TerrainKindName(kind)) + " " + Fixed(size, 0) + " m";
      const int done = static_cast<int>(results.size());
      const StatusOr<PaperTerrainResult> result = RunPaperTerrain(
          terrain, [&](const std::string& stage) { bar.Show(done, name + ": " + stage); });
      if (!result.ok()) {
        bar.Finish();
        err << prefix << name << ": " << result.status().message() << "\n";
        return cli::kExitBadInput;
      }
      results.push_back(*result);
      bar.Show(static_cast<int>(results.size()), name + ": done");
    }
  }
  bar.Finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string report = Report(options, results, seconds);
  for (const auto& [path, contents] :
       {std::pair{options.out_dir + "/results.csv", ResultsCsv(results)},
        std::pair{options.out_dir + "/report.md", report}}) {
    if (const Status written = WriteFileAtomically(path, contents); !written.ok()) {
      err << prefix << written.message() << "\n";
      return cli::kExitBadInput;
    }
  }
  if (const Status charts = WriteCharts(options, results); !charts.ok()) {
    err << prefix << charts.message() << "\n";
    return cli::kExitBadInput;
  }
  out << report;
  return cli::kExitOk;
}

void AddBenchPaperCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<BenchPaperOptions>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "paper", "The Vector Maps paper's experiment on simulated terrains (report, CSV, charts)");
  command->add_option("--out", options->out_dir, "output directory")->required();
  command->add_option("--seed", options->seed, "terrain and robot seed")->capture_default_str();
  command->add_option("--sizes", options->sizes, "terrain sizes (m), comma separated")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--kinds", options->kinds, "terrain kinds, comma separated")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--resolution", options->resolution, "grid cell size (m)")
      ->capture_default_str();
  command->add_option("--laser-fov", options->laser_fov_deg, "laser field of view (deg)")
      ->capture_default_str();
  command->add_option("--laser-step", options->laser_step_deg, "laser angular step (deg)")
      ->capture_default_str();
  command->add_option("--laser-range", options->laser_range, "laser range (m)")
      ->capture_default_str();
  command->add_flag("!--no-slam-error", options->slam_error, "map with the true poses");
  command->add_flag("!--no-line-refit", options->line_refit,
                    "vectorize without moving centre lines off the cell centres");
  command->add_flag("!--no-progress", options->progress, "no progress bar on stderr");
  command->callback([options, exit_code] {
    options->err_is_terminal = ProgressLine::StderrIsTerminal();
    *exit_code = RunBenchPaper(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::bench
