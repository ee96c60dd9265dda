#include "common/registration/placer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/vector_map/rasterizer.hpp"

namespace fleetmap::registration {
namespace {

// The largest robot map registered (cells per side): beyond, the registration is refused.
constexpr int kMaxRegisteredCells = 8000;

double Degrees(double radians) { return radians * 180.0 / M_PI; }

// The robot's map as a grid at `resolution` (vector maps rasterize at any resolution, so the two
// maps of a registration always agree on theirs).
StatusOr<grid::OccupancyGrid> RasterizeForRegistration(const vector_map::VectorMap& map,
                                                       double resolution) {
  const auto bounds = vector_map::Bounds(map);
  if (!bounds) return InvalidArgumentError("the robot's map has no geometry yet");
  const double x0 = (std::floor(bounds->first.x() / resolution) - 1) * resolution;
  const double y0 = (std::floor(bounds->first.y() / resolution) - 1) * resolution;
  const double width = std::ceil((bounds->second.x() - x0) / resolution) + 1;
  const double height = std::ceil((bounds->second.y() - y0) / resolution) + 1;
  if (width > kMaxRegisteredCells || height > kMaxRegisteredCells) {
    return InvalidArgumentError(fmt::format(
        "the robot's map spans {:.0f} x {:.0f} cells; registration takes at most {} per side",
        width, height, kMaxRegisteredCells));
  }
  return vector_map::Rasterizer().Rasterize(map, static_cast<int>(width), static_cast<int>(height),
                                            resolution, Pose2{x0, y0, 0.0});
}

}  // namespace

PlacementResult RunPlacementJob(PlacementJob job, const RegistrationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  PlacementResult result;
  if (const auto bounds = vector_map::Bounds(job.map)) {
    result.map_centre = (bounds->first + bounds->second) / 2.0;
  }
  StatusOr<grid::OccupancyGrid> map = RasterizeForRegistration(job.map, job.resolution);
  if (job.target.empty()) {
    StatusOr<grid::OccupancyGrid> target = RasterizeForRegistration(job.target_map, job.resolution);
    if (target.ok()) {
      job.target = *std::move(target);
    } else {
      result.registration = target.status();
    }
  }
  if (!map.ok()) {
    result.registration = map.status();
  } else if (!job.target.empty()) {
    result.registration = Register(job.target, *map, options);
  }
  result.took = std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::steady_clock::now() - start);
  job.map = vector_map::VectorMap();
  job.target = grid::OccupancyGrid();
  job.target_map = vector_map::VectorMap();
  result.job = std::move(job);
  return result;
}

void Placer::Say(Notice::Level level, std::string text) {
  notices_.push_back(Notice{level, std::move(text)});
}

void Placer::Set(RobotFrame frame) {
  if (const auto standing = standings_.find(frame.robot); standing != standings_.end()) {
    const Standing& known = standing->second;
    frame.standing = known.standing;
    frame.standing_reason = known.reason;
    frame.contradicted_share = std::clamp(known.contradicted_share, 0.0, 1.0);
    frame.contradicted_m = known.contradicted_m;
    frame.area_min = known.area_min;
    frame.area_max = known.area_max;
  }
  changed_.insert(frame.robot);
  frames_[frame.robot] = std::move(frame);
}

void Placer::SetStanding(const RobotId& robot, const Standing& standing) {
  standings_[robot] = standing;
  const auto frame = frames_.find(robot);
  if (frame != frames_.end()) Set(frame->second);
}

void Placer::Unplaced(const RobotId& robot) {
  if (frames_.count(robot) > 0) return;
  RobotFrame frame;
  frame.robot = robot;
  frame.state = RobotFrame::State::kUnplaced;
  Set(std::move(frame));
}

void Placer::Follow(const RobotFrame& frame) {
  followed_.insert(frame.robot);
  const auto it = frames_.find(frame.robot);
  if (it != frames_.end() && it->second.state == frame.state &&
      it->second.fleet_from_map == frame.fleet_from_map) {
    return;
  }
  Set(frame);
}

void Placer::Given(const RobotId& robot, const Pose2& fleet_from_map) {
  const auto it = frames_.find(robot);
  if (it != frames_.end() && it->second.state == RobotFrame::State::kGiven &&
      it->second.fleet_from_map == fleet_from_map) {
    return;
  }
  RobotFrame frame;
  frame.robot = robot;
  frame.state = RobotFrame::State::kGiven;
  frame.fleet_from_map = fleet_from_map;
  frame.confidence = 1.0;
  frame.overlap = 0.0;
  frame.placements = 1;
  Set(std::move(frame));
}

