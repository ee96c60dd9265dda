#include "robot_agent/sim_map_source.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

#include "common/sim/exploration_simulator.hpp"
#include "common/sim/frame_resample.hpp"
#include "common/sim/start_poses.hpp"
#include "common/sim/terrain_generator.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::agent {

Status SimOptions::Validate() const {
  if (robots < 1 || robot_index < 0 || robot_index >= robots) {
    return InvalidArgumentError("--sim-robot-index must be in 0..--sim-robots - 1");
  }
  if (!std::isfinite(scans_per_second) || scans_per_second <= 0.0) {
    return InvalidArgumentError("--sim-rate must be a positive number of scans per second");
  }
  if (scans_per_map < 1) return InvalidArgumentError("scans per map must be >= 1");
  if (!std::isfinite(resolution) || resolution <= 0.0) {
    return InvalidArgumentError("--sim-resolution must be a positive number of metres");
  }
  if (!world_from_map.finite()) return InvalidArgumentError("--sim-frame is not finite");
  return Status::Ok();
}

StatusOr<std::unique_ptr<SimMapSource>> SimMapSource::Create(const SimOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  sim::TerrainOptions terrain_options;
  terrain_options.kind = options.kind;
  terrain_options.size = options.size;
  terrain_options.seed = options.seed;
  FLEETMAP_ASSIGN_OR_RETURN(const sim::TerrainGenerator generator,
                            sim::TerrainGenerator::Create(terrain_options));
  const sim::Terrain terrain = generator.Generate();
  FLEETMAP_ASSIGN_OR_RETURN(grid::OccupancyGrid truth,
                            sim::RasterizeTerrain(terrain, options.resolution));
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<Pose2> starts,
                            sim::SpreadStarts(truth, terrain.start, options.robots));
  std::unique_ptr<SimMapSource> source(new SimMapSource(options));
  source->pose_ = Pose2::FromTransform(options.world_from_map.ToTransform().inverse() *
                                       starts[options.robot_index].ToTransform());
  source->thread_ = std::thread(
      [raw = source.get(), truth = std::move(truth),
       start = starts[options.robot_index]]() mutable { raw->Explore(std::move(truth), start); });
  return source;
}

SimMapSource::~SimMapSource() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void SimMapSource::Explore(grid::OccupancyGrid truth, Pose2 start) {
  sim::ExplorationOptions options;
  options.seed = options_.seed * 1000u + static_cast<uint32_t>(options_.robot_index);
  auto simulator = sim::ExplorationSimulator::Create(options);
  if (!simulator.ok()) {
    spdlog::error("simulated robot: {}", simulator.status().message());
    finished_.store(true);
    return;
  }
  const auto begin = std::chrono::steady_clock::now();
  const auto scan_period = std::chrono::duration<double>(1.0 / options_.scans_per_second);
  const bool own_frame = !(options_.world_from_map == Pose2{});
  const Transform2 map_from_world = options_.world_from_map.ToTransform().inverse();
  // The world-frame map in the robot's own frame, timed.
  const auto in_own_frame = [&](grid::OccupancyGrid world) {
    if (!own_frame) return world;
    const auto render_begin = std::chrono::steady_clock::now();
    grid::OccupancyGrid own = sim::ResampleIntoFrame(world, map_from_world);
    render_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - render_begin).count();
    ++renders_;
    return own;
  };
  const auto on_scan = [&](int scans, const Pose2& pose, const sim::OccupancyMapper& mapper) {
    std::optional<grid::OccupancyGrid> snapshot;
    if (scans % options_.scans_per_map == 0) snapshot = in_own_frame(mapper.ToGrid());
    {
      std::lock_guard lock(mutex_);
      pose_ = Pose2::FromTransform(map_from_world * pose.ToTransform());
      if (snapshot) latest_ = std::move(snapshot);
    }
    std::this_thread::sleep_until(
        begin + std::chrono::duration_cast<std::chrono::nanoseconds>(scan_period * scans));
    return !stop_.load();
  };
  auto result = simulator->Run(truth, start, {}, on_scan);
  if (result.ok()) {
    grid::OccupancyGrid final_map = in_own_frame(std::move(result->map));
    std::lock_guard lock(mutex_);
    latest_ = std::move(final_map);  // the final map, whatever the snapshot period
    spdlog::info("simulated robot {}: {} after {} scans and {:.0f} m", options_.robot_index,
                 result->explored ? "explored the terrain" : "stopped", result->scans,
                 result->distance);
  } else {
    spdlog::error("simulated robot: {}", result.status().message());
  }
  if (renders_ > 0) {
    spdlog::info("simulated robot {}: {} maps resampled into its own frame, {:.2f} ms each",
                 options_.robot_index, renders_, 1000.0 * render_seconds_ / renders_);
  }
  finished_.store(true);
}

std::optional<grid::OccupancyGrid> SimMapSource::Poll() {
  std::lock_guard lock(mutex_);
  std::optional<grid::OccupancyGrid> out = std::move(latest_);
  latest_.reset();
  return out;
}

std::string SimMapSource::Describe() const {
  return "simulated " + std::string(sim::TerrainKindName(options_.kind)) + " " +
         std::to_string(static_cast<int>(options_.size)) + " m, seed " +
         std::to_string(options_.seed) + ", robot " + std::to_string(options_.robot_index) +
         " of " + std::to_string(options_.robots);
}

Pose2 SimMapSource::pose() const {
  std::lock_guard lock(mutex_);
  return pose_;
}

void SimOptions::Describe(OptionsPrinter& out) const {
  out.Add("kind", sim::TerrainKindName(kind));
  out.Add("size", size);
  out.Add("seed", seed);
  out.Add("robot_index", robot_index);
  out.Add("robots", robots);
  out.Add("resolution", resolution);
  out.Add("scans_per_second", scans_per_second);
  out.Add("scans_per_map", scans_per_map);
  out.Add("world_from_map", world_from_map);
}

}  // namespace fleetmap::agent
