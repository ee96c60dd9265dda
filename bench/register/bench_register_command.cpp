#include "bench/register/bench_register_command.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <sstream>
#include <vector>

#include "bench/register/growing_experiment.hpp"
#include "bench/register/register_experiment.hpp"
#include "bench/report/bench_command.hpp"
#include "bench/report/report_format.hpp"
#include "cli/inputs/command_inputs.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/core/progress_line.hpp"
#include "common/registration/confidence_calibration.hpp"

namespace fleetmap::bench {
namespace {

StatusOr<std::vector<SourceMap>> LoadMapsDir(const std::string& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    return InvalidArgumentError("--maps " + dir + " is not a directory");
  }
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.path().extension() == ".yaml") paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  std::vector<SourceMap> maps;
  for (const std::string& path : paths) {
    FLEETMAP_ASSIGN_OR_RETURN(grid::LoadedMap loaded,
                              cli::LoadGridInput(path, cli::kDefaultMaxCells));
    maps.push_back({std::filesystem::path(path).stem().string(), std::move(loaded.grid)});
  }
  if (maps.empty()) return InvalidArgumentError("--maps " + dir + " holds no .yaml map");
  return maps;
}

std::string OverlapLabel(double target) {
  return target < 0.0 ? "all" : FormatDouble("%.0f %%", 100.0 * target);
}

std::string Percent(int count, int of) {
  return of > 0 ? FormatDouble("%.1f", 100.0 * count / of) : "-";
}

nlohmann::json ToJson(const MethodSummary& s) {
  return {{"pairs", s.pairs},
          {"found", s.found},
          {"successes", s.successes},
          {"false_accepts", s.false_accepts},
          {"success_percent", s.success_percent()},
          {"false_accept_percent", s.false_accept_percent()},
          {"median_seconds", s.median_seconds},
          {"worst_seconds", s.worst_seconds}};
}

nlohmann::json ToJson(const MethodOutcome& o) {
  return {{"found", o.found},
          {"success", o.success},
          {"right", o.right},
          {"translation_error_cells", o.translation_error_cells},
          {"yaw_error_deg", o.yaw_error_deg},
          {"seconds", o.seconds},
          {"confidence", o.confidence},
          {"score", o.score},
          {"why_not", o.why_not},
          {"agreeing_cells", o.agreeing_cells},
          {"contradicting_cells", o.contradicting_cells},
          {"peak_ratio", o.peak_ratio},
          {"right_finalist", o.right_finalist}};
}

std::string RuleCells(const RuleSummary& rule, int pairs) {
  return Percent(rule.placed, pairs) + " | " + std::to_string(rule.wrong) + " | " +
         (rule.placed > 0 ? Fixed(rule.mean_step, 2) : std::string("-"));
}

