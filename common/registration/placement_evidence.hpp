#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "common/core/ids.hpp"
#include "common/core/types.hpp"

namespace fleetmap::registration {

// One kind of registration the placer runs: `robot`'s map (or, for the root of a group, the
// merged map of its group: PlacementGroup) on `target` (empty: the fleet map). Each kind has its
// own retries and its own sequential test.
struct RegistrationKey {
  RobotId robot;
  RobotId target;
  bool as_group = false;

  friend auto operator<=>(const RegistrationKey&, const RegistrationKey&) = default;
};

// The sequential test that places an unplaced robot (docs/registration.md, "Evidence over time").
// Each registration of the robot's map on one target (the fleet map, or another robot's) votes
// for where the map sits. The robot is placed when the same placement has won
// - `confirmations` registrations in a row at the placement bar, or (off unless
//   `sequential_wins` > 0)
// - `sequential_wins` registrations in a row of its growing map, each verified (no
//   contradiction, no ambiguity) at `sequential_confidence` or more, the map grown between them.
// On repeated structure (rooms of one plan, shelf rows) an early map fits several places, and only
// the right one keeps winning as the map grows. The second way places the simulated fleet's
// robots several times sooner, where two robots' independent SLAM noise holds a right placement
// just under the bar; on growing pairs of repeated terrains most of what it adds is wrong, so it
// is off by default. A winner elsewhere starts the count again at 1; a refusal, or a confidence
// below what counts, resets it to 0 and says why. Not thread-safe: the placer owns it.
class PlacementEvidence {
 public:
  struct Options {
    int confirmations = 2;
    // The second way to be placed; 0 (the default) turns it off.
    int sequential_wins = 0;
    double sequential_confidence = 0.8;
    // Two placements are the same when they put the robot's map centre this close (metres) and
    // differ by at most this many degrees (PlacementOptions' revise_distance and revise_yaw_deg).
    double same_distance = 0.15;
    double same_yaw_deg = 1.5;
  };

  // What one registration says about the robot, on one target.
  struct Vote {
    Pose2 target_from_map;  // the best placement, also when refused
    Point2 map_centre = Point2::Zero();
    bool at_bar = false;    // found, at the placement bar's confidence
    bool verified = false;  // passed the verification (Registration::verified); implied by at_bar
    double confidence = 0.0;
    std::string why_not;       // when not at the bar
    uint64_t map_changes = 0;  // the revision of the robot's map that was registered
  };

  struct Verdict {
    bool place = false;
    int streak = 0;   // registrations in a row that found this placement at the bar
    int wins = 0;     // ... verified at sequential_confidence or more, each on a grown map
    std::string why;  // while not placed: why it waits, for people (robot_frames, the log)
  };

  explicit PlacementEvidence(const Options& options) : options_(options) {}

  Verdict Observe(const RegistrationKey& key, const Vote& vote);
  // Whether the robot waits for a confirmation of this kind of registration: one found a
  // placement at the bar that has not won often enough yet (a map that stopped growing is
  // registered again for it; the sequential wins need a grown map).
  bool Pending(const RegistrationKey& key) const;
  // The robot was placed, or left: its count starts again.
  void Forget(const RobotId& robot);

 private:
  struct Leader {
    Pose2 target_from_map;
    int streak = 0;
    int wins = 0;
    uint64_t map_changes = 0;  // of the last win counted
  };

  bool Same(const Pose2& a, const Pose2& b, const Point2& centre) const;

  Options options_;
  std::map<RegistrationKey, Leader> leaders_;
};

}  // namespace fleetmap::registration
