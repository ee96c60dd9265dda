#pragma once

#include <chrono>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/notice.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/robot_frame.hpp"
#include "common/core/status.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/registration/placement_evidence.hpp"
#include "common/registration/placement_groups.hpp"
#include "common/registration/registration.hpp"
#include "common/vector_map/vector_map.hpp"

namespace fleetmap::registration {

struct PlacementOptions {
  // A robot is placed (or its placement revised) exactly when Register finds the match:
  // registration.min_confidence is the placement bar (registration::kPlacementConfidence by
  // default, the same bar `fleetmap register` and the pair benchmark use).
  RegistrationOptions registration;
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
  // Or when this many registrations in a row of its grown map found the same placement verified
  // (no contradiction, no ambiguity) at sequential_confidence or more. Off (0) by default: it
  // places a simulated fleet several times sooner (robot maps carry independent SLAM noise, so a
  // right placement can verify a long while just under the bar), but on growing pairs of
  // repeated terrains most placements it adds are wrong (docs/registration.md).
  int sequential_wins = 0;
  double sequential_confidence = 0.8;
  // The placed frames go out on rt/tf this often (tf2 listeners forget a transform after about
  // 10 s); the server sends them.
  std::chrono::milliseconds tf_period{500};

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// What one registration was asked: where `robot`'s map sits in `target`'s frame.
struct PlacementJob {
  RobotId robot;
  vector_map::VectorMap map;  // the robot's tiles, its map frame
  // The fleet map without the robot, or (when empty) another robot's map, rasterized at
  // `resolution` by RunPlacementJob.
  grid::OccupancyGrid target;
  vector_map::VectorMap target_map;
  double resolution = 0.05;
  RobotId target_robot;  // empty: the fleet map
  // When `robot` registers for its group (PlacementGroup, the root): the other members, whose
  // maps `map` holds too, in the robot's frame.
  std::vector<RobotId> group;
  std::optional<Pose2> current;  // the robot's placement when checking it
  uint64_t map_changes = 0;      // how often the robot's map changed when the job was made
  uint64_t target_changes = 0;   // the target's, likewise (fused tile revisions for the fleet)

  RegistrationKey key() const { return {robot, target_robot, !group.empty()}; }
};

struct PlacementResult {
  PlacementJob job;                    // `map` and `target` are released
  Point2 map_centre = Point2::Zero();  // of the robot's map, its frame: where placements compare
  StatusOr<Registration> registration = Registration{};
  std::chrono::milliseconds took{0};
};

// Runs one registration: rasterizes the maps at the job's resolution and registers the robot's on
// the target. Takes up to seconds: run it beside fusion, never in its way.
PlacementResult RunPlacementJob(PlacementJob job, const RegistrationOptions& options);

// The fleet's frames table and the policy that fills it: which robots' map frames are given,
// anchored, placed or unplaced, when a registration is due, and what its result decides (the
// sequential test, checks that revise a placement, robots registered to each other that are
// placed together). DDS-free and without threads: FleetMap drives it, a runner runs its jobs.
// Every frame that changed is kept for TakeChangedFrames(), and what people should know for
// TakeNotices(). Not thread-safe.
class Placer {
 public:
  explicit Placer(const PlacementOptions& options)
      : options_(options),
        evidence_({options.confirmations, options.sequential_wins, options.sequential_confidence,
                   options.revise_distance, options.revise_yaw_deg}) {}

  // A robot's map frame to place (or move) at fleet_from_map.
  struct Decision {
    RobotId robot;
    Pose2 fleet_from_map;
  };

  // A robot with tiles in its map frame appeared (state unplaced) or one with a given frame.
  void Unplaced(const RobotId& robot);
  void Given(const RobotId& robot, const Pose2& fleet_from_map);
  // The first robot: its map frame is the fleet frame.
  Decision Anchor(const RobotId& robot);
  // A robot whose frame another server decides (a shard's robot homed on another shard,
  // docs/shards.md): its row as that server wrote it. Never registered here.
  void Follow(const RobotFrame& frame);
  bool IsFollowed(const RobotId& robot) const { return followed_.count(robot) > 0; }

