#include "view/robot_path.hpp"

#include "view/map_json.hpp"

namespace fleetmap::view {

using nlohmann::json;

namespace {

template <typename Runs>
json RunsJson(const Runs& runs) {
  json out = json::array();
  for (const std::vector<Point2>& run : runs) out.push_back(FlatPoints(run));
  return out;
}

}  // namespace

RobotPath::RobotPath(size_t max_points, double spacing_m)
    : max_points_(max_points), spacing_m_(spacing_m) {}

void RobotPath::Add(const Point2& here, const Pose2& fleet_from_map) {
  const bool new_run = !frame_ || !(*frame_ == fleet_from_map);
  if (!new_run && (runs_.back().back() - here).norm() < spacing_m_) return;
  frame_ = fleet_from_map;
  if (gained_.empty()) gained_.emplace_back();  // what continues the page's newest run
  if (new_run) {
    runs_.emplace_back();
    gained_.emplace_back();
  }
  runs_.back().push_back(here);
  gained_.back().push_back(here);
  if (++points_ <= max_points_) return;
  std::vector<Point2>& oldest = runs_.front();
  oldest.erase(oldest.begin());
  --points_;
  if (oldest.empty()) runs_.pop_front();
}

json RobotPath::Json() const { return RunsJson(runs_); }

std::optional<json> RobotPath::TakeGained() {
  if (gained_.empty()) return std::nullopt;
  json runs = RunsJson(gained_);
  gained_.clear();
  return runs;
}

}  // namespace fleetmap::view
