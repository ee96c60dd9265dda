#include "cli/learn_objects_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "cli/inputs/command_inputs.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "cli/learn_progress_printer.hpp"
#include "common/core/file_io.hpp"
#include "common/core/progress_line.hpp"
#include "common/grid/image_file.hpp"
#include "common/object_learning/object_learner.hpp"
#include "common/object_learning/snapshot_extractor.hpp"

namespace fleetmap::cli {
namespace {

namespace ol = object_learning;

// Occupied dark, free white, as maps are drawn; image row 0 is the patch's top (highest y).
cv::Mat PatchImage(const scene::Patch& patch) {
  cv::Mat image(patch.height, patch.width, CV_8UC1);
  for (int y = 0; y < patch.height; ++y) {
    for (int x = 0; x < patch.width; ++x) {
      image.at<uint8_t>(patch.height - 1 - y, x) =
          static_cast<uint8_t>(std::lround(255.0 * (1.0 - std::clamp(patch.at(x, y), 0.0f, 1.0f))));
    }
  }
  return image;
}

// Templates on the top row, objects below, each scaled up 4x, separated by grey lines.
cv::Mat Montage(const ol::LearnedModel& model) {
  constexpr int kScale = 4;
  constexpr int kGap = 4;
  const scene::Patch& shape = model.objects.front();
  const int cell_w = shape.width * kScale, cell_h = shape.height * kScale;
  const int columns =
      std::max<int>(model.objects.size(), std::max<size_t>(1, model.templates.size()));
  const int rows = model.templates.empty() ? 1 : 2;
  cv::Mat montage(rows * cell_h + (rows + 1) * kGap, columns * cell_w + (columns + 1) * kGap,
                  CV_8UC1, cv::Scalar(128));
  auto place = [&](const scene::Patch& patch, int row, int column) {
    cv::Mat big;
    cv::resize(PatchImage(patch), big, cv::Size(cell_w, cell_h), 0, 0, cv::INTER_NEAREST);
    big.copyTo(montage(
        cv::Rect(kGap + column * (cell_w + kGap), kGap + row * (cell_h + kGap), cell_w, cell_h)));
  };
  for (size_t m = 0; m < model.templates.size(); ++m)
    place(model.templates[m], 0, static_cast<int>(m));
  for (size_t n = 0; n < model.objects.size(); ++n)
    place(model.objects[n], rows - 1, static_cast<int>(n));
  return montage;
}

nlohmann::json ModelJson(const ol::LearnedModel& model, const std::vector<std::string>& maps,
                         double seconds) {
  nlohmann::json searched = nlohmann::json::array();
  for (const ol::ModelScore& s : model.searched) {
    searched.push_back({{"objects", s.num_objects},
                        {"templates", s.num_templates},
                        {"log_posterior", s.log_posterior}});
  }
  nlohmann::json snapshots = nlohmann::json::array();
  for (const ol::SnapshotAssignment& s : model.snapshots) {
    const Pose2 pose = ol::ObjectPoseInMap(s);
    snapshots.push_back(
        {{"map", maps[s.map_index]},
         {"map_index", s.map_index},
         {"object", s.object},
         {"centre", {s.centre.x(), s.centre.y()}},
         {"object_pose", {{"x", pose.x}, {"y", pose.y}, {"yaw", pose.yaw}}},
         {"alignment",
          {{"dx", s.alignment.dx}, {"dy", s.alignment.dy}, {"dphi", s.alignment.dphi}}}});
  }
  nlohmann::json objects = nlohmann::json::array();
  for (size_t n = 0; n < model.objects.size(); ++n) {
    objects.push_back(
        {{"object", n},
         {"template", model.object_template.empty() ? nlohmann::json(nullptr)
                                                    : nlohmann::json(model.object_template[n])},
         {"image", "object_" + std::to_string(n) + ".pgm"}});
  }
  nlohmann::json templates = nlohmann::json::array();
  for (size_t m = 0; m < model.templates.size(); ++m) {
    templates.push_back({{"template", m}, {"image", "template_" + std::to_string(m) + ".pgm"}});
  }
  const double resolution = model.objects.empty() ? 0.0 : model.objects.front().resolution;
  const int side = model.objects.empty() ? 0 : model.objects.front().width;
  return {{"num_objects", model.num_objects},
          {"num_templates", model.num_templates},
          {"log_posterior", model.log_posterior},
          {"searched", searched},
          {"patch", {{"cells", side}, {"resolution", resolution}}},
          {"objects", objects},
          {"templates", templates},
          {"snapshots", snapshots},
          {"warnings", model.warnings},
          {"degraded", model.degraded},
          {"estimated_memory_mb", model.estimated_memory_mb},
          {"seconds", seconds}};
}

// model.json, object_<n>.pgm, template_<m>.pgm and montage.png in `dir`.
Status WriteOutputs(const ol::LearnedModel& model, const nlohmann::json& json,
                    const std::string& dir) {
  FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(dir + "/model.json", json.dump(2) + "\n"));
  for (size_t n = 0; n < model.objects.size(); ++n) {
    FLEETMAP_RETURN_IF_ERROR(grid::WriteImageFile(dir + "/object_" + std::to_string(n) + ".pgm",
                                                  PatchImage(model.objects[n])));
  }
  for (size_t m = 0; m < model.templates.size(); ++m) {
    FLEETMAP_RETURN_IF_ERROR(grid::WriteImageFile(dir + "/template_" + std::to_string(m) + ".pgm",
                                                  PatchImage(model.templates[m])));
  }
  if (!model.objects.empty()) {
    FLEETMAP_RETURN_IF_ERROR(grid::WriteImageFile(dir + "/montage.png", Montage(model)));
  }
  return Status::Ok();
}

}  // namespace

