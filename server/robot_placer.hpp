#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/sample_queue.hpp"
#include "common/core/status.hpp"
#include "common/core/worker_thread.hpp"
#include "common/fusion/robot_trust.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/registration/registration.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/tf_topic.hpp"
#include "common/vector_map/vector_map.hpp"
#include "server/placement_evidence.hpp"
#include "server/placement_groups.hpp"

namespace fleetmap::server {

struct PlacementOptions {
  // A robot is placed (or its placement revised) exactly when Register finds the match:
  // registration.min_confidence is the placement bar (registration::kPlacementConfidence by
  // default, the same bar `fleetmap register` and the pair benchmark use).
  registration::RegistrationOptions registration;
  // An unplaced robot's map is registered again at most this often, and only once it changed.
  std::chrono::milliseconds retry_period{1000};
  // A placed robot's placement is checked against the rest of the fleet at most this often, once
  // its map changed. A check that confidently finds the map elsewhere revises the placement.
  std::chrono::milliseconds check_period{5000};
  // How far a check's placement may lie from the current one and still confirm it: metres at
  // the robot map's centre and degrees.
  double revise_distance = 0.15;
  double revise_yaw_deg = 1.5;
  // An unplaced robot is placed when this many registrations in a row (of its growing map, on the
  // same target) found the same placement at the bar: the sequential test of PlacementEvidence.
  // A robot whose map stopped growing is registered again after retry_period to confirm.
  int confirmations = 2;
  // rt/tf is published this often (tf2 listeners forget a transform after about 10 s).
  std::chrono::milliseconds tf_period{500};

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// What one registration was asked: where `robot`'s map sits in `target`'s frame.
struct PlacementJob {
  RobotId robot;
  vector_map::VectorMap map;  // the robot's tiles, its map frame
  // The fleet map without the robot, or (when empty) another robot's map, rasterized at
  // `resolution` on the registration thread.
  grid::OccupancyGrid target;
  vector_map::VectorMap target_map;
  double resolution = 0.05;
  RobotId target_robot;  // empty: the fleet map
  // When `robot` registers for its group (PlacementGroup, the root): the other members, whose
  // maps `map` holds too, in the robot's frame.
  std::vector<RobotId> group;
  std::optional<Pose2> current;  // the robot's placement when checking it
  uint64_t map_changes = 0;      // MapFrameRobots::changes() when the job was made
  uint64_t target_changes = 0;   // the target's, likewise (fused tile revisions for the fleet)

  RegistrationKey key() const { return {robot, target_robot, !group.empty()}; }
};

struct PlacementResult {
  PlacementJob job;                    // `map` and `target` are released
  Point2 map_centre = Point2::Zero();  // of the robot's map, its frame: where placements compare
  StatusOr<registration::Registration> registration = registration::Registration{};
  std::chrono::milliseconds took{0};
};

// Places the robots whose tiles come in their own map frame: runs registrations on its own thread
// (one at a time: a registration takes up to seconds and must not hold back fusion), decides from
// their results, and publishes every robot's frame on rt/fleetmap/robot_frames and rt/tf
// (fleet -> <robot>/map). The fusion worker drives it: it hands over jobs (Submit), takes results
// (Decide), and moves the robots' contributions. Call from the fusion worker's thread only.
class RobotPlacer {
 public:
  static StatusOr<std::unique_ptr<RobotPlacer>> Create(transport::Participant& participant,
                                                       const PlacementOptions& options);
  ~RobotPlacer();

  // A robot to place (or move) at fleet_from_map.
  struct Decision {
    RobotId robot;
    Pose2 fleet_from_map;
  };

  // A robot with tiles in its map frame appeared (state unplaced) or one with a given frame.
  void Unplaced(const RobotId& robot);
  void Given(const RobotId& robot, const Pose2& fleet_from_map);
  // The first robot: its map frame is the fleet frame.
  Decision Anchor(const RobotId& robot);
  // The robot left the fleet's map for good (its frame is withdrawn).
  void Forget(const RobotId& robot);

