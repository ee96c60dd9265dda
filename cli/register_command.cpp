#include "cli/register_command.hpp"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/inputs/command_inputs.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/registration/registration.hpp"

namespace fleetmap::cli {
namespace {

constexpr const char* kDescription =
    "Estimate the rigid transform a_from_b (x, y in metres, yaw in radians) that takes map B's "
    "frame into map A's frame (p_a = a_from_b * p_b; frames as ROS map_server defines them), "
    "from the two occupancy grids. Both maps must have the same resolution.\n"
    "found: whether the match is trusted. It is refused when too few of B's occupied cells "
    "agree with A (too little shared structure), when the placement puts many occupied cells on "
    "the other map's free space, or when a clearly different placement scores nearly as well "
    "(a symmetric corridor, repeated rooms).\n"
    "confidence (0..1): the estimated probability that the placement is right (within 3 cells "
    "and 2 degrees), calibrated on synthetic map pairs (docs/registration.md).\n"
    "score (0..1): the evidence confidence is computed from: consistency times distinctness. "
    "Consistency is the share of occupied cells in the overlap (both ways) that land on or next "
    "to an occupied cell of the other map rather than on its free space; distinctness is how far "
    "the best clearly different placement falls below the best (1 when it scores 70 % of the "
    "best or less, 0 at a tie).\n"
    "overlap (0..1): the share of B's known cells that land on A's known cells.\n"
    "Exit status 0 whether found or not, 2 on bad input.";

std::string Num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", value);
  return buffer;
}

// The map's cells as 100 / 0 / -1, read with the thresholds of its YAML.
grid::OccupancyGrid Trinary(const grid::LoadedMap& map) {
  const grid::StateThresholds thresholds{.occupied = map.metadata.occupied_thresh,
                                         .free = map.metadata.free_thresh};
  grid::OccupancyGrid out = map.grid;
  for (int y = 0; y < out.height(); ++y) {
    for (int x = 0; x < out.width(); ++x) {
      const grid::CellState state = map.grid.StateAt(x, y, thresholds);
      out.at(x, y) =
          state == grid::CellState::kOccupied
              ? grid::kOccupiedValue
              : (state == grid::CellState::kFree ? grid::kFreeValue : grid::kUnknownValue);
    }
  }
  return out;
}

}  // namespace

int RunRegister(const RegisterOptions& options, std::ostream& out, std::ostream& err) {
  const StatusOr<grid::LoadedMap> a = LoadGridInput(options.map_a_yaml, options.max_cells);
  if (!a.ok()) {
    err << "fleetmap register: " << a.status().message() << "\n";
    return kExitBadInput;
  }
  const StatusOr<grid::LoadedMap> b = LoadGridInput(options.map_b_yaml, options.max_cells);
  if (!b.ok()) {
    err << "fleetmap register: " << b.status().message() << "\n";
    return kExitBadInput;
  }
  // Each map's cells read as occupied / free with its own YAML's thresholds; the registration
  // then sees trinary grids.
  const grid::OccupancyGrid grid_a = Trinary(*a);
  const grid::OccupancyGrid grid_b = Trinary(*b);
  const registration::RegistrationOptions registration_options;
  const auto start = std::chrono::steady_clock::now();
  const StatusOr<registration::Registration> result =
      registration::Register(grid_a, grid_b, registration_options);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!result.ok()) {
    err << "fleetmap register: " << options.map_a_yaml << " and " << options.map_b_yaml << ": "
        << result.status().message() << "\n";
    return kExitBadInput;
  }
  const registration::Registration& r = *result;
  if (options.json) {
    nlohmann::ordered_json json;
    json["found"] = r.found;
    json["a_from_b"] = {{"x", r.a_from_b.x}, {"y", r.a_from_b.y}, {"yaw", r.a_from_b.yaw}};
    json["confidence"] = r.confidence;
    json["score"] = r.score;
    json["overlap"] = r.overlap;
    json["ms"] = ms;
    if (!r.found) json["why_not"] = r.why_not;
    out << json.dump() << "\n";
  } else {
    out << "a:          " << options.map_a_yaml << "\n"
        << "b:          " << options.map_b_yaml << "\n"
        << "found:      " << (r.found ? "yes" : "no") << "\n";
    if (!r.found) out << "why not:    " << r.why_not << "\n";
    out << (r.found ? "a_from_b:   " : "best guess: ") << "x " << Num(r.a_from_b.x) << " m, y "
        << Num(r.a_from_b.y) << " m, yaw " << Num(r.a_from_b.yaw) << " rad ("
        << Num(r.a_from_b.yaw * 180.0 / 3.14159265358979323846) << " deg)\n"
        << "confidence: " << Num(r.confidence) << " (probability the placement is right)\n"
        << "score:      " << Num(r.score) << " (consistency x distinctness)\n"
        << "overlap:    " << Num(r.overlap) << " of B's known cells on A's\n"
        << "evidence:   " << r.agreeing_cells << " of B's occupied cells agree, "
        << r.contradicting_cells
        << " occupied cells contradict, the best other placement verifies at "
        << Num(100.0 * r.peak_ratio) << " % of the best\n"
        << "time:       " << Num(ms) << " ms\n";
  }
  out.flush();
  return out ? kExitOk : kExitBadInput;
}

void AddRegisterCommand(CLI::App& app, int* exit_code) {
  auto options = std::make_shared<RegisterOptions>();
  CLI::App* command = app.add_subcommand("register", "Find the transform between two robots' maps");
  command->footer(kDescription);
  command->add_option("a", options->map_a_yaml, "map_server YAML file of map A")->required();
  command->add_option("b", options->map_b_yaml, "map_server YAML file of map B")->required();
  command->add_flag("--json", options->json, "Print one JSON line instead of text");
  command->add_option("--max-cells", options->max_cells, "Refuse images with more cells than this")
      ->check(CLI::PositiveNumber);
  command->callback(
      [options, exit_code]() { *exit_code = RunRegister(*options, std::cout, std::cerr); });
}

}  // namespace fleetmap::cli
