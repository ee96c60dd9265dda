#include "bench/fleet/fleet_sim_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "bench/fleet/baseline_bytes.hpp"
#include "bench/fleet/shard_comparison.hpp"
#include "common/core/file_io.hpp"
#include "common/grid/image_file.hpp"
#include "common/metrics/map_quality.hpp"
#include "common/sim/frame_resample.hpp"

namespace fleetmap::bench {
namespace {

// The fleet tile side the simulated fleet's servers use (fleetmap-server's default).
constexpr double kSimTileSize = 10.0;

std::string Percent(const std::optional<double>& value) {
  return value ? fmt::format("{:.2f} %", *value) : std::string("undefined");
}

std::string Ms(const std::optional<double>& value) {
  return value ? fmt::format("{:.1f} ms", *value) : std::string("n/a");
}

nlohmann::json Json(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

// How many times `tile_bytes` the `bytes` are; null without tile bytes.
nlohmann::json Ratio(uint64_t bytes, uint64_t tile_bytes) {
  if (tile_bytes == 0) return nlohmann::json(nullptr);
  return nlohmann::json(static_cast<double>(bytes) / static_cast<double>(tile_bytes));
}

// A map in grey (occupied black, free white, unknown grey) with each robot's path (same frame).
Status WriteFusedPng(const grid::OccupancyGrid& map, const FleetRunResult& run,
                     const std::string& path) {
  if (map.empty()) return NotFoundError("no fused map was received");
  cv::Mat image(map.height(), map.width(), CV_8UC3);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const grid::CellState state = map.StateAt(x, y);
      const uint8_t grey = state == grid::CellState::kOccupied ? 0
                           : state == grid::CellState::kFree   ? 255
                                                               : 180;
      // Image row 0 is the top; grid row 0 the bottom.
      image.at<cv::Vec3b>(map.height() - 1 - y, x) = cv::Vec3b(grey, grey, grey);
    }
  }
  const cv::Scalar colours[] = {{220, 60, 20}, {20, 140, 240}, {40, 170, 40}, {200, 40, 200},
                                {0, 200, 220}, {120, 90, 30},  {60, 60, 220}, {150, 150, 0}};
  int index = 0;
  for (const auto& [name, robot] : run.robots) {
    std::vector<cv::Point> points;
    for (const Pose2& pose : robot.path) {
      const auto cell = map.CellAt(pose.translation());
      if (cell) points.emplace_back(cell->x, map.height() - 1 - cell->y);
    }
    if (points.size() >= 2) {
      cv::polylines(image, points, false, colours[index % 8], 2, cv::LINE_AA);
    }
    ++index;
  }
  return grid::WriteImageFile(path, image);
}

std::string Seconds(const std::optional<double>& value) {
  return value ? fmt::format("{:.1f}", *value) : std::string("never");
}

// b - a when both happened.
std::optional<double> Between(const std::optional<double>& a, const std::optional<double>& b) {
  if (!a || !b) return std::nullopt;
  return *b - *a;
}

std::string QualityRow(const std::string& name, const metrics::QualityScores& quality) {
  return fmt::format("| {} | {} | {} | {} | {} | {} |\n", name, Percent(quality.map_score),
                     Percent(quality.cross_correlation), Percent(quality.pearson_occupied),
                     Percent(quality.occupied_picture_distance),
                     Percent(quality.unoccupied_picture_distance));
}

nlohmann::json QualityJson(const metrics::QualityScores& quality) {
  return {{"ms", Json(quality.map_score)},
          {"cc", Json(quality.cross_correlation)},
          {"pc", Json(quality.pearson_occupied)},
          {"opdf", Json(quality.occupied_picture_distance)},
          {"updf", Json(quality.unoccupied_picture_distance)}};
}

// The placement part of a run with robots at unknown poses: a markdown section, the JSON, the
// CSV rows and the summary's sentence.
struct PlacementReport {
  std::string md;
  nlohmann::json json;
  std::string csv;
  std::string summary;
};

StatusOr<PlacementReport> ReportPlacements(const FleetRunResult& tiles,
                                           const metrics::QualityScores& quality,
                                           const grid::OccupancyGrid& truth,
                                           const std::optional<FleetRunResult>& known_poses) {
  PlacementReport out;
  const auto anchor = tiles.robots.find(tiles.anchor);
  const bool anchored = anchor != tiles.robots.end() && anchor->second.placement.has_value();
  out.md = fmt::format(
      "## Placement (robots at unknown poses)\n\n"
      "Each robot's SLAM map frame is the terrain's frame moved by a seeded random rigid "
      "transform (true world_from_map below: x, y in metres, yaw in degrees; only the simulator "
      "and this observer know it); every agent ran `--unplaced` and the server placed them (rt/"
      "fleetmap/robot_frames). {}\n\n"
      "*joined*: the robot's first status. *shared*: the first check (about once a second) at "
      "which at least {:.0f} % of the robot's known cells (read from its tiles on a 0.1 m grid, "
      "carried into the terrain's frame with the true transforms) lay on known cells of the "
      "robots placed at that moment (the share it had then in brackets; the anchor needs none). "
      "*error*: at the centroid of the robot's known cells at the end of the run, the distance "
      "between where its placement and the truth (inverse(world_from_map of the anchor) * "
      "world_from_map of the robot) put that point, in {:.0f} cm cells, and the yaw error. Times "
      "are seconds since the run started.\n\n"
      "| robot | true world_from_map | state | confidence | placed against | joined | shared | "
      "placed | joined -> placed | shared -> placed | error (cells) | yaw error (deg) |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n",
      anchored ? fmt::format("Robot {} anchored the fleet frame.", tiles.anchor)
               : std::string("No robot anchored the fleet frame."),
      100.0 * kSharedFraction, 100.0 * truth.resolution());
  out.csv =
      "robot,true_x,true_y,true_yaw_deg,state,confidence,placed_against,placements,joined_s,"
      "shared_s,shared_fraction,placed_s,joined_to_placed_s,shared_to_placed_s,error_cells,"
      "yaw_error_deg,known_cells\n";
  int placed = 0;
  std::optional<double> worst_cells, worst_yaw, slowest_join, slowest_share;
  const auto max = [](std::optional<double>* into, const std::optional<double>& value) {
    if (value) *into = std::max(into->value_or(*value), *value);
  };
  const auto csv_number = [](const std::optional<double>& value) {
    return value ? fmt::format("{:.3f}", *value) : std::string();
  };
  for (const auto& [name, robot] : tiles.robots) {
    if (!robot.placement) continue;
    const RobotPlacement& p = *robot.placement;
    const std::optional<PlacementError> placement_error =
        anchored
            ? PlacementErrorOf(p, anchor->second.placement->true_world_from_map, truth.resolution())
            : std::nullopt;
    // Plain values from here: GCC's -Wmaybe-uninitialized misreads optionals copied into JSON.
    const bool measured = placement_error.has_value();
    const PlacementError error = placement_error.value_or(PlacementError{});
    const auto join_to_place = Between(p.joined_s, p.placed_s);
    const auto share_to_place = Between(p.shared_s, p.placed_s);
    placed += p.placed_s.has_value();
    if (measured) {
      worst_cells = std::max(worst_cells.value_or(0.0), error.cells);
      worst_yaw = std::max(worst_yaw.value_or(0.0), error.yaw_deg);
    }
    const std::string cells = measured ? fmt::format("{:.2f}", error.cells) : std::string();
    const std::string yaw = measured ? fmt::format("{:.2f}", error.yaw_deg) : std::string();
    max(&slowest_join, join_to_place);
    max(&slowest_share, share_to_place);
    const double true_yaw_deg = p.true_world_from_map.yaw * 180.0 / M_PI;
    out.md += fmt::format(
        "| {} | {:.2f}, {:.2f}, {:.1f} | {} | {:.2f} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
        name, p.true_world_from_map.x, p.true_world_from_map.y, true_yaw_deg, p.state, p.confidence,
        p.placed_against.empty() ? "-" : p.placed_against, Seconds(p.joined_s),
        name == tiles.anchor ? std::string("-")
        : p.shared_s ? fmt::format("{} ({:.0f} %)", Seconds(p.shared_s), 100.0 * p.shared_fraction)
                     : fmt::format("never ({:.0f} % at the end)", 100.0 * p.shared_fraction),
        Seconds(p.placed_s), Seconds(join_to_place),
        share_to_place ? Seconds(share_to_place) : std::string("-"),
        measured ? cells : std::string("-"), measured ? yaw : std::string("-"));
    out.csv += fmt::format(
        "{},{:.4f},{:.4f},{:.4f},{},{:.4f},{},{},{},{},{:.4f},{},{},{},{},{},{}\n", name,
        p.true_world_from_map.x, p.true_world_from_map.y, true_yaw_deg, p.state, p.confidence,
        p.placed_against, p.placements, csv_number(p.joined_s), csv_number(p.shared_s),
        p.shared_fraction, csv_number(p.placed_s), csv_number(join_to_place),
        csv_number(share_to_place), cells, yaw, p.known_cells);
    out.json["per_robot"][name] = {
        {"true_world_from_map",
         {{"x", p.true_world_from_map.x},
          {"y", p.true_world_from_map.y},
          {"yaw", p.true_world_from_map.yaw}}},
        {"fleet_from_map",
         {{"x", p.fleet_from_map.x}, {"y", p.fleet_from_map.y}, {"yaw", p.fleet_from_map.yaw}}},
        {"state", p.state},
        {"placed", p.placed_s.has_value()},
        {"confidence", p.confidence},
        {"placed_against", p.placed_against},
        {"placements", p.placements},
        {"joined_s", Json(p.joined_s)},
        {"shared_s", Json(p.shared_s)},
        {"shared_fraction", p.shared_fraction},
        {"placed_s", Json(p.placed_s)},
        {"joined_to_placed_s", Json(join_to_place)},
        {"shared_to_placed_s", Json(share_to_place)},
        {"error_cells", measured ? nlohmann::json(error.cells) : nlohmann::json(nullptr)},
        {"yaw_error_deg", measured ? nlohmann::json(error.yaw_deg) : nlohmann::json(nullptr)},
        {"known_cells", p.known_cells}};
  }
  out.json["anchor"] = tiles.anchor;
  out.json["robots_placed"] = placed;
  out.md += fmt::format(
      "\nThe fused map is in the anchor's map frame: it was carried into the terrain's frame with "
      "the anchor's true world_from_map (one rigid nearest-neighbour resample) to be scored "
      "against the ground truth{}.\n\n",
      known_poses ? ", beside the same scenario (seed, terrain, duration) with known poses" : "");
  out.md += "| run | MS | CC | PC | OPDF | UPDF |\n|---|---|---|---|---|---|\n";
  out.md += QualityRow("unknown poses (placed by the server)", quality);
  std::string known_summary;
  if (known_poses) {
    FLEETMAP_ASSIGN_OR_RETURN(const metrics::QualityScores known,
                              metrics::CompareMaps(ResampleOnto(known_poses->fused, truth), truth));
    out.md += QualityRow("known poses (one shared frame)", known);
    out.json["known_poses_quality"] = QualityJson(known);
    known_summary = fmt::format("; with known poses MS {} OPDF {} UPDF {}",
                                Percent(known.map_score), Percent(known.occupied_picture_distance),
                                Percent(known.unoccupied_picture_distance));
  }
  out.md += "\n";
  out.summary = fmt::format(
      "Unknown poses: {} of {} robots placed (anchor {}); joined -> placed at most {} s, shared "
      "-> placed at most {} s; error at most {} cells and {} deg{}.",
      placed, tiles.robots.size(), tiles.anchor.empty() ? "none" : tiles.anchor,
      Seconds(slowest_join), slowest_share ? Seconds(slowest_share) : std::string("-"),
      worst_cells ? fmt::format("{:.2f}", *worst_cells) : std::string("-"),
      worst_yaw ? fmt::format("{:.2f}", *worst_yaw) : std::string("-"), known_summary);
  return out;
}

}  // namespace

