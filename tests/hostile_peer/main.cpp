// fleetmap-hostile-peer: a Cyclone DDS participant that sends fleetmap's servers and agents what
// a hostile or careless peer could (issue 15), to test that they survive it. docs/testing.md.
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "tests/hostile_peer/cyclone_peer.hpp"
#include "tests/hostile_peer/scenario_runner.hpp"

namespace {

std::atomic<bool> g_stop{false};

void OnSignal(int /*signal*/) { g_stop.store(true); }

// "X,Y" as a tile key.
std::string ParseKey(const std::string& text, fleetmap::hostile::TileKey* key) {
  const size_t comma = text.find(',');
  try {
    size_t used_x = 0;
    size_t used_y = 0;
    if (comma == std::string::npos) throw std::invalid_argument(text);
    key->x = std::stoi(text.substr(0, comma), &used_x);
    key->y = std::stoi(text.substr(comma + 1), &used_y);
    if (used_x != comma || used_y != text.size() - comma - 1) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    return "\"" + text + "\" is not a tile key X,Y";
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "fleetmap-hostile-peer: a DDS participant of another vendor (Cyclone DDS) that sends "
      "valid-but-hostile and oversized samples on fleetmap's topics, then stays for --duration"};
  fleetmap::hostile::ScenarioOptions options;
  int domain = -1;
  double duration_s = 10.0;
  double period_s = 0.0;
  bool no_status = false;
  bool any_interface = false;
  std::vector<std::string> tiles;
  std::string flood_origin = "0,0";
  app.add_option("--domain", domain, "DDS domain id (default: $FLEETMAP_DOMAIN, else 0)")
      ->check(CLI::Range(0, 232));
  app.add_option("--duration", duration_s, "seconds the participant stays (default 10)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--robot-id", options.robot_id, "the peer's own robot id (default intruder)");
  app.add_option("--tile-size", options.tile_size, "tile side in metres (default 10)")
      ->check(CLI::PositiveNumber);
  app.add_option("--period", period_s, "re-send the one-shot tiles every this many seconds")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--no-status", no_status, "do not publish a status of --robot-id");
  app.add_option("--tile", tiles, "a valid wall tile of --robot-id at X,Y (repeatable)");
  app.add_flag("--far-key", options.far_key, "a tile keyed (2^31-1, 2^31-1)");
  app.add_option("--spread", options.spread, "N tiles --spread-metres apart along x")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--spread-metres", options.spread_metres, "distance of --spread tiles (1000)")
      ->check(CLI::PositiveNumber);
  app.add_flag("--spread-diagonal", options.spread_diagonal,
               "--spread along x and y: key i at (i, i) * the step");
  app.add_flag("--long-id{300}", options.long_id,
               "a robot id of 300 (--long-id=N: N) characters on robot_tiles, robot_status and "
               "fused_tiles");
  app.add_flag("--empty-id", options.empty_id, "a tile with robot_id \"\"");
  app.add_flag("--future-stamp", options.future_stamp,
               "tiles (at --tile, default 0,0) and statuses of --robot-id stamped a year ahead");
  app.add_flag("--past-stamp", options.past_stamp,
               "tiles (at --tile, default 0,0) and statuses of --robot-id stamped -5 s");
  app.add_option("--hijack", options.hijack,
                 "claim ROBOT's id in a status, dispose it, then erase ROBOT's walls with "
                 "all-free tiles at the keys it published");
  app.add_option("--squat", options.squat, "claim ROBOT's id and keep sending its status");
  app.add_flag("--flood", options.flood, "heavy tiles at a rate for the whole duration");
  app.add_option("--flood-tiles", options.flood_tiles, "tiles per flood round (40)")
      ->check(CLI::PositiveNumber);
  app.add_option("--flood-rate", options.flood_rate, "flood rounds per second (5)")
      ->check(CLI::PositiveNumber);
  app.add_option("--flood-vertices", options.flood_vertices, "obstacle vertices per tile (4000)")
      ->check(CLI::Range(2, 1000000));
  app.add_flag("--flood-zstd-bomb", options.flood_zstd_bomb,
               "flood tiles are zstd frames of --flood-vertices repeated vertices (a few KB each)");
  app.add_option("--flood-keys", options.flood_keys,
                 "N distinct light tiles of --robot-id, once (e.g. 3000)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--flood-origin", flood_origin, "X,Y: corner of the flooded block of keys (0,0)");
  app.add_flag("--any-interface", any_interface,
               "use Cyclone's own configuration ($CYCLONEDDS_URI) instead of loopback only");
  CLI11_PARSE(app, argc, argv);

  for (const std::string& text : tiles) {
    fleetmap::hostile::TileKey key;
    if (const std::string error = ParseKey(text, &key); !error.empty()) {
      std::fprintf(stderr, "fleetmap-hostile-peer: --tile %s\n", error.c_str());
      return 2;
    }
    options.tiles.push_back(key);
  }
  if (const std::string error = ParseKey(flood_origin, &options.flood_origin); !error.empty()) {
    std::fprintf(stderr, "fleetmap-hostile-peer: --flood-origin %s\n", error.c_str());
    return 2;
  }
  if (domain < 0) {
    const char* env = std::getenv("FLEETMAP_DOMAIN");
    domain = env != nullptr && *env != '\0' ? std::atoi(env) : 0;
  }
  options.status = !no_status;
  options.duration = std::chrono::milliseconds(static_cast<int64_t>(duration_s * 1000.0));
  options.period = std::chrono::milliseconds(static_cast<int64_t>(period_s * 1000.0));

  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  fleetmap::hostile::PeerOptions peer_options;
  peer_options.domain_id = domain;
  peer_options.localhost_only = !any_interface;
  try {
    fleetmap::hostile::CyclonePeer peer(peer_options);
    std::printf("hostile-peer: Cyclone DDS participant on domain %d (%s)\n", domain,
                any_interface ? "Cyclone's own configuration" : "loopback only");
    std::fflush(stdout);
    fleetmap::hostile::ScenarioRunner runner(peer, options);
    return runner.Run(g_stop) ? 0 : 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fleetmap-hostile-peer: %s\n", error.what());
    return 1;
  }
}
