#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "common/core/options_printer.hpp"
#include "common/core/types.hpp"

namespace fleetmap::grid {

// The three states a planner cares about.
enum class CellState : uint8_t { kFree, kOccupied, kUnknown };

// Cell values follow nav_msgs/OccupancyGrid: -1 unknown, 0..100 probability of occupancy (%).
inline constexpr int8_t kUnknownValue = -1;
inline constexpr int8_t kFreeValue = 0;
inline constexpr int8_t kOccupiedValue = 100;

// How a probability reads as a state: occupied above `occupied`, free below `free`
// (both in [0, 1], as in a map_server YAML); in between and -1 read as unknown.
struct StateThresholds {
  double occupied = 0.65;
  double free = 0.25;

  void Describe(OptionsPrinter& out) const {
    out.Add("occupied", occupied);
    out.Add("free", free);
  }
};

CellState StateOf(int8_t value, const StateThresholds& thresholds = {});

// Whether two resolutions (metres per cell) are the same map resolution: equal within 1e-6 of
// the larger. A resolution crosses float32 fields (DDS messages, .vmap files) and decimal text
// (map YAML), and 0.05 must stay 0.05 through both; no two real map resolutions are this close.
bool SameResolution(double a, double b);

// Cell (x, y) with x along the grid's columns and y along its rows, (0, 0) at the origin.
struct CellIndex {
  int x = 0;
  int y = 0;
  friend bool operator==(const CellIndex&, const CellIndex&) = default;
};

struct StateCounts {
  int64_t occupied = 0;
  int64_t free = 0;
  int64_t unknown = 0;
};

// A 2D occupancy grid in a map frame, laid out as nav_msgs/OccupancyGrid: row-major, row 0 at the
// origin, `origin` the map-frame pose of cell (0, 0)'s outer corner. A cell's point is its centre.
// A value type: cheap to move, safe to copy, no shared state.
class OccupancyGrid {
 public:
  OccupancyGrid() = default;
  // Width and height are cells (>= 0), resolution metres per cell (> 0).
  OccupancyGrid(int width, int height, double resolution, Pose2 origin = {},
                int8_t fill = kUnknownValue);

  int width() const { return width_; }
  int height() const { return height_; }
  int64_t cell_count() const { return static_cast<int64_t>(width_) * height_; }
  double resolution() const { return resolution_; }
  const Pose2& origin() const { return origin_; }
  bool empty() const { return cell_count() == 0; }

  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  int8_t at(int x, int y) const { return data_[Index(x, y)]; }
  int8_t& at(int x, int y) { return data_[Index(x, y)]; }
  CellState StateAt(int x, int y, const StateThresholds& thresholds = {}) const {
    return StateOf(at(x, y), thresholds);
  }

  const std::vector<int8_t>& data() const { return data_; }
  std::vector<int8_t>& mutable_data() { return data_; }

  // Map-frame centre of a cell, and the cell containing a map-frame point (if inside the grid).
  Point2 CellCenter(int x, int y) const;
  std::optional<CellIndex> CellAt(const Point2& map_point) const;

  StateCounts CountStates(const StateThresholds& thresholds = {}) const;

  friend bool operator==(const OccupancyGrid&, const OccupancyGrid&) = default;

 private:
  size_t Index(int x, int y) const { return static_cast<size_t>(y) * width_ + x; }

  int width_ = 0;
  int height_ = 0;
  double resolution_ = 0.05;
  Pose2 origin_;
  std::vector<int8_t> data_;
};

}  // namespace fleetmap::grid