grid::OccupancyGrid ResampleOnto(const grid::OccupancyGrid& fused, const grid::OccupancyGrid& truth,
                                 const Transform2& fleet_from_world) {
  grid::OccupancyGrid out(truth.width(), truth.height(), truth.resolution(), truth.origin(),
                          grid::kUnknownValue);
  sim::ResampleRigid(fused, fleet_from_world, &out);
  return out;
}

std::optional<PlacementError> PlacementErrorOf(const RobotPlacement& placement,
                                               const Pose2& world_from_anchor, double resolution) {
  if (!placement.placed_s || !placement.known_centroid) return std::nullopt;
  const Transform2 truth =
      world_from_anchor.ToTransform().inverse() * placement.true_world_from_map.ToTransform();
  const Point2& centroid = *placement.known_centroid;
  const Pose2 true_fleet_from_map = Pose2::FromTransform(truth);
  return PlacementError{
      .cells = (placement.fleet_from_map.ToTransform() * centroid - truth * centroid).norm() /
               resolution,
      .yaw_deg = std::abs(NormalizeAngle(placement.fleet_from_map.yaw - true_fleet_from_map.yaw)) *
                 180.0 / M_PI};
}

std::optional<double> Percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  const size_t rank = static_cast<size_t>(std::ceil(p / 100.0 * values.size()));
  return values[std::clamp<size_t>(rank, 1, values.size()) - 1];
}

