#pragma once

// What the page shows, kept from what the view's DDS readers hand over: the fused tiles, every
// robot (pose, path, state, wire rates, latency), the sub-map graph, the learned objects and a
// status line. It turns that into the page's two events: the whole state, for a browser that has
// just connected, and a delta of what changed since the previous delta. Plain data in, JSON out:
// no DDS, no threads (the view service calls it from one thread).

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/core/robot_status.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "view/json_dictionary.hpp"
#include "view/robot_path.hpp"

namespace fleetmap::view {

struct ViewModelOptions {
  // A robot whose status stops for this long is shown stale; DDS declares it lost once its
  // liveliness lease (2 s) lapses, which the page shows as lost.
  std::chrono::milliseconds stale_after{1200};
  // Wire rates are averaged over this window.
  std::chrono::seconds rate_window{5};
  // The recent path: this many points, one at least this far from the previous.
  size_t path_points = 200;
  double path_spacing_m = 0.2;
  // Bounds on what any peer can make the view hold: past them, new robots and new items of a
  // section (tiles, sub-maps, objects, templates) are refused and counted with their topic's
  // refusals; known ones still update.
  size_t max_robots = 1024;
  size_t max_items = 100000;
};

class FleetViewModel {
 public:
  explicit FleetViewModel(ViewModelOptions options = {});

  // rt/fleetmap/fused_tiles: a tile, its removal, or a refused sample.
  void OnFusedTile(const transport::TileEvent& event);
  // rt/fleetmap/robot_tiles: what each robot costs the wire (bytes/s, updates/s, latency), and
  // the tiles of a robot that maps in its own frame, shown (in its colour) until it is placed.
  void OnRobotTile(const transport::TileEvent& event);
  // rt/fleetmap/robot_status: the robot's pose and liveliness.
  void OnRobotEvent(const transport::RobotEvent& event, Timestamp now);
  // rt/fleetmap/robot_frames: where the server placed a robot's map frame.
  void OnRobotFrame(const transport::RobotFrameEvent& event);
  void OnSubmap(const transport::SubmapEvent& event);
  void OnObject(const transport::ObjectModelEvent& event);
  void OnTemplate(const transport::ObjectTemplateEvent& event);
  // rt/fleetmap/route_graph: the fleet map as a route graph, drawn as a layer.
  void OnRouteGraph(const transport::RouteGraphEvent& event);
  // rt/fleetmap/servers: which server serves the fleet (docs/standby.md).
  void OnServer(const transport::FleetServerEvent& event, Timestamp now);
  // rt/fleetmap/map: the fused grid the page can lay under the vectors.
  void OnFleetMap(const transport::MapMessage& map);
  // A sample one of the view's readers refused (malformed, or from a writer it may not have).
  void CountRejected(std::string_view topic);

  // Brings the time-driven parts up to `now`: live robots that went quiet turn stale, rates move,
  // servers not heard for transport::kServerSilenceLimit are gone. Once the last server is gone,
  // live robots are shown stale: nothing fuses or places what they send.
  void Tick(Timestamp now);

  // The whole state: {"type": "full", "seq", "tiles", "robots", "paths", "submaps", "objects",
  // "templates", "status"} (docs/view.md).
  std::string FullEvent() const;
  // The sections that changed since the previous delta (same layout, "type": "delta", removed
  // items null; "path_points" instead of "paths": only the points each path gained), or nullopt
  // when nothing did. Each delta advances `seq`.
  std::optional<std::string> TakeDelta();

  size_t tile_count() const { return tiles_.size(); }
  size_t robot_count() const { return robots_.size(); }

 private:
  enum class Liveliness { kLive, kStale, kLost, kLeft };
  struct TileSample {
    Timestamp received;
    size_t bytes = 0;
    double latency_ms = 0.0;
  };
  struct Robot {
    explicit Robot(const ViewModelOptions& options)
        : path(options.path_points, options.path_spacing_m) {}
    std::optional<RobotStatus> status;
    std::optional<transport::RobotFrameMessage> frame;
    Liveliness liveliness = Liveliness::kLive;
    Timestamp last_status{};
    RobotPath path;
    std::deque<TileSample> tiles;  // received within the rate window
    // Its tiles while it may be unplaced, by own_tiles key; shown while it is known to be.
    std::map<std::string, nlohmann::json> own_tiles;
    bool own_tiles_shown = false;
  };

  // The robot's record, made on first sight; nullptr (counted as refused on `topic`) for a new
  // robot past max_robots.
  Robot* RobotNamed(const RobotId& id, std::string_view topic);
  // Whether `key` may be stored in `section`: known, or a new key within max_items (else counted
  // as refused on `topic`).
  bool Admit(const JsonDictionary& section, const std::string& key, std::string_view topic);
  // A keyed state topic's event into its section: put, removed, or counted as refused on `topic`.
  template <typename Message>
  void ApplyKeyed(const transport::KeyedEvent<Message>& event, const std::string& key,
                  JsonDictionary& section, nlohmann::json (*to_json)(const Message&),
                  std::string_view topic);
  // Whether the robot's tiles are in its own, unplaced map frame: false once the server placed it
  // or when its status says it tiles in the fleet frame; nullopt before its first status.
  static std::optional<bool> OwnFrame(const Robot& robot);
  // Shows or hides the robot's own-frame tiles as OwnFrame says, and forgets them once placed.
  void RefreshOwnTiles(Robot& robot);
  // Own-frame tiles held in all robots' records, shown or not (bounded by max_items).
  size_t CountOwnTiles() const;
  // Where the robot's map frame sits in the fleet frame: the server's placement once it has one,
  // else as the robot's status gives it.
  static Pose2 FleetFromMap(const Robot& robot);
  // The robot's pose in the fleet frame: its status pose through the newest placement.
  std::optional<Pose2> FleetPose(const Robot& robot) const;
  nlohmann::json RobotJson(const std::string& id, const Robot& robot, Timestamp now) const;
  nlohmann::json StatusJson() const;
  // The serving server: {"name", "strength", "robots", "standbys"}, or null when none is live.
  nlohmann::json ServerJson() const;
  void RefreshRobot(const std::string& id, Timestamp now);

  ViewModelOptions options_;
  std::map<std::string, Robot> robot_state_;
  JsonDictionary tiles_;
  JsonDictionary own_tiles_;  // "robot/x,y": the own-frame tiles of unplaced robots
  JsonDictionary robots_;
  JsonDictionary submaps_;
  JsonDictionary objects_;
  JsonDictionary templates_;
  JsonDictionary route_graphs_;  // by graph id ("fleet", or a shard's)
  struct Server {
    transport::FleetServerMessage last;
    Timestamp heard;
  };
  // Of the live servers of `shard` (empty: unsharded), the one that serves (or, while none says
  // so, the strongest); nullptr when none.
  const Server* ServingServer(const std::string& shard) const;
  // One entry per shard whose servers are live (docs/shards.md): its name, region, server.
  nlohmann::json ShardsJson() const;
  // Live servers by id; whether one was ever heard (no server is news only after one was).
  std::map<std::string, Server> servers_;
  bool server_seen_ = false;
  std::optional<nlohmann::json> grid_;  // the newest fused grid's geometry
  uint64_t maps_received_ = 0;
  std::map<std::string, uint64_t, std::less<>> rejected_by_topic_;
  nlohmann::json sent_status_;
  uint64_t seq_ = 0;
  Timestamp now_{};
};

}  // namespace fleetmap::view
