#pragma once

// A robot's recent path in the fleet frame, kept as runs: a new run starts wherever the robot's
// map frame moved in the fleet frame (the server placed or revised it), so the page never draws a
// segment from a pose before a placement to one after it, which the robot never drove.

#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/core/types.hpp"

namespace fleetmap::view {

class RobotPath {
 public:
  // At most `max_points` points in all, each at least `spacing_m` from the previous one of its run.
  RobotPath(size_t max_points, double spacing_m);

  // The robot is at `here` in the fleet frame, seen through `fleet_from_map`.
  void Add(const Point2& here, const Pose2& fleet_from_map);

  // [[x0, y0, x1, y1, ...], ...]: every run, oldest first.
  nlohmann::json Json() const;
  // The points gained since the previous call, as runs: the first continues the newest run the
  // previous calls gave (empty when a new run began at once), each further one is a new run.
  // nullopt when none was gained.
  std::optional<nlohmann::json> TakeGained();

 private:
  size_t max_points_;
  double spacing_m_;
  std::deque<std::vector<Point2>> runs_;
  size_t points_ = 0;
  std::optional<Pose2> frame_;  // the newest point's fleet_from_map
  std::vector<std::vector<Point2>> gained_;
};

}  // namespace fleetmap::view
