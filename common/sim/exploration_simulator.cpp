#include "common/sim/exploration_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "common/sim/random.hpp"

namespace fleetmap::sim {
namespace {

// One exploration run: the robot, its sensors and its map.
class RobotRun {
 public:
  RobotRun(const ExplorationOptions& options, const LaserScanner& laser,
           const grid::OccupancyGrid& truth, OccupancyMapper mapper, SlamErrorModel error,
           FrontierPlanner planner, const Pose2& start,
           const std::function<void(const ExplorationProgress&)>& on_progress,
           const ScanObserver& on_scan)
      : options_(options),
        laser_(laser),
        truth_(truth),
        mapper_(std::move(mapper)),
        error_(std::move(error)),
        planner_(std::move(planner)),
        laser_random_(options.seed * 2246822519u + 1u),
        pose_(start),
        on_progress_(on_progress),
        on_scan_(on_scan) {
    const double r = options.robot_radius / truth.resolution() + 1.0;
    const int reach = static_cast<int>(std::ceil(r));
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        if (dx * dx + dy * dy <= r * r) footprint_.push_back({dx, dy});
      }
    }
  }

  ExplorationResult Explore() {
    Scan();
    if (options_.spin_at_goal) Spin();
    while (!BudgetSpent()) {
      const std::vector<Point2> path = planner_.Plan(mapper_, pose_.translation());
      if (path.size() < 2) {
        result_.explored = true;
        break;
      }
      FollowPath(path);
    }
    result_.map = mapper_.ToGrid();
    return std::move(result_);
  }

 private:
  bool BudgetSpent() const {
    return cancelled_ || result_.scans >= options_.max_scans ||
           result_.distance >= options_.max_distance;
  }

  void Scan() {
    const LaserScan scan = laser_.Scan(truth_, pose_, &laser_random_);
    const Pose2 belief = error_.Belief(pose_);
    mapper_.Integrate(scan, belief);
    result_.trajectory.push_back(pose_);
    result_.beliefs.push_back(belief);
    ++result_.scans;
    since_scan_ = 0.0;
    turned_since_scan_ = 0.0;
    if (on_progress_ && result_.scans % 100 == 0) {
      on_progress_({result_.scans, result_.distance, result_.goals_reached});
    }
    if (on_scan_ && !on_scan_(result_.scans, pose_, mapper_)) cancelled_ = true;
  }

  // Turns in place to `yaw`, scanning every scan_rotation radians.
  void TurnTo(double yaw) {
    double remaining = NormalizeAngle(yaw - pose_.yaw);
    while (std::abs(remaining) > 1e-6) {
      const double turn = std::clamp(remaining, -options_.scan_rotation, options_.scan_rotation);
      const double need = options_.scan_rotation - turned_since_scan_;
      const double part = std::abs(turn) > need ? std::copysign(need, turn) : turn;
      pose_.yaw = NormalizeAngle(pose_.yaw + part);
      remaining -= part;
      turned_since_scan_ += std::abs(part);
      error_.Advance(std::abs(part) * 0.3);
      if (turned_since_scan_ >= options_.scan_rotation - 1e-9) Scan();
    }
  }

  void Spin() {
    const double start = pose_.yaw;
    const int steps = static_cast<int>(std::ceil(2.0 * std::numbers::pi / options_.scan_rotation));
    for (int i = 1; i <= steps; ++i) {
      pose_.yaw = NormalizeAngle(start + 2.0 * std::numbers::pi * i / steps);
      error_.Advance(2.0 * std::numbers::pi / steps * 0.3);
      Scan();
    }
  }

