#include "tests/hostile_peer/scenario_runner.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <thread>
#include <utility>

namespace fleetmap::hostile {
namespace {

using std::chrono::milliseconds;

constexpr milliseconds kStatusPeriod{500};  // as an agent: a third of the liveliness lease
constexpr milliseconds kTick{20};
// The hijacker claims the id for this long (so the server has matched it) before disposing.
constexpr milliseconds kHijackClaim{1500};
constexpr milliseconds kForgePeriod{500};
// Forged tiles carry revisions no honest agent reaches soon.
constexpr uint32_t kForgedRevision = 1000000;
constexpr std::chrono::seconds kYear{365 * 24 * 3600};

std::string KeyText(const TileKey& key) {
  std::string text = "(";  // appended, not "(" + ...: GCC 12 warns about that (-Wrestrict)
  text += std::to_string(key.x);
  text += ", ";
  text += std::to_string(key.y);
  text += ")";
  return text;
}

void Say(const std::string& line) {
  std::printf("hostile-peer: %s\n", line.c_str());
  std::fflush(stdout);
}

// The key of the i-th tile of a square block of n tiles at `origin`.
TileKey BlockKey(TileKey origin, int i, int n) {
  const int columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(n))));
  return TileKey{origin.x + i % columns, origin.y + i / columns};
}

}  // namespace

ScenarioRunner::ScenarioRunner(CyclonePeer& peer, ScenarioOptions options)
    : peer_(peer), options_(std::move(options)) {}

WireTime ScenarioRunner::OwnStamp() const {
  if (options_.future_stamp) return StampFromNow(kYear);
  if (options_.past_stamp) return WireTime{-5, 0};
  return StampFromNow();
}

StatusSample ScenarioRunner::StatusOf(const std::string& robot, WireTime stamp) {
  StatusSample status;
  status.robot_id = robot;
  status.stamp = stamp;
  status.sequence_number = ++sequence_;
  status.tiles_published = tiles_sent_;
  return status;
}

bool ScenarioRunner::Sent(bool written, uint64_t* counter) {
  if (!written) {
    std::fprintf(stderr, "hostile-peer: %s\n", error_.c_str());
    return false;
  }
  ++*counter;
  return true;
}

void ScenarioRunner::BuildOneShotTiles() {
  const double size = options_.tile_size;
  const std::string& me = options_.robot_id;
  std::vector<TileKey> own = options_.tiles;
  if (own.empty() && (options_.future_stamp || options_.past_stamp)) own.push_back({0, 0});
  for (const TileKey& key : own) {
    one_shot_.push_back({WallTile(me, key, size), false, true});
  }
  if (!own.empty()) {
    Say("tiles of " + me + " at " + std::to_string(own.size()) + " keys" +
        (options_.future_stamp ? ", stamped a year ahead"
         : options_.past_stamp ? ", stamped -5 s (before the epoch)"
                               : ""));
  }
  if (options_.far_key) {
    const TileKey far{std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::max()};
    one_shot_.push_back({WallTile(me, far, size), false, false});
    Say("far-key: tile " + KeyText(far) + " of " + me);
  }
  if (options_.spread > 0) {
    const auto step = static_cast<int32_t>(std::lround(options_.spread_metres / size));
    for (int i = 0; i < options_.spread; ++i) {
      const TileKey key{i * step, options_.spread_diagonal ? i * step : 0};
      one_shot_.push_back({WallTile(me, key, size), false, false});
    }
    Say("spread: " + std::to_string(options_.spread) + " tiles of " + me + " " +
        std::to_string(step) + " keys apart along " + (options_.spread_diagonal ? "x and y" : "x"));
  }
  if (options_.long_id > 0) {
    const std::string long_id(static_cast<size_t>(options_.long_id), 'x');
    one_shot_.push_back({WallTile(long_id, TileKey{0, 0}, size), false, false});
    one_shot_.push_back({WallTile(long_id, TileKey{0, 0}, size), true, false});
    Say("long-id: a robot id of " + std::to_string(long_id.size()) +
        " characters on robot_tiles, robot_status and fused_tiles");
  }
  if (options_.empty_id) {
    one_shot_.push_back({WallTile("", TileKey{0, 0}, size), false, false});
    Say("empty-id: a tile (0, 0) with robot_id \"\"");
  }
}

bool ScenarioRunner::SendOneShotTiles(bool first) {
  for (OneShot& shot : one_shot_) {
    if (!first) {
      shot.tile.revision = ++revision_;
      shot.tile.stamp = shot.own_stamp ? OwnStamp() : StampFromNow();
    } else if (shot.own_stamp) {
      shot.tile.stamp = OwnStamp();
    }
    const bool written = shot.fused ? peer_.WriteFusedTile(shot.tile, &error_)
                                    : peer_.WriteRobotTile(shot.tile, &error_);
    if (!Sent(written, &tiles_sent_)) return false;
  }
  if (first && !one_shot_.empty()) {
    Say("sent " + std::to_string(one_shot_.size()) + " tiles");
  }
  return true;
}

bool ScenarioRunner::SendStatuses() {
  if (options_.status) {
    if (!Sent(peer_.WriteStatus(StatusOf(options_.robot_id, OwnStamp()), &error_),
              &statuses_sent_)) {
      return false;
    }
  }
  if (options_.long_id > 0) {
    const std::string long_id(static_cast<size_t>(options_.long_id), 'x');
    if (!Sent(peer_.WriteStatus(StatusOf(long_id, StampFromNow()), &error_), &statuses_sent_)) {
      return false;
    }
  }
  // The squatter, and the hijacker both before and after its dispose, keep claiming the id.
  for (const std::string& claimed : {options_.squat, options_.hijack}) {
    if (claimed.empty()) continue;
    if (!Sent(peer_.WriteStatus(StatusOf(claimed, StampFromNow()), &error_), &statuses_sent_)) {
      return false;
    }
  }
  return true;
}

