#include "common/sim/occupancy_mapper.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "common/grid/line_iterator.hpp"

namespace fleetmap::sim {
namespace {

float Logit(double p) { return static_cast<float>(std::log(p / (1.0 - p))); }

}  // namespace

StatusOr<OccupancyMapper> OccupancyMapper::Create(int width, int height, double resolution,
                                                  const Pose2& origin,
                                                  const MapperOptions& options) {
  if (width <= 0 || height <= 0 || !(resolution > 0.0) || origin.yaw != 0.0) {
    return InvalidArgumentError("mapper geometry must have a positive size and resolution, yaw 0");
  }
  if (!(options.log_odds_hit > 0.0f) || !(options.log_odds_miss < 0.0f)) {
    return InvalidArgumentError("mapper log_odds_hit must be > 0 and log_odds_miss < 0");
  }
  if (!(options.log_odds_min < 0.0f) || !(options.log_odds_max > 0.0f)) {
    return InvalidArgumentError("mapper log_odds_min must be < 0 and log_odds_max > 0");
  }
  if (!(options.free_probability > 0.0 && options.free_probability <= 0.5 &&
        options.occupied_probability >= 0.5 && options.occupied_probability < 1.0)) {
    return InvalidArgumentError(
        "mapper free_probability must be in (0, 0.5] and occupied_probability in [0.5, 1)");
  }
  if (options.block_size < 1) return InvalidArgumentError("mapper block_size must be >= 1");
  return OccupancyMapper(width, height, resolution, origin, options);
}

OccupancyMapper::OccupancyMapper(int width, int height, double resolution, const Pose2& origin,
                                 const MapperOptions& options)
    : width_(width),
      height_(height),
      resolution_(resolution),
      origin_(origin),
      options_(options),
      occupied_log_odds_(Logit(options.occupied_probability)),
      free_log_odds_(Logit(options.free_probability)),
      log_odds_(static_cast<size_t>(width) * height, 0.0f),
      blocks_x_((width + options.block_size - 1) / options.block_size),
      blocks_y_((height + options.block_size - 1) / options.block_size),
      block_occupied_(static_cast<size_t>(blocks_x_) * blocks_y_, 0),
      block_free_(static_cast<size_t>(blocks_x_) * blocks_y_, 0) {}

void OccupancyMapper::Update(int x, int y, float delta) {
  float& l = log_odds_[Index(x, y)];
  const MappedState before = StateOf(l);
  l = std::clamp(l + delta, options_.log_odds_min, options_.log_odds_max);
  const MappedState after = StateOf(l);
  if (before == after) return;
  const size_t block = BlockIndex(x / options_.block_size, y / options_.block_size);
  if (before == MappedState::kOccupied) --block_occupied_[block];
  if (before == MappedState::kFree) --block_free_[block];
  if (after == MappedState::kOccupied) ++block_occupied_[block];
  if (after == MappedState::kFree) ++block_free_[block];
}

// Misses on every cell of the line from (x0, y0) to (x1, y1) before its end, a hit or a miss on
// the end cell. Cells outside the grid are skipped (a drifted pose can look past the border).
void OccupancyMapper::TraceBeam(int x0, int y0, int x1, int y1, bool hit) {
  const grid::CellIndex end{x1, y1};
  const float miss = options_.log_odds_miss;
  for (const grid::CellIndex cell : grid::GridLine({x0, y0}, end)) {
    const bool inside = cell.x >= 0 && cell.y >= 0 && cell.x < width_ && cell.y < height_;
    if (!inside) continue;
    Update(cell.x, cell.y, cell == end && hit ? options_.log_odds_hit : miss);
  }
}

void OccupancyMapper::Integrate(const LaserScan& scan, const Pose2& map_from_sensor) {
  const double inv_res = 1.0 / resolution_;
  const double ox = (map_from_sensor.x - origin_.x) * inv_res;
  const double oy = (map_from_sensor.y - origin_.y) * inv_res;
  const int x0 = static_cast<int>(std::floor(ox));
  const int y0 = static_cast<int>(std::floor(oy));
  for (size_t i = 0; i < scan.ranges.size(); ++i) {
    const float range = scan.ranges[i];
    const bool hit = range != kNoReturn;
    const double length = hit ? range * inv_res + 0.5 : scan.max_range * inv_res;
    const double angle = map_from_sensor.yaw + scan.angle_min + i * scan.angle_increment;
    const int x1 = static_cast<int>(std::floor(ox + length * std::cos(angle)));
    const int y1 = static_cast<int>(std::floor(oy + length * std::sin(angle)));
    TraceBeam(x0, y0, x1, y1, hit);
  }
}

grid::OccupancyGrid OccupancyMapper::ToGrid() const {
  grid::OccupancyGrid grid(width_, height_, resolution_, origin_, grid::kUnknownValue);
  std::vector<int8_t>& data = grid.mutable_data();
  for (size_t i = 0; i < log_odds_.size(); ++i) {
    switch (StateOf(log_odds_[i])) {
      case MappedState::kOccupied:
        data[i] = grid::kOccupiedValue;
        break;
      case MappedState::kFree:
        data[i] = grid::kFreeValue;
        break;
      case MappedState::kUnknown:
        break;
    }
  }
  return grid;
}

}  // namespace fleetmap::sim