  // Distance (metres) from `p` to the nearest occupied truth cell centre, capped just above the
  // robot's radius; 0 outside the grid.
  double Clearance(const Point2& p) const {
    const double res = truth_.resolution();
    const int cx = static_cast<int>(std::floor((p.x() - truth_.origin().x) / res));
    const int cy = static_cast<int>(std::floor((p.y() - truth_.origin().y) / res));
    double best = options_.robot_radius + res;
    for (const auto& [dx, dy] : footprint_) {
      const int x = cx + dx;
      const int y = cy + dy;
      if (!truth_.Contains(x, y)) return 0.0;
      if (truth_.at(x, y) < grid::kOccupiedValue / 2) continue;
      best = std::min(best, (truth_.CellCenter(x, y) - p).norm());
    }
    return best;
  }

  // A step is blocked when it ends closer than half the robot's radius to an obstacle and closer
  // than it started (a robot in a tight spot may always back out). The planner keeps
  // inflation_radius from every obstacle it knows; this check only stops the robot from driving
  // through an obstacle its map does not show yet. Half the radius, not the full one: the planner
  // works on 20 cm blocks and string-pulled legs, which may shave a door jamb by a few cm.
  bool Blocked(const Point2& from, const Point2& to) const {
    const double after = Clearance(to);
    return after < 0.5 * options_.robot_radius && after < Clearance(from) - 0.005;
  }

  // Moves one step straight away from the nearest obstacle, as a robot backs out of a tight spot
  // before it turns again. False if that step would not gain clearance.
  bool BackOff() {
    const double res = truth_.resolution();
    const Point2 p = pose_.translation();
    const int cx = static_cast<int>(std::floor((p.x() - truth_.origin().x) / res));
    const int cy = static_cast<int>(std::floor((p.y() - truth_.origin().y) / res));
    double best = std::numeric_limits<double>::infinity();
    Point2 nearest = p;
    for (const auto& [dx, dy] : footprint_) {
      const int x = cx + dx;
      const int y = cy + dy;
      if (!truth_.Contains(x, y) || truth_.at(x, y) < grid::kOccupiedValue / 2) continue;
      const Point2 c = truth_.CellCenter(x, y);
      if ((c - p).norm() < best) {
        best = (c - p).norm();
        nearest = c;
      }
    }
    if (!std::isfinite(best) || best < 1e-9) return false;
    const Point2 next = p + (p - nearest) / best * options_.step;
    if (Clearance(next) <= Clearance(p)) return false;
    pose_.x = next.x();
    pose_.y = next.y();
    since_scan_ += options_.step;
    result_.distance += options_.step;
    error_.Advance(options_.step);
    return true;
  }

  // Drives the path's legs until the goal, replan_distance, a collision or the budget.
  void FollowPath(const std::vector<Point2>& path) {
    constexpr int kMaxBackoffs = 5;
    int backoffs = 0;
    double driven = 0.0;
    for (size_t leg = 1; leg < path.size(); ++leg) {
      const Point2 target = path[leg];
      const Point2 offset = target - pose_.translation();
      if (offset.norm() > 1e-6) TurnTo(std::atan2(offset.y(), offset.x()));
      while (true) {
        if (BudgetSpent()) return;
        const Point2 to_target = target - pose_.translation();
        const double length = to_target.norm();
        if (length < 1e-6) break;
        const double step = std::min(options_.step, length);
        const Point2 next = pose_.translation() + to_target / length * step;
        if (Blocked(pose_.translation(), next) && backoffs < kMaxBackoffs && BackOff()) {
          ++backoffs;
          continue;
        }
        if (Blocked(pose_.translation(), next)) {
          ++result_.goals_failed;
          planner_.Blacklist(mapper_, path.back());
          Scan();
          return;
        }
        pose_.x = next.x();
        pose_.y = next.y();
        driven += step;
        since_scan_ += step;
        result_.distance += step;
        error_.Advance(step);
        if (since_scan_ >= options_.scan_distance - 1e-9) Scan();
        if (driven >= options_.replan_distance) {
          if (since_scan_ > 0.0) Scan();
          return;
        }
      }
    }
    ++result_.goals_reached;
    if (options_.spin_at_goal) {
      Spin();
    } else {
      Scan();
    }
    planner_.Blacklist(mapper_, path.back());
  }