Placer::Decision Placer::Anchor(const RobotId& robot) {
  RobotFrame frame;
  frame.robot = robot;
  frame.state = RobotFrame::State::kAnchor;
  frame.confidence = 1.0;
  frame.placements = 1;
  frame.placed_against = "fleet";
  Set(std::move(frame));
  Say(Notice::Level::kInfo,
      fmt::format("robot {} anchors the fleet frame (no robot was placed)", robot.value));
  return Decision{robot, Pose2{}};
}

bool Placer::Due(const RegistrationKey& key, uint64_t map_changes, uint64_t target_changes,
                 std::chrono::steady_clock::time_point now) const {
  if (busy_ || IsGiven(key.robot) || IsFollowed(key.robot)) return false;
  const auto frame = frames_.find(key.robot);
  const bool placed = frame != frames_.end() && frame->second.placed();
  const auto attempt = attempts_.find(key);
  if (attempt == attempts_.end()) return true;
  const bool map_changed = attempt->second.map_changes != map_changes;
  if (placed) return map_changed && now - attempt->second.at >= options_.check_period;
  const bool target_changed = attempt->second.target_changes != target_changes;
  // A placement found once is registered again to confirm it, grown map or not.
  const bool confirming = evidence_.Pending(key);
  return (map_changed || target_changed || confirming) &&
         now - attempt->second.at >= options_.retry_period;
}

void Placer::Submitted(const PlacementJob& job, std::chrono::steady_clock::time_point now) {
  attempts_[job.key()] = Attempt{job.map_changes, job.target_changes, now};
  busy_ = true;
}

std::vector<Placer::Decision> Placer::Decide(const PlacementResult& result,
                                             std::chrono::steady_clock::time_point now) {
  busy_ = false;
  std::vector<Decision> decisions;
  if (std::optional<Decision> decision = DecideOne(result, now)) {
    decisions.push_back(*decision);
    PlaceFollowers(decision->robot, decision->fleet_from_map, &decisions);
  }
  return decisions;
}