int RunLearnObjects(const LearnObjectsOptions& options, std::ostream& out, std::ostream& err) {
  const std::string name = "fleetmap learn-objects: ";
  if (options.maps.size() < 2) {
    err << name << "needs at least two maps of the same place, got " << options.maps.size()
        << (options.maps.empty() ? "" : " (" + options.maps[0] + ")") << "\n";
    return kExitBadInput;
  }
  std::vector<grid::OccupancyGrid> grids;
  for (const std::string& path : options.maps) {
    StatusOr<grid::LoadedMap> map = LoadGridInput(path, kDefaultMaxCells);
    if (!map.ok()) {
      err << name << map.status().message() << "\n";
      return kExitBadInput;
    }
    grids.push_back(std::move(map->grid));
    const std::string mismatch = ol::GeometryMismatch(grids.front(), grids.back());
    if (!mismatch.empty()) {
      err << name << path << " does not share the frame of " << options.maps.front() << " ("
          << mismatch
          << "): the maps must be of the same place, same size, resolution and origin\n";
      return kExitBadInput;
    }
  }
  ol::LearnOptions learn;
  learn.seed = options.seed;
  if (options.restarts > 0) learn.restarts = options.restarts;
  if (options.object_penalty >= 0.0) learn.selection.object_penalty = options.object_penalty;
  if (options.template_penalty >= 0.0) learn.selection.template_penalty = options.template_penalty;
  learn.hierarchical = !options.flat;
  if (options.memory_budget_mb > 0.0) learn.memory_budget_mb = options.memory_budget_mb;
  const bool show_progress = options.progress > 0 || (options.progress < 0 && !options.json);
  LearnProgressPrinter printer(err, options.err_is_terminal);
  if (show_progress) {
    learn.progress = [&printer](const ol::LearnProgress& p) { printer.Report(p); };
  }
  const auto start = std::chrono::steady_clock::now();
  StatusOr<ol::LearnedModel> model = ol::LearnObjects(grids, learn);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!model.ok()) {
    err << name << model.status().message() << "\n";
    return kExitBadInput;
  }
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) {
    err << name << "cannot create " << options.out_dir << ": " << ec.message() << "\n";
    return kExitBadInput;
  }
  const nlohmann::json json = ModelJson(*model, options.maps, seconds);
  if (Status s = WriteOutputs(*model, json, options.out_dir); !s.ok()) {
    err << name << s.message() << "\n";
    return kExitBadInput;
  }
  for (const std::string& warning : model->warnings) err << name << "warning: " << warning << "\n";
  if (options.json) {
    out << json.dump(2) << "\n";
  } else if (model->objects.empty()) {
    out << "No object moved between the " << options.maps.size()
        << " maps: nothing to learn (0 objects, 0 templates). Wrote " << options.out_dir
        << "/model.json.\n";
  } else {
    out << model->snapshots.size() << " snapshots -> " << model->num_objects << " objects, "
        << model->num_templates << " templates (log posterior " << model->log_posterior << ", "
        << model->searched.size() << " (N, M) searched, " << seconds << " s"
        << (model->degraded ? ", degraded to fit the memory or work budget: see the warnings" : "")
        << "). Wrote " << options.out_dir
        << "/model.json, object_*.pgm, template_*.pgm, montage.png.\n";
  }
  return kExitOk;
}

void AddLearnObjectsCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<LearnObjectsOptions>();
  CLI::App* command = app.add_subcommand(
      "learn-objects",
      "Learn movable objects and their templates from maps taken at different times");
  command->add_option("maps", options->maps, "map YAML files of the same place (two or more)")
      ->required();
  command->add_option("--out", options->out_dir, "output directory")->required();
  command->add_flag("--json", options->json, "print model.json on stdout");
  command->add_option("--seed", options->seed, "seed of the random starts")->capture_default_str();
  command->add_option("--restarts", options->restarts, "random starts per (N, M) (0: default)")
      ->capture_default_str();
  command->add_option("--object-penalty", options->object_penalty,
                      "c_N, nats per object (negative: default)");
  command->add_option("--template-penalty", options->template_penalty,
                      "c_M, nats per template (negative: default)");
  command->add_flag("--flat", options->flat, "the flat model (objects only, no templates)");
  command->add_option("--memory-budget", options->memory_budget_mb,
                      "memory the learner may use, MB (past it, it degrades and warns; default "
                      "1024)");
  command
      ->add_option("--progress", options->progress,
                   "progress on stderr: -1 automatic (off with --json), 0 never, 1 always")
      ->capture_default_str();
  command->callback([options, exit_code] {
    options->err_is_terminal = ProgressLine::StderrIsTerminal();
    *exit_code = RunLearnObjects(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::cli