StatusOr<std::string> WriteFleetReport(const FleetSimOptions& options, const FleetRunResult& tiles,
                                       const std::optional<FleetRunResult>& compared,
                                       const grid::OccupancyGrid& truth, const std::string& out_dir,
                                       const std::optional<FleetRunResult>& known_poses) {
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) return NotFoundError(out_dir + ": " + error.message());

  // Without an anchor (robots at unknown poses, none placed) the fused map sits nowhere.
  const grid::OccupancyGrid fused_in_world =
      tiles.fleet_from_world
          ? ResampleOnto(tiles.fused, truth, *tiles.fleet_from_world)
          : grid::OccupancyGrid(truth.width(), truth.height(), truth.resolution(), truth.origin());
  FLEETMAP_ASSIGN_OR_RETURN(const metrics::QualityScores quality,
                            metrics::CompareMaps(fused_in_world, truth));
  std::optional<PlacementReport> placements;
  if (!options.sim_frames.empty()) {
    FLEETMAP_ASSIGN_OR_RETURN(placements, ReportPlacements(tiles, quality, truth, known_poses));
  }
  const auto p50 = Percentile(tiles.latencies_ms, 50);
  const auto p95 = Percentile(tiles.latencies_ms, 95);
  const auto p99 = Percentile(tiles.latencies_ms, 99);
  const std::string headline = HeadlineRatio(tiles.total_bytes, tiles.baselines);
  const std::string png = out_dir + "/fused.png";
  // Robots at unknown poses: the map and paths in the terrain's frame.
  const Status png_written =
      WriteFusedPng(options.sim_frames.empty() ? tiles.fused : fused_in_world, tiles, png);

  std::string md = fmt::format(
      "# fleetmap sim: {} robots, {} {} m, seed {}\n\n"
      "Each robot is a fleetmap-agent process exploring the terrain with the built-in simulator "
      "({} scans/s); a fleetmap-server fuses their tiles; all over DDS on loopback for {:.0f} "
      "s.\n\n",
      options.robots, sim::TerrainKindName(options.kind), options.size, options.seed,
      options.scans_per_second, std::chrono::duration<double>(options.duration).count());
  md += fmt::format(
      "## Bytes on the wire\n\nVector tiles against the ROS-native grid wires at the same map "
      "changes, as each agent measured them (payload bytes of the samples each wire would have "
      "written; in brackets, how many times the tiles' bytes): {}.\n\n",
      headline);
  md += "| robot | tiles: bytes | tile updates | map changes |";
  for (const BaselineBytes& baseline : Baselines({})) {
    md.append(" ").append(baseline.name).append(" |");
  }
  md += "\n|---|---|---|---|---|---|---|---|---|\n";
  const auto row = [&](const std::string& name, uint64_t bytes, const std::string& updates,
                       const WireBaselines& measured) {
    md += fmt::format("| {} | {} | {} | {} |", name, bytes, updates, measured.events);
    for (const BaselineBytes& baseline : Baselines(measured)) {
      md.append(" ").append(BytesAndRatio(baseline.bytes, bytes)).append(" |");
    }
    md += "\n";
  };
  for (const auto& [name, robot] : tiles.robots) {
    row(name, robot.bytes, std::to_string(robot.updates), robot.baselines);
  }
  row("**total**", tiles.total_bytes, "", tiles.baselines);
  if (compared) {
    uint64_t whole = 0, updates = 0;
    for (const auto& [name, robot] : compared->robots) {
      whole += robot.whole_grids;
      updates += robot.updates;
    }
    md += fmt::format(
        "\nThe same scenario run for real with `--wire {}` (its own map changes, which differ "
        "from the tile run's with timing): {} bytes ({} whole grids and {} patches), {:.1f}x the "
        "tile run's bytes.\n",
        compared->wire, compared->total_bytes, whole, updates - whole,
        tiles.total_bytes > 0 ? static_cast<double>(compared->total_bytes) / tiles.total_bytes
                              : 0.0);
  }
  md += "\n";
  md += fmt::format(
      "## Update latency\n\nRobot tile published -> fused tile received by another process "
      "(the observer), {} samples: p50 {}, p95 {}, p99 {}.\n\n",
      tiles.latencies_ms.size(), Ms(p50), Ms(p95), Ms(p99));
  md += fmt::format(
      "## Fused map against the ground truth\n\nMS {}, CC {}, PC {}, OPDF {}, UPDF {}.\n\n",
      Percent(quality.map_score), Percent(quality.cross_correlation),
      Percent(quality.pearson_occupied), Percent(quality.occupied_picture_distance),
      Percent(quality.unoccupied_picture_distance));
  if (placements) md += placements->md;
  std::optional<ShardComparison> shards;
  if (options.shards >= 2) {
    FLEETMAP_ASSIGN_OR_RETURN(shards, CompareShardedMap(tiles.fused, tiles.reference_fused,
                                                        tiles.shard_regions, kSimTileSize));
    md += shards->Markdown(options.shards);
  }
  md += fmt::format(
      "## Server\n\nCPU {:.2f} s over {:.0f} s ({:.0f} % of one core), peak memory "
      "{:.1f} MB.\n\n",
      tiles.server_cpu_seconds, tiles.seconds,
      100.0 * tiles.server_cpu_seconds / std::max(1e-9, tiles.seconds),
      tiles.server_peak_rss_bytes / 1e6);
  md +=
      png_written.ok() ? "![fused map](fused.png)\n" : "No image: " + png_written.message() + "\n";
  FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(out_dir + "/report.md", md));

  nlohmann::json json = {{"robots", options.robots},
                         {"terrain", std::string(sim::TerrainKindName(options.kind))},
                         {"size_m", options.size},
                         {"seed", options.seed},
                         {"duration_s", std::chrono::duration<double>(options.duration).count()},
                         {"tiles_total_bytes", tiles.total_bytes},
                         {"map_changes", tiles.baselines.events},
                         {"baselines_pending_patches", tiles.baselines.patches_pending},
                         {"latency_ms",
                          {{"samples", tiles.latencies_ms.size()},
                           {"p50", Json(p50)},
                           {"p95", Json(p95)},
                           {"p99", Json(p99)}}},
                         {"quality", QualityJson(quality)},
                         {"server",
                          {{"cpu_seconds", tiles.server_cpu_seconds},
                           {"peak_rss_bytes", tiles.server_peak_rss_bytes},
                           {"wall_seconds", tiles.seconds}}}};
  for (const BaselineBytes& baseline : Baselines(tiles.baselines)) {
    json["baselines"][baseline.key] = {{"name", baseline.name},
                                       {"bytes", baseline.bytes},
                                       {"over_tiles", Ratio(baseline.bytes, tiles.total_bytes)}};
  }
  const BaselineBytes smallest = SmallestBaseline(tiles.baselines);
  json["smallest_baseline"] = {{"key", smallest.key},
                               {"bytes", smallest.bytes},
                               {"over_tiles", Ratio(smallest.bytes, tiles.total_bytes)}};
  if (compared) {
    json["compared_run"] = {{"wire", compared->wire},
                            {"total_bytes", compared->total_bytes},
                            {"over_tiles", Ratio(compared->total_bytes, tiles.total_bytes)}};
  }
  for (const auto& [name, robot] : tiles.robots) {
    json["per_robot"][name] = {{"bytes", robot.bytes}, {"updates", robot.updates}};
    for (const BaselineBytes& baseline : Baselines(robot.baselines)) {
      json["per_robot"][name]["baselines"][baseline.key] = baseline.bytes;
    }
  }
  if (shards) {
    json["shards"] = {{"shards", options.shards},
                      {"cells", shards->cells},
                      {"differing", shards->differing},
                      {"differing_near_border", shards->differing_near_border}};
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(out_dir + "/server.log", tiles.server_output));
  }
  if (placements) {
    json["unknown_poses"] = placements->json;
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(out_dir + "/placement.csv", placements->csv));
    // The server's own account of each registration (placed, refused, revised).
    FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(out_dir + "/server.log", tiles.server_output));
  }
  FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(out_dir + "/report.json", json.dump(2) + "\n"));

  const std::string shard_summary =
      shards ? fmt::format(
                   "{} shards: {} of {} cells differ from one server's map in the same run "
                   "({} near a border)\n",
                   options.shards, shards->differing, shards->cells, shards->differing_near_border)
             : std::string();
  return fmt::format(
      "{}{}{} robots, {} {} m, {:.0f} s: {} bytes of vector tiles on the wire, {}; latency p50 {} "
      "p95 {} p99 {}; fused map MS {} OPDF {} UPDF {}; server {:.0f} % of a core, {:.0f} MB.\n"
      "Report: {}/report.md, image: {}",
      placements ? placements->summary + "\n" : std::string(), shard_summary, options.robots,
      sim::TerrainKindName(options.kind), options.size, tiles.seconds, tiles.total_bytes, headline,
      Ms(p50), Ms(p95), Ms(p99), Percent(quality.map_score),
      Percent(quality.occupied_picture_distance), Percent(quality.unoccupied_picture_distance),
      100.0 * tiles.server_cpu_seconds / std::max(1e-9, tiles.seconds),
      tiles.server_peak_rss_bytes / 1e6, out_dir, png_written.ok() ? png : "none");
}

}  // namespace fleetmap::bench