  // Whether this registration (RegistrationKey: whose map, on what) is due. A placed robot is
  // checked when its map changed since the last check and the check period passed; an unplaced
  // one is tried again when its map or the target changed, or a placement found waits for its
  // confirmation, and the retry period passed.
  bool Due(const RegistrationKey& key, uint64_t map_changes, uint64_t target_changes,
           std::chrono::steady_clock::time_point now) const;
  // A job is out (Submitted, its result not Decided yet): no other is due meanwhile.
  bool Busy() const { return busy_; }
  void Submitted(const PlacementJob& job, std::chrono::steady_clock::time_point now);

  // What a finished registration decides: none, or the robots to place (itself, and those
  // registered to it while unplaced).
  std::vector<Decision> Decide(const PlacementResult& result,
                               std::chrono::steady_clock::time_point now);

  // Whether the robot's tiles are fused (quarantine): carried by every frame of the robot.
  struct Standing {
    RobotFrame::Standing standing = RobotFrame::Standing::kTrusted;
    std::string reason;
    double contradicted_share = 0.0;
    double contradicted_m = 0.0;
    Point2 area_min = Point2::Zero();
    Point2 area_max = Point2(-1.0, -1.0);
  };
  void SetStanding(const RobotId& robot, const Standing& standing);

  // The frames table: one row per robot the fleet knows, and one holder of it.
  const std::map<RobotId, RobotFrame>& frames() const { return frames_; }
  std::optional<RobotFrame> FrameOf(const RobotId& robot) const;
  // Where the robot's map frame sits in the fleet frame; nullopt while unplaced or unknown.
  std::optional<Pose2> PlacementOf(const RobotId& robot) const;
  // The frames that changed since the last call, as they are now.
  std::vector<RobotFrame> TakeChangedFrames();
  std::vector<Notice> TakeNotices();

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
  const PlacementOptions& options() const { return options_; }

 private:
  // An unplaced robot registered to another unplaced one (the leader): where its map sits in the
  // leader's. Whichever of the two is placed first places the other.
  struct Follower {
    RobotId leader;
    Pose2 leader_from_map;
    double confidence = 0.0;
    double overlap = 0.0;
  };
  struct Attempt {
    uint64_t map_changes = 0;
    uint64_t target_changes = 0;
    std::chrono::steady_clock::time_point at{};
  };

  // The robot's row becomes `frame` (with its standing): one changed frame.
  void Set(RobotFrame frame);
  std::optional<Decision> DecideOne(const PlacementResult& result,
                                    std::chrono::steady_clock::time_point now);
  // Says on the robot's frame why an unplaced robot waits (when that changed).
  void Waiting(const RobotId& robot, const std::string& why);
  // Robots registered to `placed_robot` (or it to them) while unplaced are placed with it.
  void PlaceFollowers(const RobotId& placed_robot, const Pose2& placement,
                      std::vector<Decision>* decisions);
  void Say(Notice::Level level, std::string text);

  PlacementOptions options_;
  std::map<RobotId, RobotFrame> frames_;
  std::set<RobotId> followed_;             // rows another server decides
  std::map<RobotId, Standing> standings_;  // robots not trusted, or no longer
  std::map<RegistrationKey, Attempt> attempts_;
  std::map<RobotId, Follower> followers_;
  PlacementEvidence evidence_;
  static constexpr std::chrono::seconds kRefusalNoticePeriod{10};
  std::map<RobotId, std::chrono::steady_clock::time_point> last_refusal_notice_;
  bool busy_ = false;
  std::set<RobotId> changed_;
  std::vector<Notice> notices_;
};

}  // namespace fleetmap::registration