  // Whether this registration (RegistrationKey: whose map, on what) is due. A placed robot is
  // checked when its map changed since the last check and the check period passed; an unplaced
  // one is tried again when its map or the target changed, or a placement found waits for its
  // confirmation, and the retry period passed.
  bool Due(const RegistrationKey& key, uint64_t map_changes, uint64_t target_changes,
           std::chrono::steady_clock::time_point now) const;
  bool Busy() const { return busy_; }
  void Submit(PlacementJob job, std::chrono::steady_clock::time_point now);

  // The finished registrations' decisions; `placement_of` tells where each robot is placed now.
  using PlacementOf = std::function<std::optional<Pose2>(const RobotId&)>;
  std::vector<Decision> Decide(const PlacementOf& placement_of);

  // Whether the robot's tiles are fused (quarantine): carried by every frame published for it,
  // and its current frame is published again with it.
  void SetStanding(const fusion::TrustReport& report);

  // Publishes rt/tf when due.
  void PublishTf(std::chrono::steady_clock::time_point now);

  // Every robot's frame as last published.
  const std::map<RobotId, transport::RobotFrameMessage>& frames() const { return frames_; }
  // Robots other than `robot` whose maps are not placed (candidates to register against), and
  // not in its group.
  std::vector<RobotId> UnplacedOthers(const RobotId& robot) const;
  // The unplaced robots registered to `robot` and to each other, as one group (itself alone
  // when it has no links, or is placed).
  PlacementGroup GroupOf(const RobotId& robot) const;
  // The robot's frame was given (--fleet-from-map, a transforms file): never registered, moved
  // or revised.
  bool IsGiven(const RobotId& robot) const;
  // Some robot's frame is known (given, anchored or placed): the fleet frame exists.
  bool AnyPlaced() const;

 private:
  explicit RobotPlacer(const PlacementOptions& options)
      : options_(options),
        evidence_({options.confirmations, options.revise_distance, options.revise_yaw_deg}) {}

  // Runs on the registration thread.
  void Work();
  void Publish(transport::RobotFrameMessage frame);
  std::optional<Decision> DecideOne(const PlacementResult& result, const PlacementOf& placement_of);
  // Says on robot_frames why an unplaced robot waits (published when it changed).
  void Waiting(const RobotId& robot, const std::string& why);
  // Robots registered to `placed_robot` (or it to them) while unplaced are placed with it.
  void PlaceFollowers(const RobotId& placed_robot, const Pose2& placement,
                      std::vector<Decision>* decisions);

  struct Attempt {
    uint64_t map_changes = 0;
    uint64_t target_changes = 0;
    std::chrono::steady_clock::time_point at{};
  };
  // An unplaced robot registered to another unplaced one (the leader): where its map sits in the
  // leader's. Whichever of the two is placed first places the other.
  struct Follower {
    RobotId leader;
    Pose2 leader_from_map;
    double confidence = 0.0;
    double overlap = 0.0;
  };

  PlacementOptions options_;
  std::unique_ptr<transport::RobotFrameWriter> frame_writer_;
  std::unique_ptr<transport::TfWriter> tf_writer_;
  std::map<RobotId, transport::RobotFrameMessage> frames_;
  std::map<RobotId, fusion::TrustReport> standings_;  // robots not trusted, or no longer
  std::map<RegistrationKey, Attempt> attempts_;
  std::map<RobotId, Follower> followers_;
  PlacementEvidence evidence_;
  std::chrono::steady_clock::time_point last_tf_{};
  static constexpr std::chrono::seconds kRefusalLogPeriod{10};
  std::map<RobotId, std::chrono::steady_clock::time_point> last_refusal_log_;
  bool busy_ = false;

  std::mutex mutex_;
  std::optional<PlacementJob> pending_;  // guarded by mutex_
  SampleQueue<PlacementResult> results_{64};
  WorkerThread thread_{std::nullopt};  // last: stops before the rest goes
};

}  // namespace fleetmap::server
