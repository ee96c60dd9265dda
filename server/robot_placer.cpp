#include "server/robot_placer.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "common/vector_map/rasterizer.hpp"

namespace fleetmap::server {
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

StatusOr<std::unique_ptr<RobotPlacer>> RobotPlacer::Create(transport::Participant& participant,
                                                           const PlacementOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  std::unique_ptr<RobotPlacer> self(new RobotPlacer(options));
  FLEETMAP_ASSIGN_OR_RETURN(self->frame_writer_, transport::RobotFrameWriter::Create(participant));
  FLEETMAP_ASSIGN_OR_RETURN(self->tf_writer_, transport::TfWriter::Create(participant));
  self->thread_.Start([raw = self.get()] {
    raw->Work();
    return false;
  });
  return self;
}

RobotPlacer::~RobotPlacer() {
  thread_.Stop();
  frame_writer_.reset();
  tf_writer_.reset();
}

void RobotPlacer::Publish(transport::RobotFrameMessage frame) {
  frame.stamp = Clock::now();
  if (const auto standing = standings_.find(frame.robot); standing != standings_.end()) {
    const fusion::TrustReport& report = standing->second;
    using Standing = transport::RobotFrameMessage::Standing;
    switch (report.standing) {
      case fusion::Standing::kTrusted:
        frame.standing = Standing::kTrusted;
        break;
      case fusion::Standing::kQuarantined:
        frame.standing = Standing::kQuarantined;
        break;
      case fusion::Standing::kAdmitted:
        frame.standing = Standing::kAdmitted;
        break;
    }
    frame.standing_reason = report.reason;
    frame.contradicted_share = std::clamp(report.share, 0.0, 1.0);
    frame.contradicted_m = report.contradicted_m;
    frame.area_min = report.area_min;
    frame.area_max = report.area_max;
  }
  if (StatusOr<size_t> written = frame_writer_->Write(frame); !written.ok()) {
    spdlog::warn("server: {}", written.status().message());
  }
  frames_[frame.robot] = std::move(frame);
}

void RobotPlacer::SetStanding(const fusion::TrustReport& report) {
  standings_[report.robot] = report;
  const auto frame = frames_.find(report.robot);
  if (frame != frames_.end()) Publish(frame->second);
}

void RobotPlacer::Unplaced(const RobotId& robot) {
  if (frames_.count(robot) > 0) return;
  transport::RobotFrameMessage frame;
  frame.robot = robot;
  frame.state = transport::RobotFrameMessage::State::kUnplaced;
  Publish(std::move(frame));
}

void RobotPlacer::Given(const RobotId& robot, const Pose2& fleet_from_map) {
  const auto it = frames_.find(robot);
  if (it != frames_.end() && it->second.state == transport::RobotFrameMessage::State::kGiven &&
      it->second.fleet_from_map == fleet_from_map) {
    return;
  }
  transport::RobotFrameMessage frame;
  frame.robot = robot;
  frame.state = transport::RobotFrameMessage::State::kGiven;
  frame.fleet_from_map = fleet_from_map;
  frame.confidence = 1.0;
  frame.overlap = 0.0;
  frame.placements = 1;
  Publish(std::move(frame));
}

RobotPlacer::Decision RobotPlacer::Anchor(const RobotId& robot) {
  transport::RobotFrameMessage frame;
  frame.robot = robot;
  frame.state = transport::RobotFrameMessage::State::kAnchor;
  frame.confidence = 1.0;
  frame.placements = 1;
  frame.placed_against = "fleet";
  Publish(std::move(frame));
  spdlog::info("server: robot {} anchors the fleet frame (no robot was placed)", robot.value);
  return Decision{robot, Pose2{}};
}

void RobotPlacer::Forget(const RobotId& robot) {
  const auto it = frames_.find(robot);
  if (it == frames_.end()) return;
  if (const Status disposed = frame_writer_->Dispose(it->second); !disposed.ok()) {
    spdlog::warn("server: {}", disposed.message());
  }
  frames_.erase(it);
  followers_.erase(robot);
  evidence_.Forget(robot);
  last_refusal_log_.erase(robot);
  std::erase_if(attempts_, [&](const auto& entry) { return entry.first.robot == robot; });
}

bool RobotPlacer::Due(const RegistrationKey& key, uint64_t map_changes, uint64_t target_changes,
                      std::chrono::steady_clock::time_point now) const {
  if (busy_ || IsGiven(key.robot)) return false;
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

void RobotPlacer::Submit(PlacementJob job, std::chrono::steady_clock::time_point now) {
  attempts_[job.key()] = Attempt{job.map_changes, job.target_changes, now};
  busy_ = true;
  {
    std::lock_guard lock(mutex_);
    pending_ = std::move(job);
  }
  thread_.Wake();
}

void RobotPlacer::Work() {
  std::optional<PlacementJob> job;
  {
    std::lock_guard lock(mutex_);
    job.swap(pending_);
  }
  if (!job) return;
  const auto start = std::chrono::steady_clock::now();
  PlacementResult result;
  if (const auto bounds = vector_map::Bounds(job->map)) {
    result.map_centre = (bounds->first + bounds->second) / 2.0;
  }
  StatusOr<grid::OccupancyGrid> map = RasterizeForRegistration(job->map, job->resolution);
  if (job->target.empty()) {
    StatusOr<grid::OccupancyGrid> target =
        RasterizeForRegistration(job->target_map, job->resolution);
    if (target.ok()) {
      job->target = *std::move(target);
    } else {
      result.registration = target.status();
    }
  }
  if (!map.ok()) {
    result.registration = map.status();
  } else if (!job->target.empty()) {
    result.registration = registration::Register(job->target, *map, options_.registration);
  }
  result.took = std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::steady_clock::now() - start);
  job->map = vector_map::VectorMap();
  job->target = grid::OccupancyGrid();
  job->target_map = vector_map::VectorMap();
  result.job = *std::move(job);
  results_.Push(std::move(result));
}

std::vector<RobotPlacer::Decision> RobotPlacer::Decide(const PlacementOf& placement_of) {
  std::vector<Decision> decisions;
  for (const PlacementResult& result : results_.Drain()) {
    busy_ = false;
    if (std::optional<Decision> decision = DecideOne(result, placement_of)) {
      decisions.push_back(*decision);
      PlaceFollowers(decision->robot, decision->fleet_from_map, &decisions);
    }
  }
  return decisions;
}

std::optional<RobotPlacer::Decision> RobotPlacer::DecideOne(const PlacementResult& result,
                                                            const PlacementOf& placement_of) {
  const PlacementJob& job = result.job;
  if (IsGiven(job.robot)) return std::nullopt;  // given meanwhile: a given frame is never moved
  const std::string against =
      job.target_robot.value.empty() ? "the fleet map" : "robot " + job.target_robot.value;
  if (!result.registration.ok()) {
    spdlog::info("server: cannot register robot {} on {} yet: {}", job.robot.value, against,
                 result.registration.status().message());
    return std::nullopt;
  }
  const registration::Registration& found = *result.registration;
  const auto frame = frames_.find(job.robot);
  if (frame == frames_.end()) return std::nullopt;  // forgotten meanwhile
  // found: verified and at the placement bar (RegistrationOptions::min_confidence).
  const bool at_bar = found.found;
  const std::string& why_not = found.why_not;
  if (!frame->second.placed()) {
    // The sequential test: placed only when the same placement keeps winning.
    const PlacementEvidence::Verdict verdict = evidence_.Observe(
        job.key(), {found.a_from_b, result.map_centre, at_bar, found.confidence, why_not});
    if (!verdict.place) {
      Waiting(job.robot,
              (job.target_robot.value.empty() ? "on the fleet map: "
                                              : "on robot " + job.target_robot.value + ": ") +
                  verdict.why);
      if (at_bar) {
        spdlog::debug("server: robot {} on {}: {}", job.robot.value, against, verdict.why);
        return std::nullopt;
      }
    }
  }
  if (!at_bar) {
    // Every try at debug level; at info, what keeps a robot unplaced, every 10 s at most.
    const auto now = std::chrono::steady_clock::now();
    auto& last = last_refusal_log_[job.robot];
    if (!frame->second.placed() && now - last >= kRefusalLogPeriod) {
      last = now;
      spdlog::info("server: robot {} not placed on {} yet ({} ms): {}", job.robot.value, against,
                   result.took.count(), why_not);
    } else {
      spdlog::debug("server: robot {} not placed on {} ({} ms): {}", job.robot.value, against,
                    result.took.count(), why_not);
    }
    return std::nullopt;
  }
  const std::optional<Pose2> now_placed = placement_of(job.robot);

  Pose2 fleet_from_map = found.a_from_b;
  if (!job.target_robot.value.empty()) {
    // Registered to another robot's map: follow it once (or as soon as) it is placed.
    const auto known = followers_.find(job.robot);
    const bool new_link = known == followers_.end() || known->second.leader != job.target_robot;
    followers_[job.robot] =
        Follower{job.target_robot, found.a_from_b, found.confidence, found.overlap};
    const std::optional<Pose2> leader = placement_of(job.target_robot);
    if (!leader || now_placed) {
      if (new_link) {
        spdlog::info(
            "server: robot {} registered to robot {} (confidence {:.2f}): whichever of the two "
            "is placed first places the other",
            job.robot.value, job.target_robot.value, found.confidence);
      }
      return std::nullopt;
    }
    fleet_from_map = Pose2::FromTransform(leader->ToTransform() * found.a_from_b.ToTransform());
  }

  transport::RobotFrameMessage placed = frame->second;
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
    placed.state = transport::RobotFrameMessage::State::kRevised;
    spdlog::warn(
        "server: robot {}'s placement contradicts the fleet map: moved by {:.2f} m and {:.1f} "
        "degrees (confidence {:.2f}); its contribution is fused again",
        job.robot.value, (was - is).norm(), Degrees(yaw), found.confidence);
  } else {
    placed.state = transport::RobotFrameMessage::State::kPlaced;
    std::string with_group;
    for (const RobotId& member : job.group) {
      with_group += with_group.empty() ? " with the map of its group (" : ", ";
      with_group += member.value;
    }
    if (!with_group.empty()) with_group += ")";
    spdlog::info(
        "server: robot {} placed on {}{} at ({:.2f}, {:.2f}, {:.1f} deg), confidence {:.2f}, "
        "overlap {:.2f} ({} ms)",
        job.robot.value, against, with_group, fleet_from_map.x, fleet_from_map.y,
        Degrees(fleet_from_map.yaw), found.confidence, found.overlap, result.took.count());
  }
  ++placed.placements;
  Publish(std::move(placed));
  return Decision{job.robot, fleet_from_map};
}

