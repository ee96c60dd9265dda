#pragma once

// Occupancy-grid mapping from laser scans by log-odds ray casting (the inverse sensor model of
// Thrun, Burgard and Fox, "Probabilistic Robotics", ch. 9): along each beam, the cells before the
// end point get `log_odds_miss`, the end cell `log_odds_hit` (beams without a return clear up to
// max range). A beam's end point is taken half a cell behind the measured range, so that a return
// from a surface lands in the surface's own cell rather than, by rounding, in the free cell before
// it. Cells are walked with an integer Bresenham line (grid::GridLine). Values are clamped so that
// a cell can change its mind (a moved object, a speckle cleared later).
//
// It also keeps, per square block of `block_size` cells, how many cells are occupied and free, up
// to date on every change of a cell's state: the frontier planner reads those counts instead of
// rescanning the whole grid before each plan.
//
// Thread-safety: not thread-safe; one owner.

#include <cstdint>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/sim/laser_scanner.hpp"

namespace fleetmap::sim {

struct MapperOptions {
  float log_odds_hit = 0.85f;   // > 0
  float log_odds_miss = -0.4f;  // < 0
  float log_odds_min = -2.0f;   // clamp, < 0
  float log_odds_max = 3.5f;    // clamp, > 0
  // A cell reads occupied above this probability and free below free_probability (trinary
  // output, same defaults as grid::StateThresholds).
  double occupied_probability = 0.65;
  double free_probability = 0.25;
  int block_size = 4;  // cells per side of a planner block, >= 1
};

enum class MappedState : uint8_t { kUnknown, kFree, kOccupied };

class OccupancyMapper {
 public:
  // The map's geometry (the ground truth's, so maps compare cell for cell). Errors
  // (kInvalidArgument) name the option: bad log odds, thresholds, block size, geometry.
  static StatusOr<OccupancyMapper> Create(int width, int height, double resolution,
                                          const Pose2& origin, const MapperOptions& options);

  // Integrates a scan taken from `map_from_sensor` (the robot's belief, not the truth).
  void Integrate(const LaserScan& scan, const Pose2& map_from_sensor);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  const Pose2& origin() const { return origin_; }
  MappedState StateAt(int x, int y) const { return StateOf(log_odds_[Index(x, y)]); }
  float LogOddsAt(int x, int y) const { return log_odds_[Index(x, y)]; }

  int block_size() const { return options_.block_size; }
  int blocks_x() const { return blocks_x_; }
  int blocks_y() const { return blocks_y_; }
  int BlockOccupied(int bx, int by) const { return block_occupied_[BlockIndex(bx, by)]; }
  int BlockFree(int bx, int by) const { return block_free_[BlockIndex(bx, by)]; }

  // The trinary map: 100 occupied, 0 free, -1 unknown.
  grid::OccupancyGrid ToGrid() const;

 private:
  OccupancyMapper(int width, int height, double resolution, const Pose2& origin,
                  const MapperOptions& options);

  size_t Index(int x, int y) const { return static_cast<size_t>(y) * width_ + x; }
  size_t BlockIndex(int bx, int by) const { return static_cast<size_t>(by) * blocks_x_ + bx; }
  MappedState StateOf(float l) const {
    return l > occupied_log_odds_
               ? MappedState::kOccupied
               : (l < free_log_odds_ ? MappedState::kFree : MappedState::kUnknown);
  }
  void Update(int x, int y, float delta);
  void TraceBeam(int x0, int y0, int x1, int y1, bool hit);

  int width_;
  int height_;
  double resolution_;
  Pose2 origin_;
  MapperOptions options_;
  float occupied_log_odds_;
  float free_log_odds_;
  std::vector<float> log_odds_;
  int blocks_x_;
  int blocks_y_;
  std::vector<int32_t> block_occupied_;
  std::vector<int32_t> block_free_;
};

}  // namespace fleetmap::sim
