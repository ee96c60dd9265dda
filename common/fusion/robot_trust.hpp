#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/types.hpp"
#include "common/fusion/contradiction.hpp"
#include "common/fusion/fusion_options.hpp"

namespace fleetmap::fusion {

// Whether a robot's tiles are fused.
enum class Standing {
  kTrusted,      // fused
  kQuarantined,  // kept, not fused: its map contradicts what the fleet established
  kAdmitted,     // an operator admitted it (`fleetmap admit`): fused, never quarantined again
};

const char* StandingName(Standing standing);

// A robot's standing and why, for robot_frames, the view and the log.
struct TrustReport {
  RobotId robot;
  Standing standing = Standing::kTrusted;
  int64_t contradicted_cells = 0;  // summed over its tiles
  int64_t established_seen = 0;    // the fleet's established occupied cells it knows
  double share = 0.0;              // contradicted / established_seen (0 when it sees none)
  double contradicted_m = 0.0;     // contradicted_cells as metres of wall
  // The contradicting area in the fleet frame (metres): the bounding box of its contradicted
  // cells, empty (min > max) when there are none.
  Point2 area_min = Point2::Zero();
  Point2 area_max = Point2(-1.0, -1.0);
  std::string reason;  // for people: why it entered (or left) quarantine; empty when trusted
  // False when only the figures of a quarantined robot moved (its standing did not change).
  bool standing_changed = true;
};

// The quarantine's bookkeeping: every robot's contradiction, tile by tile, and the rule that
// turns it into a standing (QuarantineOptions). It decides; TileFusion counts and fuses.
// Not thread-safe: TileFusion's owner calls it.
class RobotTrust {
 public:
  RobotTrust(const QuarantineOptions& options, double tile_size, double resolution);

  // The robot's contradiction on `tile` now (replacing the last count for that tile).
  void Record(const RobotId& robot, const TileId& tile, const TileContradiction& counted);
  // The robot no longer contributes to `tile`.
  void ForgetTile(const RobotId& robot, const TileId& tile);
  // Applies the rule to the robot's counts; true when its standing changed.
  bool Decide(const RobotId& robot);
  // Applies the corroboration rule (QuarantineOptions::corroborate_share) to the robot's counts;
  // true when the robot became corroborated. It stays so until Forget(): a robot whose map moves
  // (a relocalization, a wrong transform) must not take the corroboration of the robots that
  // confirmed it, and with it the evidence it is weighed against, away by disagreeing with them.
  bool Corroborate(const RobotId& robot);
  // Whether robots of other participants confirmed enough of the robot's walls.
  bool corroborated(const RobotId& robot) const;
  // An operator's word: the robot is fused and never quarantined again (until Forget).
  // True when its standing changed.
  bool Admit(const RobotId& robot);
  // The robot's data is gone for good: its counts and standing too.
  void Forget(const RobotId& robot);

  // Whether a quarantined robot's contradiction moved by a quarter, or by min_contradicted_m,
  // since its last TakeReport(): what an operator sees follows the evidence while it waits.
  bool FiguresMoved(const RobotId& robot) const;
  // Report(), remembered as the last one given out.
  TrustReport TakeReport(const RobotId& robot);

  Standing standing(const RobotId& robot) const;
  bool quarantined(const RobotId& robot) const { return standing(robot) == Standing::kQuarantined; }
  TrustReport Report(const RobotId& robot) const;
  // Robots quarantined now.
  std::vector<RobotId> quarantined_robots() const;
  const QuarantineOptions& options() const { return options_; }

 private:
  struct Totals {
    int64_t contradicted = 0;
    int64_t established_seen = 0;
    int64_t walls_known = 0;
    int64_t walls_confirmed = 0;
  };
  struct Book {
    std::map<TileId, TileContradiction> tiles;
    Standing standing = Standing::kTrusted;
    bool corroborated = false;
    std::string reason;
    int64_t reported_contradicted = 0;  // at the last TakeReport()
  };

  Totals TotalsOf(const Book& book) const;
  std::string Describe(const Totals& totals) const;

  QuarantineOptions options_;
  double tile_size_;
  double resolution_;
  int64_t min_cells_;  // min_contradicted_m of wall, in cells
  int64_t max_cells_;  // max_contradicted_m likewise
  std::map<RobotId, Book> books_;
};

}  // namespace fleetmap::fusion