// `--growing N`: the placer's sequential test on growing maps (growing_experiment.hpp).
int ReportGrowing(const BenchRegisterOptions& options, const RegisterBenchOptions& pairs,
                  const std::vector<SourceMap>& maps, ProgressLine* progress, std::ostream& out,
                  std::ostream& err) {
  GrowingBenchOptions growing;
  growing.pairs = pairs;
  growing.steps = options.growing_steps;
  const GrowingBenchRun run = RunGrowingBench(maps, growing, progress);
  const auto& rule = growing.sequential;
  out << "The sequential test on growing maps: " << run.pairs.size() << " pairs from "
      << maps.size() << " source maps (" << options.pairs_per_overlap
      << " per map and overlap, seed " << options.seed << ")";
  if (run.not_generated > 0) out << ", " << run.not_generated << " could not be generated";
  out << ". B grows in " << growing.steps << " steps (after 1/" << growing.steps << ", 2/"
      << growing.steps
      << ", ... of its drive), each registered on A and fed to the placer's PlacementEvidence. "
         "Bar only: placed when "
      << growing.bar_only.confirmations << " registrations in a row find the same placement at "
      << Fixed(pairs.registration.min_confidence, 2) << ". Sequential: also when "
      << rule.sequential_wins << " registrations in a row of the grown map find it verified at "
      << Fixed(rule.sequential_confidence, 2) << " or more. Wrong: placed more than "
      << Fixed(pairs.max_translation_cells, 0) << " cells or " << Fixed(pairs.max_yaw_deg, 0)
      << " deg off. " << MachineDescription()
      << ".\n\n"
         "| pairs from | pairs | bar only: placed | wrong | mean step | sequential: placed | "
         "wrong | mean step |\n|---|---|---|---|---|---|---|---|\n";
  for (const GrowingSummaryRow& row : SummarizeGrowing(run.pairs)) {
    out << "| " << (row.group.empty() ? "every pair" : row.group) << " | " << row.pairs << " | "
        << RuleCells(row.bar_only, row.pairs) << " | " << RuleCells(row.sequential, row.pairs)
        << " |\n";
  }
  std::vector<double> seconds;
  for (const GrowingPairOutcome& p : run.pairs) {
    seconds.insert(seconds.end(), p.seconds.begin(), p.seconds.end());
  }
  out << "\nMedian registration " << Fixed(Median(seconds), 3) << " s over " << seconds.size()
      << ".\n";
  if (!options.csv_path.empty()) {
    std::ostringstream csv;
    csv << "map,group,target_overlap,step,confidence,verified,right,error_cells,score,overlap,"
           "peak_ratio,bar_only_placed_at,bar_only_right,sequential_placed_at,sequential_right\n";
    for (const GrowingPairOutcome& p : run.pairs) {
      for (size_t k = 0; k < p.confidence.size(); ++k) {
        csv << p.map << "," << p.group << "," << Fixed(p.target_overlap, 2) << "," << k + 1 << ","
            << Fixed(p.confidence[k], 4) << "," << int{p.verified[k]} << "," << int{p.right[k]}
            << "," << Fixed(p.error_cells[k], 2) << "," << Fixed(p.score[k], 4) << ","
            << Fixed(p.overlap[k], 3) << "," << Fixed(p.peak_ratio[k], 3) << ","
            << p.bar_only.placed_at << "," << p.bar_only.right << "," << p.sequential.placed_at
            << "," << p.sequential.right << "\n";
      }
    }
    if (const Status written = WriteFileAtomically(options.csv_path, csv.str()); !written.ok()) {
      err << "fleetmap bench register: " << written.message() << "\n";
      return cli::kExitBadInput;
    }
  }
  return cli::kExitOk;
}

}  // namespace

