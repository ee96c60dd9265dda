#include "bench/fleet/fleet_sim_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "bench/fleet/baseline_bytes.hpp"
#include "common/core/file_io.hpp"
#include "common/grid/image_file.hpp"
#include "common/metrics/map_quality.hpp"

namespace fleetmap::bench {
namespace {

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

// The fused map in grey (occupied black, free white, unknown grey) with each robot's path.
Status WriteFusedPng(const FleetRunResult& run, const std::string& path) {
  const grid::OccupancyGrid& map = run.fused;
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

}  // namespace

grid::OccupancyGrid ResampleOnto(const grid::OccupancyGrid& fused,
                                 const grid::OccupancyGrid& truth) {
  grid::OccupancyGrid out(truth.width(), truth.height(), truth.resolution(), truth.origin(),
                          grid::kUnknownValue);
  if (fused.empty()) return out;
  for (int y = 0; y < truth.height(); ++y) {
    for (int x = 0; x < truth.width(); ++x) {
      const auto cell = fused.CellAt(truth.CellCenter(x, y));
      if (cell) out.at(x, y) = fused.at(cell->x, cell->y);
    }
  }
  return out;
}

std::optional<double> Percentile(std::vector<double> values, double p) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  const size_t rank = static_cast<size_t>(std::ceil(p / 100.0 * values.size()));
  return values[std::clamp<size_t>(rank, 1, values.size()) - 1];
}

StatusOr<std::string> WriteFleetReport(const FleetSimOptions& options, const FleetRunResult& tiles,
                                       const std::optional<FleetRunResult>& compared,
                                       const grid::OccupancyGrid& truth,
                                       const std::string& out_dir) {
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) return NotFoundError(out_dir + ": " + error.message());

  FLEETMAP_ASSIGN_OR_RETURN(const metrics::QualityScores quality,
                            metrics::CompareMaps(ResampleOnto(tiles.fused, truth), truth));
  const auto p50 = Percentile(tiles.latencies_ms, 50);
  const auto p95 = Percentile(tiles.latencies_ms, 95);
  const auto p99 = Percentile(tiles.latencies_ms, 99);
  const std::string headline = HeadlineRatio(tiles.total_bytes, tiles.baselines);
  const std::string png = out_dir + "/fused.png";
  const Status png_written = WriteFusedPng(tiles, png);

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
                         {"quality",
                          {{"ms", Json(quality.map_score)},
                           {"cc", Json(quality.cross_correlation)},
                           {"pc", Json(quality.pearson_occupied)},
                           {"opdf", Json(quality.occupied_picture_distance)},
                           {"updf", Json(quality.unoccupied_picture_distance)}}},
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
  FLEETMAP_RETURN_IF_ERROR(WriteFileAtomically(out_dir + "/report.json", json.dump(2) + "\n"));

  return fmt::format(
      "{} robots, {} {} m, {:.0f} s: {} bytes of vector tiles on the wire, {}; latency p50 {} "
      "p95 {} p99 {}; fused map MS {} OPDF {} UPDF {}; server {:.0f} % of a core, {:.0f} MB.\n"
      "Report: {}/report.md, image: {}",
      options.robots, sim::TerrainKindName(options.kind), options.size, tiles.seconds,
      tiles.total_bytes, headline, Ms(p50), Ms(p95), Ms(p99), Percent(quality.map_score),
      Percent(quality.occupied_picture_distance), Percent(quality.unoccupied_picture_distance),
      100.0 * tiles.server_cpu_seconds / std::max(1e-9, tiles.seconds),
      tiles.server_peak_rss_bytes / 1e6, out_dir, png_written.ok() ? png : "none");
}

}  // namespace fleetmap::bench