bool ScenarioRunner::StepHijack(Clock::duration elapsed) {
  const std::string& victim = options_.hijack;
  std::set<TileKey> keys = peer_.RobotTileKeys(victim);  // learns the victim's tiles meanwhile
  if (!keys.empty() && !victim_tiles_read_) {
    victim_tiles_read_ = true;
    Say("hijack: read the tiles of " + victim + " at " + std::to_string(keys.size()) + " keys");
  }
  if (!hijack_disposed_) {
    if (elapsed < kHijackClaim) return true;
    if (!Sent(peer_.DisposeStatus(StatusOf(victim, StampFromNow()), &error_), &statuses_sent_)) {
      return false;
    }
    // Claims the id again at once, before the real agent's next status can.
    if (!Sent(peer_.WriteStatus(StatusOf(victim, StampFromNow()), &error_), &statuses_sent_)) {
      return false;
    }
    hijack_disposed_ = true;
    Say("hijack: disposed the robot_status instance of " + victim + " and claimed it");
    next_forge_ = Clock::now();
  }
  if (Clock::now() < next_forge_) return true;
  next_forge_ += kForgePeriod;
  if (keys.empty()) keys.insert(TileKey{0, 0});  // nothing seen of the victim: its likely tile
  for (const TileKey& key : keys) {
    TileSample tile = AllFreeTile(victim, key, options_.tile_size);
    tile.revision = kForgedRevision + revision_;
    if (!Sent(peer_.WriteRobotTile(tile, &error_), &tiles_sent_)) return false;
    if (forged_.insert(key).second) {
      Say("hijack: forged an all-free tile " + KeyText(key) + " of " + victim);
    }
  }
  ++revision_;
  return true;
}

bool ScenarioRunner::SendFloodRound(uint32_t round) {
  for (int i = 0; i < options_.flood_tiles; ++i) {
    const TileKey key = BlockKey(options_.flood_origin, i, options_.flood_tiles);
    TileSample tile =
        options_.flood_zstd_bomb
            ? ZstdBombTile(options_.robot_id, key, options_.tile_size, options_.flood_vertices)
            : HeavyTile(options_.robot_id, key, options_.tile_size, options_.flood_vertices,
                        round * static_cast<uint32_t>(options_.flood_tiles) + i);
    tile.revision = round + 1;
    if (!Sent(peer_.WriteRobotTile(tile, &error_), &tiles_sent_)) return false;
  }
  if (round == 0) {
    char rate[32];
    std::snprintf(rate, sizeof(rate), "%g", options_.flood_rate);
    Say(std::string(options_.flood_zstd_bomb ? "flood (zstd bombs): " : "flood: ") +
        std::to_string(options_.flood_tiles) + " tiles of " +
        std::to_string(options_.flood_vertices) + " vertices, " + rate + " rounds per second");
  }
  return true;
}

bool ScenarioRunner::SendFloodKeys() {
  for (int i = 0; i < options_.flood_keys; ++i) {
    const TileKey key = BlockKey(options_.flood_origin, i, options_.flood_keys);
    if (!Sent(peer_.WriteRobotTile(WallTile(options_.robot_id, key, options_.tile_size), &error_),
              &tiles_sent_)) {
      return false;
    }
  }
  Say("flood-keys: sent " + std::to_string(options_.flood_keys) + " distinct tile keys of " +
      options_.robot_id + " from " + KeyText(options_.flood_origin));
  return true;
}

void ScenarioRunner::ReportMatches() {
  const int tiles = peer_.MatchedRobotTileReaders();
  const int statuses = peer_.MatchedStatusReaders();
  if (tiles != tile_readers_) {
    Say("matched " + std::to_string(tiles) + " reader(s) on " + kRobotTilesTopic);
  }
  if (statuses != status_readers_) {
    Say("matched " + std::to_string(statuses) + " reader(s) on " + kRobotStatusTopic);
  }
  tile_readers_ = tiles;
  status_readers_ = statuses;
}

bool ScenarioRunner::Run(const std::atomic<bool>& stop) {
  const Clock::time_point start = Clock::now();
  BuildOneShotTiles();
  bool ok = SendOneShotTiles(true) && SendStatuses();
  if (ok && options_.flood_keys > 0) ok = SendFloodKeys();
  Clock::time_point next_status = start + kStatusPeriod;
  Clock::time_point next_resend = start + options_.period;
  Clock::time_point next_flood = start;
  const auto flood_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / std::max(options_.flood_rate, 1e-3)));
  uint32_t flood_round = 0;
  while (ok && !stop.load() && Clock::now() - start < options_.duration) {
    const Clock::time_point now = Clock::now();
    if (now >= next_status) {
      ok = SendStatuses();
      next_status += kStatusPeriod;
    }
    if (ok && options_.period.count() > 0 && now >= next_resend) {
      ok = SendOneShotTiles(false);
      next_resend += options_.period;
    }
    if (ok && options_.flood && now >= next_flood) {
      ok = SendFloodRound(flood_round++);
      // A round that took longer than the period starts the next one at once, never a burst.
      next_flood = std::max(next_flood + flood_period, Clock::now());
    }
    if (ok && !options_.hijack.empty()) ok = StepHijack(now - start);
    ReportMatches();
    std::this_thread::sleep_for(kTick);
  }
  Say("done: " + std::to_string(tiles_sent_) + " tiles and " + std::to_string(statuses_sent_) +
      " statuses sent" + (ok ? "" : " (stopped by a write error)"));
  return ok;
}

}  // namespace fleetmap::hostile
