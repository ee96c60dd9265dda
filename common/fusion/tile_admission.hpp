#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "common/core/ids.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/robot_status.hpp"
#include "common/fusion/fusion_options.hpp"
#include "common/fusion/refusal.hpp"
#include "common/fusion/tile_budget.hpp"
#include "common/vector_map/vector_tile.hpp"

namespace fleetmap::fusion {

// What the server accepts from one robot. The defaults admit any honest agent with room to
// spare and bound what a misbehaving or hostile peer can make the server hold.
struct AdmissionOptions {
  // Stamps later than the server's clock by more than this are refused (robots' clocks drift;
  // a stamp from the future would win every conflict over newer evidence).
  std::chrono::milliseconds max_clock_ahead{std::chrono::seconds(30)};
  // Stamps older than this are refused. An agent's tiles reach a restarted server with the stamp
  // of their last change, which can be days old.
  std::chrono::hours max_age{24 * 30};
  // Distinct tiles one robot id may hold (a 10 m tile fused costs about 250 KB).
  size_t max_tiles_per_robot = 1024;
  // Sustained serialized bytes per second per robot, and the burst above it (a new robot sends
  // its whole map at once).
  double max_bytes_per_second = 4e6;
  double burst_bytes = 64e6;
  // What tiles may cost decoded: per tile, per robot, per participant and host, and in all.
  BudgetOptions budget;

  // What the tile reader may decode a robot tile to (the per-tile budget).
  vector_map::TileDecodeLimits DecodeLimits() const;
  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// Decides, tile by tile, whether a robot tile may reach fusion: its robot id, key, settings,
// stamp and the robot's quotas. DDS-free and deterministic given `now`. Not thread-safe: the
// fusion worker owns it.
class TileAdmission {
 public:
  struct Admitted {
    // The stamp fusion dates the tile's evidence with: the sample's own, but never later than
    // its arrival (evidence cannot be newer than the moment it was received).
    Timestamp evidence_stamp;
    // Robots claimed after this one whose data the caller must drop (DropRobot) to make room in
    // the global memory budget, newest first.
    std::vector<RobotId> evict;
  };
  struct Refused {
    Refusal reason;
    std::string detail;
  };
  using Verdict = std::variant<Admitted, Refused>;

  TileAdmission(const AdmissionOptions& options, const fusion::FusionOptions& fusion)
      : options_(options), fusion_(fusion), budget_(options.budget, fusion) {}

  // Whether `robot` may name a robot tile's owner: a ROS 2 name token, not the fused map's.
  static std::optional<Refused> CheckRobotId(const vector_map::VectorTile& tile);

  // Checks a decoded robot tile of `bytes` serialized bytes received at `now` (system clock for
  // stamps, steady clock for rates). An admitted tile counts towards its robot's quotas.
  Verdict Admit(const vector_map::VectorTile& tile, size_t bytes, Timestamp now,
                std::chrono::steady_clock::time_point steady_now);
  // The same, paid for by `source` (the robot id, the participant and host that sent it).
  Verdict Admit(const vector_map::VectorTile& tile, size_t bytes, const TileBudget::Source& source,
                Timestamp now, std::chrono::steady_clock::time_point steady_now);

  // A robot's tile that exists without passing Admit (restored from the store): it counts
  // towards the robot's tile quota.
  void Adopt(const RobotId& robot, const TileId& tile);
  // The robot removed the tile: it no longer counts.
  void Forget(const RobotId& robot, const TileId& tile);
  // Every tile of `robot` no longer counts; returns them (the caller drops their data).
  std::vector<TileId> DropRobot(const RobotId& robot);

  size_t tiles_held(const RobotId& robot) const;
  const TileBudget& budget() const { return budget_; }
  // See TileBudget::SetSharedBytes.
  void SetSharedBytes(uint64_t bytes) { budget_.SetSharedBytes(bytes); }

 private:
  struct RobotQuota {
    std::set<TileId> tiles;
    double byte_tokens = 0.0;
    std::chrono::steady_clock::time_point refilled{};
    bool started = false;
  };

  std::optional<Refused> CheckSettings(const vector_map::VectorTile& tile) const;
  std::optional<Refused> CheckStamp(const vector_map::VectorTile& tile, Timestamp now) const;

  AdmissionOptions options_;
  fusion::FusionOptions fusion_;
  TileBudget budget_;
  std::map<RobotId, RobotQuota> robots_;
};

}  // namespace fleetmap::fusion
