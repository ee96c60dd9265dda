#include "bench/objects/bench_objects_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include "bench/objects/contrast_experiment.hpp"
#include "bench/objects/object_experiment.hpp"
#include "bench/objects/real_plan_experiment.hpp"
#include "bench/objects/real_plan_series.hpp"
#include "bench/objects/small_piece_experiment.hpp"
#include "bench/report/bench_command.hpp"
#include "bench/report/report_format.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/file_io.hpp"
#include "common/grid/map_io.hpp"

namespace fleetmap::bench {
namespace {

std::string Searched(const ModelComparison& c) {
  std::string text;
  for (const object_learning::ModelScore& s : c.searched) {
    text += (text.empty() ? "" : ", ") + std::string("(") + std::to_string(s.num_objects) +
            (c.model == "flat" ? "" : ", " + std::to_string(s.num_templates)) +
            "): " + Fixed(s.log_posterior, 1);
  }
  return text;
}

nlohmann::json ToJson(const ModelComparison& c) {
  nlohmann::json searched = nlohmann::json::array();
  for (const object_learning::ModelScore& s : c.searched) {
    searched.push_back({{"objects", s.num_objects},
                        {"templates", s.num_templates},
                        {"log_posterior", s.log_posterior}});
  }
  return {{"model", c.model},
          {"starts", c.starts},
          {"good", c.good},
          {"train_log_likelihood", c.train_log_likelihood},
          {"test_log_likelihood", c.test_log_likelihood},
          {"chosen_objects", c.chosen_objects},
          {"chosen_templates", c.chosen_templates},
          {"searched", searched},
          {"seconds_starts", c.seconds_starts},
          {"seconds_selection", c.seconds_selection},
          {"seconds_cross_validation", c.seconds_cross_validation}};
}

nlohmann::json ToJson(const ContrastModel& m) {
  return {{"good", m.good},
          {"near_best", m.near_best},
          {"test_log_likelihood", m.test_log_likelihood},
          {"train_log_likelihood", m.train_log_likelihood},
          {"seconds", m.seconds}};
}

// Writes each (path, contents) atomically; on the first failure prints its message (which names
// the file) and returns false.
bool WriteOutputs(const std::vector<std::pair<std::string, std::string>>& files,
                  std::ostream& err) {
  for (const auto& [path, contents] : files) {
    if (const Status written = WriteFileAtomically(path, contents); !written.ok()) {
      err << "fleetmap bench objects: " << written.message() << "\n";
      return false;
    }
  }
  return true;
}

// The floor YAML files named by `inputs`: files as given, directories' *.yaml sorted by name.
std::vector<std::string> FloorFiles(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (!std::filesystem::is_directory(input, ec)) {
      files.push_back(input);
      continue;
    }
    std::vector<std::string> in_dir;
    for (const auto& entry : std::filesystem::directory_iterator(input, ec)) {
      if (entry.path().extension() == ".yaml") in_dir.push_back(entry.path().string());
    }
    std::sort(in_dir.begin(), in_dir.end());
    files.insert(files.end(), in_dir.begin(), in_dir.end());
  }
  return files;
}

// The speck census (speck_census.hpp) of each map named by --maps, beside the small-piece
// benchmark's noise-only floors at a few speck densities, so the two can be read together.
int RunSpeckCensus(const BenchObjectsOptions& options, std::ostream& out, std::ostream& err) {
  const std::string name = "fleetmap bench objects: ";
  const std::vector<std::string> floors = FloorFiles(options.floors);
  if (floors.empty()) {
    err << name << "--speck-census needs --maps naming at least one map YAML file\n";
    return cli::kExitBadInput;
  }
  std::vector<std::pair<std::string, grid::LoadedMap>> maps;  // all read before any output
  for (const std::string& floor : floors) {
    StatusOr<grid::LoadedMap> loaded = grid::LoadMap(floor);
    if (!loaded.ok()) {
      err << name << loaded.status().message() << "\n";
      return cli::kExitBadInput;
    }
    maps.emplace_back(std::filesystem::path(floor).stem().string(), std::move(*loaded));
  }
  out << "Lone clusters of occupied cells in free space (bench/objects/speck_census.hpp), per "
         "100 m2 of free space.\n\n"
      << "| map | resolution (m) | free m2 | specks of 1-3 cells | clusters of 4-8 | compact "
         "(a small object's look) |\n|---|---|---|---|---|---|\n";
  std::ostringstream csv;
  csv << "map,resolution_m,free_m2,lone_specks,lone_clusters,lone_compact\n";
  const auto row = [&](const std::string& map, double resolution, const SpeckCensus& c) {
    out << "| " << map << " | " << Fixed(resolution, 3) << " | " << Fixed(c.free_area_m2, 0)
        << " | " << c.lone_specks << " (" << Fixed(c.Per100m2(c.lone_specks), 2) << ") | "
        << c.lone_clusters << " (" << Fixed(c.Per100m2(c.lone_clusters), 2) << ") | "
        << c.lone_compact << " (" << Fixed(c.Per100m2(c.lone_compact), 2) << ") |\n";
    csv << map << "," << resolution << "," << Fixed(c.free_area_m2, 2) << "," << c.lone_specks
        << "," << c.lone_clusters << "," << c.lone_compact << "\n";
  };
  for (const auto& [map_name, map] : maps) {
    row(map_name, map.grid.resolution(), CountLoneSpecks(map.grid));
  }
  constexpr int kFloorsPerDensity = 20;
  for (const double events : {1.0, 2.0, 5.0, 10.0}) {
    sim::Random random(options.seed);
    SpeckCensus census;
    double resolution = 0.0;
    for (int k = 0; k < kFloorsPerDensity; ++k) {
      const grid::OccupancyGrid floor = SpeckledFloor(events, &random);
      resolution = floor.resolution();
      census.Add(CountLoneSpecks(floor));
    }
    row("small-piece noise, " + Fixed(events, 0) + " events / 100 m2 (" +
            std::to_string(kFloorsPerDensity) + " floors)",
        resolution, census);
  }
  if (!options.out_dir.empty() &&
      !WriteOutputs({{options.out_dir + "/speck_census.csv", csv.str()}}, err)) {
    return cli::kExitBadInput;
  }
  return cli::kExitOk;
}

// The real-plan benchmark (issue 22): prints its table, writes its files under options.out_dir.
int RunRealPlans(const BenchObjectsOptions& options, std::ostream& out, std::ostream& err) {
  const std::string name = "fleetmap bench objects: ";
  const std::vector<std::string> floors = FloorFiles(options.floors);
  if (floors.empty()) {
    err << name << "--maps names no map YAML file\n";
    return cli::kExitBadInput;
  }
  object_learning::LearnOptions learn;
  learn.seed = options.seed;
  if (options.restarts > 0) learn.restarts = options.restarts;
  if (options.memory_budget_mb > 0.0) learn.memory_budget_mb = options.memory_budget_mb;
  RealPlanOptions plan;
  plan.maps = options.plan_maps;
  plan.pieces = options.plan_pieces;
  plan.width = options.plan_width;
  plan.height = options.plan_height;
  plan.seed = options.seed;
  out << "\nObject learning on real building maps: " << plan.maps << " maps of " << plan.width
      << " x " << plan.height << " cells per floor, " << plan.pieces
      << " pieces per map (desks, cabinets, tables, L-shapes, bins, small bins) moved between "
         "maps (seed "
      << plan.seed << "); found = snapshot centre within 0.3 m of a piece, one thread, budget "
      << Fixed(learn.memory_budget_mb, 0) << " MB.\n\n";
  out << "| floor | pieces drawn | snapshots | found | precision | recall | chosen (N, M) | "
         "(N, M) searched | s | peak MB |\n|---|---|---|---|---|---|---|---|---|---|\n";
  nlohmann::json rows = nlohmann::json::array();
  std::ostringstream csv;
  csv << "floor,maps,pieces_per_map,pieces_drawn,snapshots,found,precision,recall,objects,"
         "templates,searched,seconds,peak_rss_mb\n";
  for (const std::string& floor : floors) {
    StatusOr<RealPlanSeries> series = MakeRealPlanSeries(floor, plan);
    if (!series.ok()) {
      err << name << series.status().message() << "\n";
      return cli::kExitBadInput;
    }
    const std::string stem = std::filesystem::path(floor).stem().string();
    if (!options.out_dir.empty()) {
      const std::string dir = options.out_dir + "/real_plans/" + stem;
      std::error_code ec;
      std::filesystem::create_directories(dir, ec);
      for (size_t t = 0; t < series->maps.size() && !ec; ++t) {
        const Status saved =
            grid::SaveMap(series->maps[t], dir + "/map_" + std::to_string(t) + ".yaml");
        if (!saved.ok()) {
          err << name << saved.message() << "\n";
          return cli::kExitBadInput;
        }
      }
    }
    if (!options.out_dir.empty()) {
      // The truth beside the maps, so that `learn-objects` runs on them can be scored too.
      nlohmann::json truth = nlohmann::json::array();
      for (size_t t = 0; t < series->pieces.size(); ++t) {
        for (const PlacedPiece& p : series->pieces[t]) {
          truth.push_back({{"map_index", t},
                           {"piece", p.piece},
                           {"shape", PlanShapeName(p.shape)},
                           {"x", p.centre.x()},
                           {"y", p.centre.y()},
                           {"yaw", p.yaw},
                           {"cells", p.cells}});
        }
      }
      const std::string path = options.out_dir + "/real_plans/" + stem + "/pieces.json";
      if (const Status written = WriteFileAtomically(path, truth.dump(1) + "\n"); !written.ok()) {
        err << name << written.message() << "\n";
        return cli::kExitBadInput;
      }
    }
    StatusOr<RealPlanResult> r = RunRealPlanExperiment(*series, learn);
    if (!r.ok()) {
      err << name << floor << ": " << r.status().message() << "\n";
      return cli::kExitBadInput;
    }
    const double peak_mb = r->peak_rss_bytes < 0 ? -1.0 : r->peak_rss_bytes / 1e6;
    nlohmann::json missed = nlohmann::json::array(), spurious = nlohmann::json::array();
    for (size_t i = 0; i < r->score.missed.size(); ++i) {
      const PlacedPiece& p = r->score.missed[i];
      missed.push_back({{"map_index", r->score.missed_map[i]},
                        {"piece", p.piece},
                        {"shape", PlanShapeName(p.shape)},
                        {"x", p.centre.x()},
                        {"y", p.centre.y()}});
    }
    for (const object_learning::SnapshotAssignment& a : r->score.spurious) {
      spurious.push_back({{"map_index", a.map_index}, {"x", a.centre.x()}, {"y", a.centre.y()}});
    }
    out << "| " << stem << " | " << r->score.true_pieces << " | " << r->score.snapshots << " | "
        << r->score.matched << " | " << Fixed(r->score.precision, 3) << " | "
        << Fixed(r->score.recall, 3) << " | (" << r->num_objects << ", " << r->num_templates
        << ") | " << r->searched << " | " << Fixed(r->seconds, 1) << " | " << Fixed(peak_mb, 0)
        << (r->peak_reset ? "" : " (process)") << " |\n";
    if (series->unplaced > 0 || series->overlapping_earlier > 0) {
      out << "  " << stem << ": " << series->unplaced << " piece(s) found no free spot, "
          << series->overlapping_earlier
          << " stand where a piece of an earlier map stood (the floor is full)\n";
    }
    for (const std::string& w : r->warnings) out << "  " << stem << ": " << w << "\n";
    rows.push_back({{"floor", floor},
                    {"maps", r->maps},
                    {"pieces_per_map", r->pieces},
                    {"pieces_drawn", r->score.true_pieces},
                    {"unplaced", r->unplaced},
                    {"overlapping_earlier", series->overlapping_earlier},
                    {"missed", missed},
                    {"spurious", spurious},
                    {"shapes", r->shapes},
                    {"snapshots", r->score.snapshots},
                    {"found", r->score.matched},
                    {"precision", r->score.precision},
                    {"recall", r->score.recall},
                    {"objects", r->num_objects},
                    {"templates", r->num_templates},
                    {"searched", r->searched},
                    {"seconds", r->seconds},
                    {"peak_rss_bytes", r->peak_rss_bytes},
                    {"learner_estimate_mb", r->estimated_mb},
                    {"peak_is_learning_only", r->peak_reset},
                    {"warnings", r->warnings}});
    csv << stem << "," << r->maps << "," << r->pieces << "," << r->score.true_pieces << ","
        << r->score.snapshots << "," << r->score.matched << "," << Fixed(r->score.precision, 4)
        << "," << Fixed(r->score.recall, 4) << "," << r->num_objects << "," << r->num_templates
        << "," << r->searched << "," << Fixed(r->seconds, 3) << "," << Fixed(peak_mb, 1) << "\n";
  }
  if (!options.out_dir.empty()) {
    const nlohmann::json json = {{"width", plan.width},
                                 {"height", plan.height},
                                 {"maps", plan.maps},
                                 {"pieces", plan.pieces},
                                 {"seed", plan.seed},
                                 {"match_distance_m", 0.3},
                                 {"memory_budget_mb", learn.memory_budget_mb},
                                 {"machine", MachineDescription()},
                                 {"floors", rows}};
    if (!WriteOutputs({{options.out_dir + "/real_plans.json", json.dump(2) + "\n"},
                       {options.out_dir + "/real_plans.csv", csv.str()}},
                      err)) {
      return cli::kExitBadInput;
    }
  }
  return cli::kExitOk;
}

// The flat/hierarchical contrast: prints its table as each condition finishes (progress on
// `err`), writes DIR/contrast.md, .csv and .json.
int RunContrast(const BenchObjectsOptions& options, std::ostream& out, std::ostream& err) {
  const std::string name = "fleetmap bench objects: ";
  if (options.contrast_data_sets < 1 || options.contrast_data_sets > 100) {
    err << name << "--data-sets " << options.contrast_data_sets << " must be in [1, 100]\n";
    return cli::kExitBadInput;
  }
  std::vector<ContrastCondition> conditions;
  for (const ContrastCondition& c : ContrastConditions()) {
    const auto& wanted = options.contrast_conditions;
    if (wanted.empty() || std::find(wanted.begin(), wanted.end(), c.name) != wanted.end()) {
      conditions.push_back(c);
    }
  }
  if (conditions.size() < std::max<size_t>(1, options.contrast_conditions.size())) {
    std::string known;
    for (const ContrastCondition& c : ContrastConditions()) known += " '" + c.name + "'";
    err << name << "--condition names an unknown condition; known:" << known << "\n";
    return cli::kExitBadInput;
  }
  std::ostringstream report;
  report << "Flat against hierarchical EM (the object-learning paper's contrast): good starts of "
         << options.starts << " random starts per model on each of " << options.contrast_data_sets
         << " simulated data sets (data seeds " << options.seed << "-"
         << options.seed + options.contrast_data_sets - 1
         << "), both models from the same starts at the true (N, M). good: the true partition "
            "(IsGoodSolution); best optimum: within "
         << Fixed(ContrastRunOptions{}.near_best_nats, 0)
         << " nats of the best start's training log-likelihood; test log-lik: leave one map "
            "out, summed over the data sets.\n\n"
         << "| condition | what differs from the paper's set-up | objects, shapes | snapshots | "
            "good: hierarchical / flat | best optimum: hierarchical / flat | test log-lik: "
            "hierarchical - flat | s: hierarchical / flat |\n"
            "|---|---|---|---|---|---|---|---|\n";
  out << report.str();
  nlohmann::json rows = nlohmann::json::array();
  std::ostringstream csv;
  csv << "condition,data_sets,maps,snapshots,objects,shapes,starts,hierarchical_good,flat_good,"
         "hierarchical_near_best,flat_near_best,hierarchical_test_log_likelihood,"
         "flat_test_log_likelihood,hierarchical_seconds,flat_seconds\n";
  for (size_t i = 0; i < conditions.size(); ++i) {
    err << name << "contrast " << i + 1 << "/" << conditions.size() << ": " << conditions[i].name
        << "\n";
    ContrastRunOptions run;
    run.first_seed = options.seed;
    run.data_sets = options.contrast_data_sets;
    run.starts = options.starts;
    const StatusOr<ContrastRow> row = RunContrastCondition(conditions[i], run);
    if (!row.ok()) {
      err << name << "condition '" << conditions[i].name << "': " << row.status().message() << "\n";
      return cli::kExitBadInput;
    }
    std::ostringstream line;
    const ContrastModel& h = row->hierarchical;
    const ContrastModel& f = row->flat;
    line << "| " << row->condition << " | " << row->changed << " | " << row->true_objects << ", "
         << row->true_templates << " | " << row->snapshots << " | " << h.good << " / " << f.good
         << " of " << row->starts << " | " << h.near_best << " / " << f.near_best << " | "
         << Fixed(h.test_log_likelihood - f.test_log_likelihood, 1) << " | " << Fixed(h.seconds, 1)
         << " / " << Fixed(f.seconds, 1) << " |\n";
    out << line.str() << std::flush;
    report << line.str();
    rows.push_back({{"condition", row->condition},
                    {"changed", row->changed},
                    {"data_sets", row->data_sets},
                    {"maps", row->maps},
                    {"snapshots", row->snapshots},
                    {"true_objects", row->true_objects},
                    {"true_templates", row->true_templates},
                    {"starts", row->starts},
                    {"hierarchical", ToJson(row->hierarchical)},
                    {"flat", ToJson(row->flat)}});
    csv << row->condition << "," << row->data_sets << "," << row->maps << "," << row->snapshots
        << "," << row->true_objects << "," << row->true_templates << "," << row->starts << ","
        << h.good << "," << f.good << "," << h.near_best << "," << f.near_best << ","
        << Fixed(h.test_log_likelihood, 3) << "," << Fixed(f.test_log_likelihood, 3) << ","
        << Fixed(h.seconds, 3) << "," << Fixed(f.seconds, 3) << "\n";
  }
  if (options.out_dir.empty()) return cli::kExitOk;
  const nlohmann::json json = {{"starts_per_data_set", options.starts},
                               {"near_best_nats", ContrastRunOptions{}.near_best_nats},
                               {"data_sets", options.contrast_data_sets},
                               {"first_seed", options.seed},
                               {"machine", MachineDescription()},
                               {"conditions", rows}};
  const bool written = WriteOutputs({{options.out_dir + "/contrast.md", report.str()},
                                     {options.out_dir + "/contrast.csv", csv.str()},
                                     {options.out_dir + "/contrast.json", json.dump(2) + "\n"}},
                                    err);
  return written ? cli::kExitOk : cli::kExitBadInput;
}

}  // namespace