std::optional<Placer::Decision> Placer::DecideOne(const PlacementResult& result,
                                                  std::chrono::steady_clock::time_point now) {
  const PlacementJob& job = result.job;
  if (IsGiven(job.robot)) return std::nullopt;  // given meanwhile: a given frame is never moved
  const std::string against =
      job.target_robot.value.empty() ? "the fleet map" : "robot " + job.target_robot.value;
  if (!result.registration.ok()) {
    Say(Notice::Level::kInfo, fmt::format("cannot register robot {} on {} yet: {}", job.robot.value,
                                          against, result.registration.status().message()));
    return std::nullopt;
  }
  const Registration& found = *result.registration;
  const auto frame = frames_.find(job.robot);
  if (frame == frames_.end()) return std::nullopt;  // not a robot of the table
  // found: verified and at the placement bar (RegistrationOptions::min_confidence).
  const bool at_bar = found.found;
  std::string why_not = found.why_not;
  bool place = at_bar;
  std::string sequence;  // how the sequential test placed it, for the notice
  if (!frame->second.placed()) {
    // The sequential test: placed only when the same placement keeps winning.
    const PlacementEvidence::Verdict verdict =
        evidence_.Observe(job.key(), {found.a_from_b, result.map_centre, at_bar, found.verified,
                                      found.confidence, why_not, job.map_changes});
    place = verdict.place;
    if (place && !at_bar) {
      sequence = fmt::format(", found {} times in a row at {:.2f} or more", verdict.wins,
                             options_.sequential_confidence);
    }
    if (!place) {
      Waiting(job.robot,
              (job.target_robot.value.empty() ? "on the fleet map: "
                                              : "on robot " + job.target_robot.value + ": ") +
                  verdict.why);
      if (at_bar) {
        Say(Notice::Level::kDebug,
            fmt::format("robot {} on {}: {}", job.robot.value, against, verdict.why));
        return std::nullopt;
      }
      why_not = verdict.why;
    }
  }
  if (!place) {
    // Every try at debug level; at info, what keeps a robot unplaced, every 10 s at most.
    auto& last = last_refusal_notice_[job.robot];
    const bool tell = !frame->second.placed() && now - last >= kRefusalNoticePeriod;
    if (tell) last = now;
    Say(tell ? Notice::Level::kInfo : Notice::Level::kDebug,
        fmt::format("robot {} not placed on {}{} ({} ms): {}", job.robot.value, against,
                    tell ? " yet" : "", result.took.count(), why_not));
    return std::nullopt;
  }
  const std::optional<Pose2> now_placed = PlacementOf(job.robot);

  Pose2 fleet_from_map = found.a_from_b;
  if (!job.target_robot.value.empty()) {
    // Registered to another robot's map: follow it once (or as soon as) it is placed.
    const auto known = followers_.find(job.robot);
    const bool new_link = known == followers_.end() || known->second.leader != job.target_robot;
    followers_[job.robot] =
        Follower{job.target_robot, found.a_from_b, found.confidence, found.overlap};
    const std::optional<Pose2> leader = PlacementOf(job.target_robot);
    if (!leader || now_placed) {
      if (new_link) {
        Say(Notice::Level::kInfo,
            fmt::format("robot {} registered to robot {} (confidence {:.2f}): whichever of the "
                        "two is placed first places the other",
                        job.robot.value, job.target_robot.value, found.confidence));
      }
      return std::nullopt;
    }
    fleet_from_map = Pose2::FromTransform(leader->ToTransform() * found.a_from_b.ToTransform());
  }

  RobotFrame placed = frame->second;
  placed.waiting_reason.clear();
  placed.fleet_from_map = fleet_from_map;
  placed.confidence = found.confidence;
  placed.overlap = found.overlap;
  placed.placed_against = job.target_robot.value.empty() ? "fleet" : job.target_robot.value;
  if (now_placed) {
    // A check: the same placement confirms it; a confident different one revises it.
    const Point2 was = now_placed->ToTransform() * result.map_centre;
    const Point2 is = fleet_from_map.ToTransform() * result.map_centre;
    const double yaw = std::abs(NormalizeAngle(fleet_from_map.yaw - now_placed->yaw));
    if ((was - is).norm() <= options_.revise_distance && Degrees(yaw) <= options_.revise_yaw_deg) {
      return std::nullopt;
    }
    placed.state = RobotFrame::State::kRevised;
    Say(Notice::Level::kWarning,
        fmt::format("robot {}'s placement contradicts the fleet map: moved by {:.2f} m and {:.1f} "
                    "degrees (confidence {:.2f}); its contribution is fused again",
                    job.robot.value, (was - is).norm(), Degrees(yaw), found.confidence));
  } else {
    placed.state = RobotFrame::State::kPlaced;
    std::string with_group;
    for (const RobotId& member : job.group) {
      with_group += with_group.empty() ? " with the map of its group (" : ", ";
      with_group += member.value;
    }
    if (!with_group.empty()) with_group += ")";
    Say(Notice::Level::kInfo,
        fmt::format("robot {} placed on {}{} at ({:.2f}, {:.2f}, {:.1f} deg), confidence {:.2f}{}, "
                    "overlap {:.2f} ({} ms)",
                    job.robot.value, against, with_group, fleet_from_map.x, fleet_from_map.y,
                    Degrees(fleet_from_map.yaw), found.confidence, sequence, found.overlap,
                    result.took.count()));
  }
  ++placed.placements;
  Set(std::move(placed));
  return Decision{job.robot, fleet_from_map};
}

void Placer::Waiting(const RobotId& robot, const std::string& why) {
  const auto frame = frames_.find(robot);
  if (frame == frames_.end() || frame->second.placed() || frame->second.waiting_reason == why) {
    return;
  }
  RobotFrame waiting = frame->second;
  waiting.waiting_reason = why;
  Set(std::move(waiting));
}