int RunBenchRegister(const BenchRegisterOptions& options, std::ostream& out, std::ostream& err) {
  if (options.pairs_per_overlap < 1 || options.pairs_per_overlap > 1000) {
    err << "fleetmap bench register: --pairs-per-overlap " << options.pairs_per_overlap
        << " must be in [1, 1000]\n";
    return cli::kExitBadInput;
  }
  if (options.growing_steps != 0 && (options.growing_steps < 2 || options.growing_steps > 20)) {
    err << "fleetmap bench register: --growing " << options.growing_steps
        << " must be in [2, 20] (steps of B's growth)\n";
    return cli::kExitBadInput;
  }
  if (options.synthetic_maps < 0 || options.synthetic_maps > 200) {
    err << "fleetmap bench register: --synthetic " << options.synthetic_maps
        << " must be in [0, 200]\n";
    return cli::kExitBadInput;
  }
  if (options.repeated_maps < 0 || options.repeated_maps > 60) {
    err << "fleetmap bench register: --repeated " << options.repeated_maps
        << " must be in [0, 60]\n";
    return cli::kExitBadInput;
  }
  if ((options.synthetic_maps > 0) == !options.maps_dir.empty()) {
    err << "fleetmap bench register: give either --maps DIR or --synthetic K\n";
    return cli::kExitBadInput;
  }
  StatusOr<std::vector<SourceMap>> maps =
      options.synthetic_maps > 0 ? SyntheticSourceMaps(options.synthetic_maps, options.seed)
                                 : LoadMapsDir(options.maps_dir);
  if (maps.ok() && options.synthetic_maps == 0 && options.repeated_maps > 0) {
    StatusOr<std::vector<SourceMap>> repeated =
        RepeatedSourceMaps(options.repeated_maps, options.seed);
    if (repeated.ok()) {
      for (SourceMap& map : *repeated) maps->push_back(std::move(map));
    } else {
      maps = repeated.status();
    }
  }
  if (!maps.ok()) {
    err << "fleetmap bench register: " << maps.status().message() << "\n";
    return cli::kExitBadInput;
  }
  // One core for both methods (OpenCV would otherwise spread AKAZE and the field over threads).
  cv::setNumThreads(1);
  RegisterBenchOptions bench_options;
  bench_options.pairs_per_overlap = options.pairs_per_overlap;
  bench_options.seed = options.seed;
  bench_options.run_mexplore = !options.skip_mexplore;
  bench_options.drift = !options.no_drift;
  bench_options.registration.max_drift_per_m = options.max_drift_per_m;
  bench_options.pairs.wall_noise = options.wall_noise;
  ProgressLine progress(err, {.terminal = options.err_is_terminal});
  if (options.growing_steps > 0) {
    return ReportGrowing(options, bench_options, *maps, &progress, out, err);
  }
  const RegisterBenchRun run = RunRegisterBench(*maps, bench_options, &progress);
  const std::vector<SummaryRow> rows = Summarize(run.pairs);
  const std::vector<ReliabilityBin> bins = Reliability(run.pairs);

  std::string source = std::to_string(options.synthetic_maps);
  if (options.synthetic_maps > 0) {
    source += " synthetic terrains (office, maze, unstructured, warehouse, office rows, corridors)";
  } else {
    source = std::to_string(maps->size() - static_cast<size_t>(options.repeated_maps));
    source.append(" maps in ").append(options.maps_dir);
    if (options.repeated_maps > 0) {
      source.append(" and ")
          .append(std::to_string(options.repeated_maps))
          .append(" repeated-structure terrains");
    }
  }
  if (bench_options.drift) {
    source.append(", each pair also with B drifted (scale up to ")
        .append(Fixed(100.0 * bench_options.drift_options.max_scale, 0))
        .append(" %, bend up to ")
        .append(Fixed(bench_options.drift_options.max_bend_deg_per_m, 2))
        .append(" deg/m), drifted pairs judged where they overlap A");
  }
  source.append(bench_options.registration.max_drift_per_m > 0.0
                    ? "; fleetmap verifies allowing drift up to " +
                          Fixed(100.0 * bench_options.registration.max_drift_per_m, 1) +
                          " cm per metre"
                    : "; fleetmap verifies rigidly (--max-drift-per-m 0)");
  if (options.wall_noise > 0.0) {
    source.append("; each map's wall faces moved apart with probability " +
                  Fixed(options.wall_noise, 2) + " (--wall-noise)");
  }
  out << "Map registration, " << source << ", " << options.pairs_per_overlap
      << " pairs per map and overlap (seed " << options.seed << "): " << run.pairs.size()
      << " pairs";
  if (run.not_generated > 0) out << " (" << run.not_generated << " could not be generated)";
  out << ". Success: within " << Fixed(bench_options.max_translation_cells, 0)
      << " cells at B's known centroid and " << Fixed(bench_options.max_yaw_deg, 0)
      << " deg; found: confidence at least the placement bar "
      << Fixed(bench_options.registration.min_confidence, 2)
      << " (the server's) and verified; false accept: found but not a success (% of pairs). "
      << MachineDescription() << ".\n\n";
  out << "| pairs from | overlap | pairs | achieved | fleetmap success % | fleetmap false accepts "
         "% | "
         "fleetmap median s | fleetmap worst s | m-explore success % | m-explore false accepts % | "
         "m-explore median s | m-explore worst s |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SummaryRow& row : rows) {
    out << "| " << (row.group.empty() ? "every pair" : row.group) << " | "
        << OverlapLabel(row.target_overlap) << " | " << row.fleetmap.pairs << " | "
        << FormatDouble("%.0f %%", 100.0 * row.mean_overlap);
    for (const MethodSummary* s : {&row.fleetmap, &row.mexplore}) {
      if (options.skip_mexplore && s == &row.mexplore) {
        out << " | - | - | - | -";
        continue;
      }
      out << " | " << Percent(s->successes, s->pairs) << " | "
          << Percent(s->false_accepts, s->pairs) << " | " << Fixed(s->median_seconds, 3) << " | "
          << Fixed(s->worst_seconds, 3);
    }
    out << " |\n";
  }
  out << "\nReliability of fleetmap's confidence (found pairs):\n\n"
         "| confidence | found | correct | fraction correct | mean confidence |\n"
         "|---|---|---|---|---|\n";
  for (const ReliabilityBin& b : bins) {
    out << "| " << Fixed(b.lo, 2) << " - " << Fixed(b.hi, 2) << " | " << b.found << " | "
        << b.correct << " | "
        << (b.found > 0 ? Fixed(static_cast<double>(b.correct) / b.found, 3) : std::string("-"))
        << " | " << (b.found > 0 ? Fixed(b.mean_confidence, 3) : std::string("-")) << " |\n";
  }
  out << "\nExpected calibration error: " << Fixed(ExpectedCalibrationError(bins), 3) << "\n";

  if (options.synthetic_maps > 0) {
    // Every pair, found or not, labelled by whether its placement (the best guess when refused)
    // is right: refused pairs carry most of the wrong placements the score must learn from.
    std::vector<registration::ConfidenceCalibration::Sample> samples;
    for (const PairOutcome& p : run.pairs) samples.push_back({p.fleetmap.score, p.fleetmap.right});
    if (!samples.empty()) {
      const auto fit = registration::ConfidenceCalibration::Fit(samples, 20);
      out << "\nCalibration fit (isotonic, score -> probability the placement is right, "
          << samples.size() << " pairs):\n{";
      for (size_t k = 0; k < fit.knots().size(); ++k) {
        out << (k > 0 ? ", " : "") << "{" << FormatDouble("%.4f", fit.knots()[k].score) << ", "
            << FormatDouble("%.4f", fit.knots()[k].probability) << "}";
      }
      out << "}\n";
    }
  }

  if (!options.json_path.empty()) {
    nlohmann::json json = {{"source", source},
                           {"pairs_per_overlap", options.pairs_per_overlap},
                           {"seed", options.seed},
                           {"min_confidence", bench_options.registration.min_confidence},
                           {"machine", MachineDescription()},
                           {"not_generated", run.not_generated}};
    nlohmann::json summary = nlohmann::json::array();
    for (const SummaryRow& row : rows) {
      summary.push_back({{"group", row.group},
                         {"overlap", OverlapLabel(row.target_overlap)},
                         {"target_overlap", row.target_overlap},
                         {"mean_overlap", row.mean_overlap},
                         {"fleetmap", ToJson(row.fleetmap)},
                         {"mexplore", ToJson(row.mexplore)}});
    }
    json["summary"] = summary;
    nlohmann::json reliability = nlohmann::json::array();
    for (const ReliabilityBin& b : bins) {
      reliability.push_back({{"lo", b.lo},
                             {"hi", b.hi},
                             {"found", b.found},
                             {"correct", b.correct},
                             {"mean_confidence", b.mean_confidence}});
    }
    json["reliability"] = reliability;
    json["expected_calibration_error"] = ExpectedCalibrationError(bins);
    nlohmann::json pairs = nlohmann::json::array();
    for (const PairOutcome& p : run.pairs) {
      pairs.push_back({{"map", p.map},
                       {"group", p.group},
                       {"target_overlap", p.target_overlap},
                       {"overlap", p.overlap},
                       {"fleetmap", ToJson(p.fleetmap)},
                       {"mexplore", ToJson(p.mexplore)}});
    }
    json["pairs"] = pairs;
    if (const Status written = WriteFileAtomically(options.json_path, json.dump(2) + "\n");
        !written.ok()) {
      err << "fleetmap bench register: " << written.message() << "\n";
      return cli::kExitBadInput;
    }
  }
  if (!options.csv_path.empty()) {
    std::ostringstream csv;
    csv << "map,group,target_overlap,overlap,method,found,success,translation_error_cells,"
           "yaw_error_deg,seconds,confidence\n";
    for (const PairOutcome& p : run.pairs) {
      for (const auto& [method, o] :
           {std::pair<std::string, const MethodOutcome*>{"fleetmap", &p.fleetmap},
            {"mexplore", &p.mexplore}}) {
        if (options.skip_mexplore && method == "mexplore") continue;
        csv << p.map << "," << p.group << "," << Fixed(p.target_overlap, 2) << ","
            << Fixed(p.overlap, 4) << "," << method << "," << o->found << "," << o->success << ","
            << Fixed(o->translation_error_cells, 3) << "," << Fixed(o->yaw_error_deg, 3) << ","
            << Fixed(o->seconds, 4) << "," << Fixed(o->confidence, 4) << "\n";
      }
    }
    if (const Status written = WriteFileAtomically(options.csv_path, csv.str()); !written.ok()) {
      err << "fleetmap bench register: " << written.message() << "\n";
      return cli::kExitBadInput;
    }
  }
  return cli::kExitOk;
}

void AddBenchRegisterCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<BenchRegisterOptions>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "register",
      "Map registration on map pairs at 20-70 % overlap, plain and drifted: fleetmap against "
      "m-explore's pipeline");
  command->add_option("--maps", options->maps_dir, "directory of map_server maps (*.yaml)");
  command
      ->add_option("--repeated", options->repeated_maps,
                   "with --maps, also this many repeated-structure terrains (warehouse, "
                   "office rows, corridors), reported as their own rows")
      ->capture_default_str();
  command->add_flag("--no-drift", options->no_drift,
                    "skip the drifted pairs (each pair again with B warped smoothly)");
  command
      ->add_option("--max-drift-per-m", options->max_drift_per_m,
                   "drift the verification allows per metre from where the maps agree "
                   "(docs/registration.md, Drift); 0 verifies rigidly")
      ->check(CLI::Range(0.0, 0.2))
      ->capture_default_str();
  command->add_option("--synthetic", options->synthetic_maps,
                      "use this many synthetic terrains (office, maze, unstructured, warehouse, "
                      "office rows, corridors) instead of --maps, and print the confidence "
                      "calibration fit");
  command
      ->add_option("--pairs-per-overlap", options->pairs_per_overlap, "pairs per map and overlap")
      ->capture_default_str();
  command->add_option("--seed", options->seed, "pair generator seed")->capture_default_str();
  command->add_option("--csv", options->csv_path, "write one row per pair and method");
  command->add_option("--json", options->json_path, "write the summary, reliability and pairs");
  command->add_option("--growing", options->growing_steps,
                      "instead of the pairs: B grows in this many steps, each registered, and "
                      "the placer's sequential test (bar only, and with verified wins under it) "
                      "says when it would place the robot, and whether rightly (m-explore not "
                      "run)");
  command
      ->add_option("--wall-noise", options->wall_noise,
                   "independent noise on each map of a pair: the probability that a wall face "
                   "cell moves by one cell (two SLAM runs of one wall; 0: the crops share walls)")
      ->check(CLI::Range(0.0, 0.5))
      ->capture_default_str();
  command->add_flag("--skip-mexplore", options->skip_mexplore,
                    "run fleetmap only (for the calibration fit)");
  command->callback([options, exit_code] {
    options->err_is_terminal = ProgressLine::StderrIsTerminal();
    *exit_code = RunBenchRegister(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::bench
