#include "bench/extrapolation/bench_extrapolation_command.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "bench/extrapolation/extrapolation_experiment.hpp"
#include "bench/report/bench_command.hpp"
#include "bench/report/report_format.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"

namespace fleetmap::bench {
namespace {

using extrapolation::PredictionCheck;

std::string Ratio(int64_t a, int64_t b) {
  return b > 0 ? Fixed(static_cast<double>(a) / b, 3) : "n/a";
}

std::string Precision(const PredictionCheck& c) {
  return c.true_free + c.false_free > 0 ? Fixed(c.precision, 3) : "n/a";
}

struct Totals {
  int closed_doors = 0, doors_detected = 0, hinges = 0, door_fp = 0;
  int stairs_views = 0, stairs_detected = 0, stairs_fp = 0;
  int tracks = 0, sides = 0;
  int64_t observed_free = 0;
  double cell_area = 0;
  std::vector<PredictionCheck> stairs, doors, people, overall;
  std::vector<int64_t> door_cells, people_cells;
  std::vector<double> gain_sum;  // sum over scenes of door cells / observed free cells
};

Totals Sum(const std::vector<ExtrapolationSceneResult>& results, size_t thresholds) {
  Totals t;
  t.stairs.resize(thresholds), t.doors.resize(thresholds), t.people.resize(thresholds);
  t.overall.resize(thresholds), t.door_cells.resize(thresholds), t.people_cells.resize(thresholds);
  t.gain_sum.resize(thresholds);
  for (const ExtrapolationSceneResult& r : results) {
    t.closed_doors += r.closed_doors_viewed, t.doors_detected += r.doors_detected;
    t.hinges += r.hinges_correct, t.door_fp += r.door_false_positives;
    t.stairs_views += r.stairs_views, t.stairs_detected += r.stairs_detected;
    t.stairs_fp += r.stairs_false_positives, t.tracks += r.tracks;
    t.sides += r.dominant_sides_correct, t.observed_free += r.observed_free_cells;
    t.cell_area = r.cell_area;
    for (size_t k = 0; k < thresholds; ++k) {
      const ThresholdScores& s = r.scores[k];
      t.stairs[k] += s.stairs, t.doors[k] += s.doors, t.people[k] += s.people;
      t.overall[k] += s.stairs, t.overall[k] += s.doors, t.overall[k] += s.people;
      t.door_cells[k] += s.door_new_cells, t.people_cells[k] += s.people_new_cells;
      if (r.observed_free_cells > 0) {
        t.gain_sum[k] += static_cast<double>(s.door_new_cells) / r.observed_free_cells;
      }
    }
  }
  return t;
}

std::string Report(const BenchExtrapolationOptions& options,
                   const std::vector<ExtrapolationSceneResult>& results, double seconds) {
  const size_t n = options.p_th.size();
  const Totals t = Sum(results, n);
  std::ostringstream md;
  md << "# Map extrapolation on simulated indoor scenes\n\n"
     << "Command: `fleetmap bench extrapolation --scenes " << options.scenes << " --seed "
     << options.seed << "`  \nMachine: " << MachineDescription() << ", Release build.  \n"
     << "Wall time: " << Fixed(seconds, 1) << " s for " << results.size() << " scenes.\n\n";
  md << "## Detection recall (one RGB-D view per closed door, " << results.front().stairs_views
     << " per flight of stairs)\n\n"
     << "| entity | detected / views | recall | paper | false positives |\n|---|---|---|---|---|\n"
     << "| stairs | " << t.stairs_detected << " / " << t.stairs_views << " | "
     << Ratio(t.stairs_detected, t.stairs_views) << " | 0.95 | " << t.stairs_fp << " |\n"
     << "| doors (closed) | " << t.doors_detected << " / " << t.closed_doors << " | "
     << Ratio(t.doors_detected, t.closed_doors) << " | 0.67 | " << t.door_fp << " |\n\n"
     << "Hinge side right for " << t.hinges << " of " << t.doors_detected
     << " detected doors; dominant side inferred right for " << t.sides << " of " << t.tracks
     << " people's tracks.\n\n";
  md << "## Free-space precision TP / (TP + FP)\n\n| class |";
  for (double p : options.p_th) md << " p_th " << Fixed(p, 2) << " |";
  md << " paper (0.5 / 0.6 / 0.7) |\n|---|";
  for (size_t k = 0; k < n; ++k) md << "---|";
  md << "---|\n";
  auto row = [&](const char* name, const std::vector<PredictionCheck>& checks, const char* paper) {
    md << "| " << name << " |";
    for (const PredictionCheck& c : checks) {
      md << " " << Precision(c) << " (" << c.true_free + c.false_free << " cells) |";
    }
    md << " " << paper << " |\n";
  };
  row("static (stairs)", t.stairs, "0.91 / 0.93 / 0.93");
  row("quasi-static (doors)", t.doors, "0.98 / 0.99 / 0.99");
  row("dynamic (people)", t.people, "0.95 / 0.94 / 0.93");
  row("overall", t.overall, "0.95 / 0.95 / 0.95");
  md << "\n## Surface gained with closed doors\n\n"
     << "Predicted free area behind the detected closed doors (cells the local map did not know) "
        "over the observed free area.\n\n| p_th | predicted m2 | observed m2 | gain (total) | "
        "gain (mean per scene) | people m2 |\n|---|---|---|---|---|---|\n";
  for (size_t k = 0; k < n; ++k) {
    const double predicted = t.door_cells[k] * t.cell_area;
    const double observed = t.observed_free * t.cell_area;
    md << "| " << Fixed(options.p_th[k], 2) << " | " << Fixed(predicted, 1) << " | "
       << Fixed(observed, 1) << " | +"
       << Fixed(observed > 0 ? 100.0 * predicted / observed : 0.0, 1) << " % | +"
       << Fixed(100.0 * t.gain_sum[k] / std::max<size_t>(1, results.size()), 1) << " % | "
       << Fixed(t.people_cells[k] * t.cell_area, 1) << " |\n";
  }
  md << "\nPaper: up to +10 % at p_th 0.7 and +20 % at 0.5 with closed doors.\n";
  return md.str();
}

std::string ResultsCsv(const BenchExtrapolationOptions& options,
                       const std::vector<ExtrapolationSceneResult>& results) {
  std::ostringstream csv;
  csv << "seed,p_th,closed_doors,doors_detected,hinges_correct,door_fp,stairs_views,"
         "stairs_detected,stairs_fp,tracks,sides_correct,observed_free_cells,"
         "static_tp,static_fp,static_unobserved,doors_tp,doors_fp,doors_unobserved,people_tp,"
         "people_fp,people_unobserved,door_new_cells,people_new_cells\n";
  for (const ExtrapolationSceneResult& r : results) {
    for (size_t k = 0; k < options.p_th.size(); ++k) {
      const ThresholdScores& s = r.scores[k];
      csv << r.seed << "," << options.p_th[k] << "," << r.closed_doors_viewed << ","
          << r.doors_detected << "," << r.hinges_correct << "," << r.door_false_positives << ","
          << r.stairs_views << "," << r.stairs_detected << "," << r.stairs_false_positives << ","
          << r.tracks << "," << r.dominant_sides_correct << "," << r.observed_free_cells;
      for (const PredictionCheck* c : {&s.stairs, &s.doors, &s.people}) {
        csv << "," << c->true_free << "," << c->false_free << "," << c->unobserved;
      }
      csv << "," << s.door_new_cells << "," << s.people_new_cells << "\n";
    }
  }
  return csv.str();
}

nlohmann::json SummaryJson(const BenchExtrapolationOptions& options,
                           const std::vector<ExtrapolationSceneResult>& results, double seconds) {
  const size_t n = options.p_th.size();
  const Totals t = Sum(results, n);
  auto check = [](const PredictionCheck& c) {
    return nlohmann::json{{"true_free", c.true_free},
                          {"false_free", c.false_free},
                          {"unobserved", c.unobserved},
                          {"precision", c.true_free + c.false_free > 0 ? nlohmann::json(c.precision)
                                                                       : nlohmann::json(nullptr)}};
  };
  nlohmann::json thresholds = nlohmann::json::array();
  for (size_t k = 0; k < n; ++k) {
    const double observed = static_cast<double>(t.observed_free);
    thresholds.push_back(
        {{"p_th", options.p_th[k]},
         {"static", check(t.stairs[k])},
         {"quasi_static", check(t.doors[k])},
         {"dynamic", check(t.people[k])},
         {"overall", check(t.overall[k])},
         {"door_predicted_m2", t.door_cells[k] * t.cell_area},
         {"people_predicted_m2", t.people_cells[k] * t.cell_area},
         {"surface_gain", observed > 0 ? t.door_cells[k] / observed : 0.0},
         {"surface_gain_mean_per_scene", t.gain_sum[k] / std::max<size_t>(1, results.size())}});
  }
  return {
      {"scenes", results.size()},
      {"first_seed", options.seed},
      {"seconds", seconds},
      {"machine", MachineDescription()},
      {"recall",
       {{"stairs", t.stairs_views ? static_cast<double>(t.stairs_detected) / t.stairs_views : 0.0},
        {"stairs_views", t.stairs_views},
        {"stairs_false_positives", t.stairs_fp},
        {"doors", t.closed_doors ? static_cast<double>(t.doors_detected) / t.closed_doors : 0.0},
        {"closed_doors", t.closed_doors},
        {"door_false_positives", t.door_fp},
        {"hinges_correct", t.hinges},
        {"dominant_sides_correct", t.sides},
        {"tracks", t.tracks}}},
      {"observed_free_m2", t.observed_free * t.cell_area},
      {"thresholds", thresholds}};
}

}  // namespace

int RunBenchExtrapolation(const BenchExtrapolationOptions& options, std::ostream& out,
                          std::ostream& err) {
  const std::string prefix = "fleetmap bench extrapolation: ";
  if (options.scenes < 1 || options.scenes > 10000) {
    err << prefix << "--scenes: " << options.scenes << " must be in [1, 10000]\n";
    return cli::kExitBadInput;
  }
  if (options.p_th.empty() || static_cast<int>(options.p_th.size()) > kMaxThresholds) {
    err << prefix << "--pth: give 1 to " << kMaxThresholds << " thresholds\n";
    return cli::kExitBadInput;
  }
  for (double p : options.p_th) {
    if (!(p > 0.0 && p < 1.0)) {
      err << prefix << "--pth: " << p << " is not in (0, 1)\n";
      return cli::kExitBadInput;
    }
  }
  if (!options.out_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.out_dir, ec);
    if (ec) {
      err << prefix << "--out: " << options.out_dir << ": cannot create the directory\n";
      return cli::kExitBadInput;
    }
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<ExtrapolationSceneResult> results;
  for (int i = 0; i < options.scenes; ++i) {
    ExtrapolationSceneOptions scene;
    scene.seed = options.seed + static_cast<uint32_t>(i);
    scene.p_th = options.p_th;
    if (i == 0 && !options.out_dir.empty()) {
      scene.example_dir = options.out_dir + "/scene_" + std::to_string(scene.seed);
    }
    if (options.progress) {
      err << "\r" << prefix << "scene " << i + 1 << "/" << options.scenes << std::flush;
    }
    StatusOr<ExtrapolationSceneResult> result = RunExtrapolationScene(scene);
    if (!result.ok()) {
      err << "\n" << prefix << "seed " << scene.seed << ": " << result.status().message() << "\n";
      return cli::kExitBadInput;
    }
    results.push_back(std::move(result).value());
  }
  if (options.progress) err << "\n";
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string report = Report(options, results, seconds);
  out << report;
  if (!options.out_dir.empty()) {
    for (const auto& [path, contents] :
         {std::pair{options.out_dir + "/report.md", report},
          std::pair{options.out_dir + "/results.csv", ResultsCsv(options, results)},
          std::pair{options.out_dir + "/results.json",
                    SummaryJson(options, results, seconds).dump(2) + "\n"}}) {
      if (const Status written = WriteFileAtomically(path, contents); !written.ok()) {
        err << prefix << written.message() << "\n";
        return cli::kExitBadInput;
      }
    }
  }
  return cli::kExitOk;
}

void AddBenchExtrapolationCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<BenchExtrapolationOptions>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "extrapolation", "Map extrapolation on simulated indoor scenes (recall, precision, surface)");
  command->add_option("--out", options->out_dir, "output directory (report, CSV, JSON)");
  command->add_option("--scenes", options->scenes, "number of scenes")->capture_default_str();
  command->add_option("--seed", options->seed, "first scene seed")->capture_default_str();
  command->add_option("--pth", options->p_th, "thresholds in (0, 1), comma separated")
      ->delimiter(',')
      ->capture_default_str();
  command->add_flag("!--no-progress", options->progress, "no progress on stderr");
  command->callback(
      [options, exit_code] { *exit_code = RunBenchExtrapolation(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::bench