void RobotPlacer::Waiting(const RobotId& robot, const std::string& why) {
  const auto frame = frames_.find(robot);
  if (frame == frames_.end() || frame->second.placed() || frame->second.waiting_reason == why) {
    return;
  }
  transport::RobotFrameMessage waiting = frame->second;
  waiting.waiting_reason = why;
  Publish(std::move(waiting));
}

void RobotPlacer::PlaceFollowers(const RobotId& placed_robot, const Pose2& placement,
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
    transport::RobotFrameMessage placed = frame->second;
    placed.state = transport::RobotFrameMessage::State::kPlaced;
    placed.waiting_reason.clear();
    placed.fleet_from_map = fleet_from_map;
    placed.confidence = link.confidence;
    placed.overlap = link.overlap;
    placed.placed_against = placed_robot.value;
    ++placed.placements;
    Publish(std::move(placed));
    spdlog::info("server: robot {} placed with robot {} at ({:.2f}, {:.2f}, {:.1f} deg)",
                 other.value, placed_robot.value, fleet_from_map.x, fleet_from_map.y,
                 Degrees(fleet_from_map.yaw));
    decisions->push_back(Decision{other, fleet_from_map});
    PlaceFollowers(other, fleet_from_map, decisions);
  }
}

std::vector<RobotId> RobotPlacer::UnplacedOthers(const RobotId& robot) const {
  const PlacementGroup group = GroupOf(robot);
  std::vector<RobotId> out;
  for (const auto& [other, frame] : frames_) {
    if (!frame.placed() && group.root_from_member.count(other) == 0) out.push_back(other);
  }
  return out;
}

