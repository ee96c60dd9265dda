#include "cli/register_command.hpp"

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "cli/inputs/command_inputs.hpp"
#include "cli/inputs/exit_codes.hpp"
#include "common/core/number_format.hpp"
#include "common/registration/registration.hpp"

namespace fleetmap::cli {
namespace {

constexpr const char* kDescription =
    "Estimate the rigid transform a_from_b (x, y in metres, yaw in radians) that takes map B's "
    "frame into map A's frame (p_a = a_from_b * p_b; frames as ROS map_server defines them), "
    "from the two occupancy grids. Both maps must have the same resolution.\n"
    "found: the server's placement decision for the pair: yes when the placement passes the "
    "verification and its confidence reaches the placement bar (--min-confidence, by default "
    "the server's, 0.95; fleetmap-server --placement-confidence sets the same bar). It is "
    "refused when too few of B's occupied cells agree with A (too little shared structure), "
    "when the placement puts many occupied cells on the other map's free space, when a clearly "
    "different placement scores nearly as well (a symmetric corridor, repeated rooms), or when "
    "the confidence is below the bar; \"why not\" says which.\n"
    "best guess: the best placement found, printed whether found or not (when not found, a "
    "hint only).\n"
    "confidence (0..1): the estimated probability that the placement is right (within 3 cells "
    "and 2 degrees), calibrated on synthetic map pairs with repeated structure and drift "
    "(docs/registration.md).\n"
    "score (0..1): the evidence confidence is computed from: consistency times distinctness. "
    "Consistency is the share of occupied cells in the overlap (both ways) that land on or next "
    "to an occupied cell of the other map rather than on its free space; distinctness is how far "
    "the best clearly different placement falls below the best (1 when it scores 70 % of the "
    "best or less, 0 at a tie).\n"
    "overlap (0..1): the share of B's known cells that land on A's known cells.\n"
    "Exit status 0 whether found or not, 2 on bad input (a map that cannot be read, "
    "--min-confidence outside 0..1).";

// Text output to the digits that mean something: metres to the millimetre, shares to a tenth of
// a percent, yaw to a hundredth of a degree, milliseconds to a tenth.
std::string Metres(double value) { return FixedNumber(value, 3); }
std::string Share(double value) { return FixedNumber(value, 3); }

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
  if (!(options.min_confidence >= 0.0 && options.min_confidence <= 1.0)) {
    err << "fleetmap register: --min-confidence " << ShortNumber(options.min_confidence)
        << " must be in [0, 1] (the least confidence at which a placement is found)\n";
    return kExitBadInput;
  }
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
  registration::RegistrationOptions registration_options;
  registration_options.min_confidence = options.min_confidence;
  registration_options.max_drift_per_m = options.max_drift_per_m;
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
  std::string best_guess = "x ";
  best_guess.append(Metres(r.a_from_b.x))
      .append(" m, y ")
      .append(Metres(r.a_from_b.y))
      .append(" m, yaw ")
      .append(FixedNumber(r.a_from_b.yaw, 4))
      .append(" rad (")
      .append(FixedNumber(r.a_from_b.yaw * 180.0 / std::numbers::pi, 2))
      .append(" deg)");
  if (options.json) {
    // To the micrometre and microradian: no float noise (0.0039999999999995595), and finer than
    // any placement is right.
    const auto micro = [](double value) { return RoundToDecimals(value, 6); };
    const nlohmann::ordered_json pose = {
        {"x", micro(r.a_from_b.x)}, {"y", micro(r.a_from_b.y)}, {"yaw", micro(r.a_from_b.yaw)}};
    nlohmann::ordered_json json;
    json["found"] = r.found;
    json["min_confidence"] = options.min_confidence;
    json["best_guess"] = pose;
    if (r.found) json["a_from_b"] = pose;
    json["confidence"] = r.confidence;
    json["score"] = r.score;
    json["overlap"] = r.overlap;
    json["drift_m"] = RoundToDecimals(r.drift, 3);
    json["ms"] = RoundToDecimals(ms, 1);
    if (!r.found) json["why_not"] = r.why_not;
    out << json.dump() << "\n";
  } else {
    out << "a:          " << options.map_a_yaml << "\n"
        << "b:          " << options.map_b_yaml << "\n"
        << "found:      " << (r.found ? "yes" : "no") << " (placement bar: confidence "
        << ShortNumber(options.min_confidence) << ")\n";
    if (!r.found) out << "why not:    " << r.why_not << "\n";
    if (r.found) out << "a_from_b:   " << best_guess << "\n";
    out << "best guess: " << best_guess << "\n"
        << "confidence: " << Share(r.confidence) << " (probability the placement is right)\n"
        << "score:      " << Share(r.score) << " (consistency x distinctness)\n"
        << "overlap:    " << Share(r.overlap) << " of B's known cells on A's\n"
        << "evidence:   " << r.agreeing_cells << " of B's occupied cells agree, "
        << r.contradicting_cells
        << " occupied cells contradict, the best other placement verifies at "
        << FixedNumber(100.0 * r.peak_ratio, 1) << " % of the best\n"
        << "drift:      " << FixedNumber(r.drift, 3)
        << " m, the largest shift a block of B took to verify (docs/registration.md)\n"
        << "time:       " << FixedNumber(ms, 1) << " ms\n";
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
  command
      ->add_option("--max-drift-per-m", options->max_drift_per_m,
                   "Verify allowing each 3 m block of B to shift by this much per metre from "
                   "where the maps agree (drift; 0: rigid; the server's default, 0.03)")
      ->check(CLI::Range(0.0, 0.2))
      ->capture_default_str();
  // Read as text and checked here and in RunRegister, so that any bad value exits 2 with the
  // option and the range named; CLI11 would take an empty value as none.
  auto min_confidence = std::make_shared<std::string>();
  std::string help =
      "Least confidence (0..1) at which the placement is found: the placement bar, by default "
      "the server's (";
  help.append(ShortNumber(registration::kPlacementConfidence)).append(")");
  CLI::Option* min_confidence_option =
      command->add_option("--min-confidence", *min_confidence, help);
  command->callback([options, min_confidence, min_confidence_option, exit_code]() {
    if (min_confidence_option->count() > 0) {
      char* end = nullptr;
      options->min_confidence = std::strtod(min_confidence->c_str(), &end);
      if (end == min_confidence->c_str() || *end != '\0') {
        std::cerr << "fleetmap register: --min-confidence '" << *min_confidence
                  << "' is not a number in [0, 1]\n";
        *exit_code = kExitBadInput;
        return;
      }
    }
    *exit_code = RunRegister(*options, std::cout, std::cerr);
  });
}

}  // namespace fleetmap::cli