int RunBenchObjects(const BenchObjectsOptions& options, std::ostream& out, std::ostream& err) {
  if (options.starts < 1 || options.starts > 1000) {
    err << "fleetmap bench objects: --starts " << options.starts << " must be in [1, 1000]\n";
    return cli::kExitBadInput;
  }
  if (options.sessions < 2 || options.sessions > 50) {
    err << "fleetmap bench objects: --sessions " << options.sessions << " must be in [2, 50]\n";
    return cli::kExitBadInput;
  }
  if (options.restarts < 0 || options.restarts > 100) {
    err << "fleetmap bench objects: --restarts " << options.restarts << " must be in [0, 100]\n";
    return cli::kExitBadInput;
  }
  if (options.plan_maps < 2 || options.plan_maps > 50 || options.plan_pieces < 1 ||
      options.plan_pieces > 500) {
    err << "fleetmap bench objects: --plan-maps must be in [2, 50] and --pieces in [1, 500]\n";
    return cli::kExitBadInput;
  }
  if (!options.out_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.out_dir, ec);
    if (ec) {
      err << "fleetmap bench objects: cannot create " << options.out_dir << ": " << ec.message()
          << "\n";
      return cli::kExitBadInput;
    }
  }
  if (options.small_pieces > 0) {
    SmallPieceOptions small;
    small.seed = options.seed;
    small.pairs = options.small_pieces;
    small.speck_events_per_100m2 = options.speck_events;
    small.snapshots.isolation_radius_m = options.isolation_radius;
    small.small_in_one_map = options.small_in_one_map;
    const StatusOr<SmallPieceResult> result = RunSmallPieceExperiment(small);
    if (!result.ok()) {
      err << "fleetmap bench objects: " << result.status().message() << "\n";
      return cli::kExitBadInput;
    }
    const std::string report = SmallPieceReport(small, *result);
    out << report;
    if (!options.out_dir.empty() &&
        !WriteOutputs({{options.out_dir + "/small_pieces.md", report}}, err)) {
      return cli::kExitBadInput;
    }
    return cli::kExitOk;
  }
  if (options.contrast) return RunContrast(options, out, err);
  if (options.speck_census) return RunSpeckCensus(options, out, err);
  if (options.skip_sim)
    return options.floors.empty() ? cli::kExitOk : RunRealPlans(options, out, err);
  ObjectDatasetOptions dataset_options;
  dataset_options.terrain = options.terrain;
  dataset_options.size = options.size;
  dataset_options.seed = options.seed;
  dataset_options.plan.sessions = options.sessions;
  object_learning::LearnOptions learn;
  learn.seed = options.seed;
  if (options.restarts > 0) learn.restarts = options.restarts;
  const auto t0 = std::chrono::steady_clock::now();
  StatusOr<ObjectDataset> data = MakeObjectDataset(dataset_options, learn.snapshots);
  if (!data.ok()) {
    err << "fleetmap bench objects: " << data.status().message() << "\n";
    return cli::kExitBadInput;
  }
  const double seconds_sim =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const ObjectExperimentResult r = RunObjectExperiment(*data, options.starts, learn);

  std::string per_map;
  for (int k : r.per_map) per_map += (per_map.empty() ? "" : " ") + std::to_string(k);
  out << "Object-template learning, " << r.maps << " maps of a " << Fixed(options.size, 0) << " m "
      << options.terrain << " (seed " << options.seed << "), " << r.true_objects << " objects of "
      << r.true_templates << " shapes; " << r.snapshots << " snapshots (per map: " << per_map
      << "), " << r.spurious_snapshots << " spurious. Simulation " << Fixed(seconds_sim, 1)
      << " s.\n\n";
  out << "| model | good starts | test log-lik (LOMO) | chosen (N, M) | starts s | selection s | "
         "CV s |\n|---|---|---|---|---|---|---|\n";
  for (const ModelComparison* c : {&r.hierarchical, &r.flat}) {
    out << "| " << c->model << " | " << c->good << "/" << c->starts << " | "
        << Fixed(c->test_log_likelihood, 1) << " | (" << c->chosen_objects << ", "
        << (c->model == "flat" ? std::string("-") : std::to_string(c->chosen_templates)) << ") | "
        << Fixed(c->seconds_starts, 2) << " | " << Fixed(c->seconds_selection, 2) << " | "
        << Fixed(c->seconds_cross_validation, 2) << " |\n";
  }
  out << "\nLog posterior searched, hierarchical (N, M): " << Searched(r.hierarchical)
      << "\nLog posterior searched, flat (N): " << Searched(r.flat) << "\n";

  if (!options.out_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.out_dir + "/maps", ec);
    if (ec) {
      err << "fleetmap bench objects: cannot create " << options.out_dir << ": " << ec.message()
          << "\n";
      return cli::kExitBadInput;
    }
    for (size_t t = 0; t < data->maps.size(); ++t) {
      const std::string path = options.out_dir + "/maps/session_" + std::to_string(t) + ".yaml";
      const Status saved = grid::SaveMap(data->maps[t], path);
      if (!saved.ok()) {
        err << "fleetmap bench objects: " << saved.message() << "\n";  // it names the file
        return cli::kExitBadInput;
      }
    }
    nlohmann::json json = {{"maps", r.maps},
                           {"terrain", options.terrain},
                           {"size_m", options.size},
                           {"seed", options.seed},
                           {"snapshots", r.snapshots},
                           {"snapshots_per_map", r.per_map},
                           {"spurious_snapshots", r.spurious_snapshots},
                           {"true_objects", r.true_objects},
                           {"true_templates", r.true_templates},
                           {"restarts", learn.restarts},
                           {"machine", MachineDescription()},
                           {"seconds_simulation", seconds_sim},
                           {"models", {ToJson(r.hierarchical), ToJson(r.flat)}}};
    std::ostringstream csv;
    csv << "model,starts,good,test_log_likelihood,chosen_objects,chosen_templates,seconds_starts,"
           "seconds_selection,seconds_cross_validation\n";
    for (const ModelComparison* c : {&r.hierarchical, &r.flat}) {
      csv << c->model << "," << c->starts << "," << c->good << ","
          << Fixed(c->test_log_likelihood, 3) << "," << c->chosen_objects << ","
          << c->chosen_templates << "," << Fixed(c->seconds_starts, 3) << ","
          << Fixed(c->seconds_selection, 3) << "," << Fixed(c->seconds_cross_validation, 3) << "\n";
    }
    if (!WriteOutputs({{options.out_dir + "/results.json", json.dump(2) + "\n"},
                       {options.out_dir + "/results.csv", csv.str()}},
                      err)) {
      return cli::kExitBadInput;
    }
  }
  if (!options.floors.empty()) return RunRealPlans(options, out, err);
  return cli::kExitOk;
}

void AddBenchObjectsCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<BenchObjectsOptions>();
  CLI::App* command = BenchCommand(app)->add_subcommand(
      "objects", "The object-template learning paper's comparison on simulated mapping sessions");
  command->add_option("--out", options->out_dir, "output directory (results, maps)");
  command->add_option("--starts", options->starts, "random starts per model")
      ->capture_default_str();
  command->add_option("--seed", options->seed, "simulation and learning seed")
      ->capture_default_str();
  command->add_option("--terrain", options->terrain, "lab or office")->capture_default_str();
  command->add_option("--size", options->size, "terrain side (m)")->capture_default_str();
  command->add_option("--sessions", options->sessions, "mapping sessions (maps)")
      ->capture_default_str();
  command
      ->add_option("--restarts", options->restarts,
                   "random starts per (N, M) in selection and cross validation (0: default)")
      ->capture_default_str();
  command->add_option("--maps", options->floors,
                      "real-plan benchmark: floor maps (map_server YAML files or directories)");
  command->add_option("--plan-maps", options->plan_maps, "real-plan maps per floor")
      ->capture_default_str();
  command->add_option("--pieces", options->plan_pieces, "real-plan pieces per map")
      ->capture_default_str();
  command->add_option("--width", options->plan_width, "real-plan map width (cells)")
      ->capture_default_str();
  command->add_option("--height", options->plan_height, "real-plan map height (cells)")
      ->capture_default_str();
  command->add_flag("--no-sim", options->skip_sim, "skip the simulated lab (real plans only)");
  command
      ->add_option("--small-pieces", options->small_pieces,
                   "map pairs of small objects against SLAM specks (only this benchmark)")
      ->capture_default_str();
  command
      ->add_option("--speck-events", options->speck_events,
                   "small pieces: speck events per 100 m2 per map")
      ->capture_default_str();
  command->add_flag("--small-in-one-map", options->small_in_one_map,
                    "small pieces: every small piece in the first map of its pair only");
  command
      ->add_option("--isolation-radius", options->isolation_radius,
                   "small pieces: isolation radius (m; 0: recurrence only)")
      ->capture_default_str();
  command->add_flag("--speck-census", options->speck_census,
                    "count the lone specks of the --maps and of the small-piece benchmark's "
                    "noise (only this benchmark)");
  command->add_flag("--contrast", options->contrast,
                    "flat against hierarchical EM over conditions (only this benchmark)");
  command
      ->add_option("--data-sets", options->contrast_data_sets, "contrast: data seeds per condition")
      ->capture_default_str();
  command->add_option("--condition", options->contrast_conditions,
                      "contrast: conditions to run (default: all)");
  command->add_option("--memory-budget", options->memory_budget_mb,
                      "the learner's memory budget on real plans, MB (0: default)");
  command->callback(
      [options, exit_code] { *exit_code = RunBenchObjects(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::bench
