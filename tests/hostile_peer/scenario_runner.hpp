#pragma once

// The hostile peer's scenarios (issue 15), run over one CyclonePeer for a given time. Each is one
// option and they combine: all one-shot tiles go out first (again every `period` if set), the
// statuses every 0.5 s (each renews the writer's liveliness), the flood and the hijack on their
// own clocks. Prints one line per action to stdout, so a test can wait for it.
// Not thread-safe: construct, Run once.

#include <atomic>
#include <chrono>
#include <set>
#include <string>
#include <vector>

#include "tests/hostile_peer/cyclone_peer.hpp"
#include "tests/hostile_peer/hostile_samples.hpp"

namespace fleetmap::hostile {

struct ScenarioOptions {
  std::string robot_id = "intruder";          // the peer's own robot
  double tile_size = 10.0;                    // metres, as the fleet tiles
  std::chrono::milliseconds duration{10000};  // how long the participant stays
  std::chrono::milliseconds period{0};        // re-send one-shot tiles this often (0: once)
  bool status = true;                         // a status of robot_id every 0.5 s
  std::vector<TileKey> tiles;                 // valid wall tiles of robot_id
  bool far_key = false;                       // a tile keyed (2^31-1, 2^31-1)
  int spread = 0;                             // tiles `spread_metres` apart along x
  double spread_metres = 1000.0;
  bool spread_diagonal = false;  // ... along x and y (a square bounding box)
  int long_id = 0;               // a robot id this long on all three topics (0: off)
  bool empty_id = false;         // tiles with robot_id ""
  bool future_stamp = false;     // robot_id's tiles and statuses a year ahead
  bool past_stamp = false;       // ... at -5 s (before the epoch)
  std::string hijack;            // claim, dispose, then erase this robot's walls
  std::string squat;             // claim this robot id and keep it
  bool flood = false;            // heavy tiles at a rate
  int flood_tiles = 40;
  double flood_rate = 5.0;       // rounds per second
  int flood_vertices = 4000;     // per tile
  bool flood_zstd_bomb = false;  // flood tiles are zstd bombs of flood_vertices vertices
  int flood_keys = 0;            // this many distinct light tiles, once
  TileKey flood_origin{0, 0};    // corner of the square block of flooded keys
};

class ScenarioRunner {
 public:
  ScenarioRunner(CyclonePeer& peer, ScenarioOptions options);

  // Runs until the duration ends or `stop` is set; false if a sample could not be written.
  bool Run(const std::atomic<bool>& stop);

 private:
  using Clock = std::chrono::steady_clock;

  struct OneShot {
    TileSample tile;
    bool fused = false;      // on rt/fleetmap/fused_tiles rather than robot_tiles
    bool own_stamp = false;  // stamped as robot_id's (future / past), else now
  };

  // The one-shot tiles of the options (far key, spread, long and empty ids, own tiles).
  void BuildOneShotTiles();
  bool SendOneShotTiles(bool first);
  bool SendStatuses();
  bool StepHijack(Clock::duration elapsed);
  bool SendFloodRound(uint32_t round);
  bool SendFloodKeys();
  void ReportMatches();
  WireTime OwnStamp() const;
  StatusSample StatusOf(const std::string& robot, WireTime stamp);
  // Counts a written sample, or prints why it was not written.
  bool Sent(bool written, uint64_t* counter);

  CyclonePeer& peer_;
  ScenarioOptions options_;
  std::vector<OneShot> one_shot_;
  uint32_t sequence_ = 0;  // of statuses
  uint32_t revision_ = 1;  // of re-sent and forged tiles
  int tile_readers_ = 0;   // last reported matches
  int status_readers_ = 0;
  bool hijack_disposed_ = false;
  bool victim_tiles_read_ = false;  // said once: the tiles of the victim were read
  std::set<TileKey> forged_;        // keys of the hijacked robot already reported
  Clock::time_point next_forge_{};
  std::string error_;
  uint64_t tiles_sent_ = 0;
  uint64_t statuses_sent_ = 0;
};

}  // namespace fleetmap::hostile