void Placer::PlaceFollowers(const RobotId& placed_robot, const Pose2& placement,
                            std::vector<Decision>* decisions) {
  // Each link says where one robot's map sits in another's; it works both ways.
  for (const auto& [robot, link] : followers_) {
    RobotId other;
    Transform2 placed_from_other;
    if (link.leader == placed_robot) {
      other = robot;
      placed_from_other = link.leader_from_map.ToTransform();
    } else if (robot == placed_robot) {
      other = link.leader;
      placed_from_other = link.leader_from_map.ToTransform().inverse();
    } else {
      continue;
    }
    const auto frame = frames_.find(other);
    if (frame == frames_.end() || frame->second.placed()) continue;
    const Pose2 fleet_from_map = Pose2::FromTransform(placement.ToTransform() * placed_from_other);
    RobotFrame placed = frame->second;
    placed.state = RobotFrame::State::kPlaced;
    placed.waiting_reason.clear();
    placed.fleet_from_map = fleet_from_map;
    placed.confidence = link.confidence;
    placed.overlap = link.overlap;
    placed.placed_against = placed_robot.value;
    ++placed.placements;
    Set(std::move(placed));
    Say(Notice::Level::kInfo,
        fmt::format("robot {} placed with robot {} at ({:.2f}, {:.2f}, {:.1f} deg)", other.value,
                    placed_robot.value, fleet_from_map.x, fleet_from_map.y,
                    Degrees(fleet_from_map.yaw)));
    decisions->push_back(Decision{other, fleet_from_map});
    PlaceFollowers(other, fleet_from_map, decisions);
  }
}

std::optional<RobotFrame> Placer::FrameOf(const RobotId& robot) const {
  const auto frame = frames_.find(robot);
  if (frame == frames_.end()) return std::nullopt;
  return frame->second;
}

std::optional<Pose2> Placer::PlacementOf(const RobotId& robot) const {
  const auto frame = frames_.find(robot);
  if (frame == frames_.end() || !frame->second.placed()) return std::nullopt;
  return frame->second.fleet_from_map;
}

std::vector<RobotFrame> Placer::TakeChangedFrames() {
  std::vector<RobotFrame> changed;
  for (const RobotId& robot : changed_) changed.push_back(frames_.at(robot));
  changed_.clear();
  return changed;
}

std::vector<Notice> Placer::TakeNotices() { return std::exchange(notices_, {}); }

std::vector<RobotId> Placer::UnplacedOthers(const RobotId& robot) const {
  const PlacementGroup group = GroupOf(robot);
  std::vector<RobotId> out;
  for (const auto& [other, frame] : frames_) {
    if (!frame.placed() && group.root_from_member.count(other) == 0) out.push_back(other);
  }
  return out;
}

PlacementGroup Placer::GroupOf(const RobotId& robot) const {
  std::set<RobotId> placed;
  for (const auto& [other, frame] : frames_) {
    if (frame.placed()) placed.insert(other);
  }
  if (placed.count(robot) > 0) return PlacementGroup{robot, {{robot, Pose2{}}}};
  std::vector<RobotLink> links;
  for (const auto& [follower, link] : followers_) {
    links.push_back(RobotLink{follower, link.leader, link.leader_from_map});
  }
  return registration::GroupOf(robot, links, placed);
}

bool Placer::IsGiven(const RobotId& robot) const {
  const auto frame = frames_.find(robot);
  return frame != frames_.end() && frame->second.state == RobotFrame::State::kGiven;
}

bool Placer::AnyPlaced() const {
  return std::any_of(frames_.begin(), frames_.end(),
                     [](const auto& entry) { return entry.second.placed(); });
}

Status PlacementOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(registration.Validate());
  if (retry_period.count() < 0 || check_period.count() < 0 || tf_period.count() <= 0) {
    return InvalidArgumentError("placement periods must not be negative (tf_period > 0)");
  }
  if (confirmations < 1) return InvalidArgumentError("placement confirmations must be >= 1");
  if (sequential_wins < 0 || !(sequential_confidence >= 0.0 && sequential_confidence <= 1.0)) {
    return InvalidArgumentError(
        "placement sequential_wins must be >= 0 and sequential_confidence in [0, 1]");
  }
  if (!(revise_distance > 0.0) || !(revise_yaw_deg > 0.0)) {
    return InvalidArgumentError("placement revise_distance and revise_yaw_deg must be > 0");
  }
  return Status::Ok();
}

void PlacementOptions::Describe(OptionsPrinter& out) const {
  out.Nested("registration", registration);
  out.Add("retry_period", retry_period);
  out.Add("check_period", check_period);
  out.Add("revise_distance", revise_distance);
  out.Add("revise_yaw_deg", revise_yaw_deg);
  out.Add("confirmations", confirmations);
  out.Add("sequential_wins", sequential_wins);
  out.Add("sequential_confidence", sequential_confidence);
  out.Add("tf_period", tf_period);
}

}  // namespace fleetmap::registration