PlacementGroup RobotPlacer::GroupOf(const RobotId& robot) const {
  std::set<RobotId> placed;
  for (const auto& [other, frame] : frames_) {
    if (frame.placed()) placed.insert(other);
  }
  if (placed.count(robot) > 0) return PlacementGroup{robot, {{robot, Pose2{}}}};
  std::vector<RobotLink> links;
  for (const auto& [follower, link] : followers_) {
    links.push_back(RobotLink{follower, link.leader, link.leader_from_map});
  }
  return server::GroupOf(robot, links, placed);
}

bool RobotPlacer::IsGiven(const RobotId& robot) const {
  const auto frame = frames_.find(robot);
  return frame != frames_.end() &&
         frame->second.state == transport::RobotFrameMessage::State::kGiven;
}

bool RobotPlacer::AnyPlaced() const {
  return std::any_of(frames_.begin(), frames_.end(),
                     [](const auto& entry) { return entry.second.placed(); });
}

void RobotPlacer::PublishTf(std::chrono::steady_clock::time_point now) {
  if (now - last_tf_ < options_.tf_period) return;
  last_tf_ = now;
  std::vector<transport::FrameTransform> transforms;
  const Timestamp stamp = Clock::now();
  for (const auto& [robot, frame] : frames_) {
    if (!frame.placed()) continue;
    transforms.push_back(transport::FrameTransform{
        stamp, "fleet", transport::RobotMapFrame(robot.value), frame.fleet_from_map});
  }
  if (transforms.empty()) return;
  if (StatusOr<size_t> written = tf_writer_->Write(transforms); !written.ok()) {
    spdlog::warn("server: {}", written.status().message());
  }
}

Status PlacementOptions::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(registration.Validate());
  if (retry_period.count() < 0 || check_period.count() < 0 || tf_period.count() <= 0) {
    return InvalidArgumentError("placement periods must not be negative (tf_period > 0)");
  }
  if (confirmations < 1) return InvalidArgumentError("placement confirmations must be >= 1");
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
  out.Add("tf_period", tf_period);
}

}  // namespace fleetmap::server