  const ExplorationOptions& options_;
  const LaserScanner& laser_;
  const grid::OccupancyGrid& truth_;
  OccupancyMapper mapper_;
  SlamErrorModel error_;
  FrontierPlanner planner_;
  Random laser_random_;
  Pose2 pose_;
  const std::function<void(const ExplorationProgress&)>& on_progress_;
  const ScanObserver& on_scan_;
  bool cancelled_ = false;  // the observer asked to stop
  std::vector<std::pair<int, int>> footprint_;
  double since_scan_ = 0.0;
  double turned_since_scan_ = 0.0;
  ExplorationResult result_;
};

}  // namespace

StatusOr<ExplorationSimulator> ExplorationSimulator::Create(const ExplorationOptions& options) {
  FLEETMAP_ASSIGN_OR_RETURN(LaserScanner laser, LaserScanner::Create(options.laser));
  FLEETMAP_RETURN_IF_ERROR(SlamErrorModel::Create(options.error, 0).status());
  FLEETMAP_RETURN_IF_ERROR(FrontierPlanner::Create(options.frontier).status());
  FLEETMAP_RETURN_IF_ERROR(OccupancyMapper::Create(1, 1, 1.0, Pose2{}, options.mapper).status());
  if (!(options.robot_radius > 0.0) ||
      !(options.robot_radius < options.frontier.inflation_radius)) {
    return InvalidArgumentError(
        "exploration robot_radius must be > 0 and below frontier.inflation_radius");
  }
  if (!(options.planner_block > 0.0) || !std::isfinite(options.planner_block)) {
    return InvalidArgumentError("exploration planner_block must be > 0");
  }
  if (!(options.step > 0.0) || !(options.scan_distance > 0.0) || !(options.scan_rotation > 0.0) ||
      !(options.replan_distance > 0.0)) {
    return InvalidArgumentError(
        "exploration step, scan_distance, scan_rotation and replan_distance must be > 0");
  }
  if (options.max_scans < 1 || !(options.max_distance > 0.0)) {
    return InvalidArgumentError("exploration max_scans must be >= 1 and max_distance > 0");
  }
  return ExplorationSimulator(options, std::move(laser));
}

StatusOr<ExplorationResult> ExplorationSimulator::Run(
    const grid::OccupancyGrid& truth, const Pose2& start,
    const std::function<void(const ExplorationProgress&)>& on_progress,
    const ScanObserver& on_scan) const {
  if (truth.origin().yaw != 0.0 || truth.empty()) {
    return InvalidArgumentError("exploration truth grid must be non-empty with origin yaw 0");
  }
  const std::optional<grid::CellIndex> cell = truth.CellAt(start.translation());
  if (!cell || truth.at(cell->x, cell->y) != grid::kFreeValue) {
    return InvalidArgumentError("exploration start pose is outside the terrain or not free");
  }
  MapperOptions mapper_options = options_.mapper;
  mapper_options.block_size =
      std::max(1, static_cast<int>(std::lround(options_.planner_block / truth.resolution())));
  FLEETMAP_ASSIGN_OR_RETURN(
      OccupancyMapper mapper,
      OccupancyMapper::Create(truth.width(), truth.height(), truth.resolution(), truth.origin(),
                              mapper_options));
  FLEETMAP_ASSIGN_OR_RETURN(
      SlamErrorModel error,
      SlamErrorModel::Create(options_.error, options_.seed * 3266489917u + 7u));
  FLEETMAP_ASSIGN_OR_RETURN(FrontierPlanner planner, FrontierPlanner::Create(options_.frontier));
  RobotRun run(options_, laser_, truth, std::move(mapper), std::move(error), std::move(planner),
               start, on_progress, on_scan);
  return run.Explore();
}

}  // namespace fleetmap::sim
