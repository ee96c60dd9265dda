#include "bench/objects/bench_objects_command.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "bench/objects/object_experiment.hpp"
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
    for (const auto& [path, contents] :
         {std::pair{options.out_dir + "/results.json", json.dump(2) + "\n"},
          std::pair{options.out_dir + "/results.csv", csv.str()}}) {
      if (const Status written = WriteFileAtomically(path, contents); !written.ok()) {
        err << "fleetmap bench objects: " << written.message() << "\n";
        return cli::kExitBadInput;
      }
    }
  }
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
  command->callback(
      [options, exit_code] { *exit_code = RunBenchObjects(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::bench
