#include "view/fleet_view_model.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "common/transport/served_state.hpp"
#include "common/transport/topics.hpp"
#include "view/map_json.hpp"

namespace fleetmap::view {
namespace {

using nlohmann::json;

double Millimetres(double metres) { return std::round(metres * 1000.0) / 1000.0; }
// To a whole number of `per_unit`ths (10: tenths), which prints without binary noise (0.7, not
// 0.7000000000000001).
double Rounded(double value, double per_unit) { return std::round(value * per_unit) / per_unit; }

double SecondsBetween(Timestamp from, Timestamp to) {
  return std::chrono::duration<double>(to - from).count();
}

const char* LivelinessName(int liveliness) {
  static constexpr const char* kNames[] = {"live", "stale", "lost", "left"};
  return kNames[liveliness];
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

FleetViewModel::FleetViewModel(ViewModelOptions options) : options_(options) {}

FleetViewModel::Robot* FleetViewModel::RobotNamed(const RobotId& id, std::string_view topic) {
  const auto it = robot_state_.find(id.value);
  if (it != robot_state_.end()) return &it->second;
  if (robot_state_.size() >= options_.max_robots) {
    CountRejected(topic);
    return nullptr;
  }
  return &robot_state_.try_emplace(id.value, options_).first->second;
}

bool FleetViewModel::Admit(const JsonDictionary& section, const std::string& key,
                           std::string_view topic) {
  if (section.contains(key) || section.size() < options_.max_items) return true;
  CountRejected(topic);
  return false;
}

void FleetViewModel::OnFusedTile(const transport::TileEvent& event) {
  switch (event.kind) {
    case transport::TileEvent::Kind::kTile:
      if (const std::string key = TileKey(event.tile.tile);
          Admit(tiles_, key, transport::kFusedTilesTopic)) {
        tiles_.Put(key, TileJson(event.tile));
      }
      break;
    case transport::TileEvent::Kind::kRemoved:
      tiles_.Remove(TileKey(event.tile.tile));
      break;
    case transport::TileEvent::Kind::kRejected:
      CountRejected(transport::kFusedTilesTopic);
      break;
  }
}

void FleetViewModel::OnRobotTile(const transport::TileEvent& event) {
  if (event.kind == transport::TileEvent::Kind::kRejected) {
    CountRejected(transport::kRobotTilesTopic);
    return;
  }
  const std::string& id = event.tile.robot_id.value;
  const std::string key = id + "/" + TileKey(event.tile.tile);
  if (event.kind == transport::TileEvent::Kind::kRemoved) {
    if (const auto it = robot_state_.find(id); it != robot_state_.end())
      it->second.own_tiles.erase(key);
    own_tiles_.Remove(key);
    return;
  }
  Robot* robot = RobotNamed(event.tile.robot_id, transport::kRobotTilesTopic);
  if (robot == nullptr) return;
  robot->tiles.push_back({event.received, event.serialized_bytes,
                          1000.0 * SecondsBetween(event.tile.stamp, event.received)});
  // Its own-frame tiles, kept until the robot is known to be placed or to tile in the fleet frame.
  if (const std::optional<bool> own_frame = OwnFrame(*robot); own_frame && !*own_frame) return;
  if (robot->own_tiles.count(key) == 0 && CountOwnTiles() >= options_.max_items) {
    CountRejected(transport::kRobotTilesTopic);
    return;
  }
  json item = TileJson(event.tile);
  item["robot"] = id;
  if (robot->own_tiles_shown) own_tiles_.Put(key, item);
  robot->own_tiles[key] = std::move(item);
}

std::optional<bool> FleetViewModel::OwnFrame(const Robot& robot) {
  if (robot.frame && robot.frame->placed()) return false;
  if (!robot.status) return std::nullopt;
  return robot.status->tiles_in_map_frame;
}

size_t FleetViewModel::CountOwnTiles() const {
  size_t count = 0;
  for (const auto& [id, robot] : robot_state_) count += robot.own_tiles.size();
  return count;
}

void FleetViewModel::RefreshOwnTiles(Robot& robot) {
  const std::optional<bool> own_frame = OwnFrame(robot);
  const bool show = own_frame.value_or(false);
  if (show != robot.own_tiles_shown) {
    for (const auto& [key, item] : robot.own_tiles) {
      if (show) {
        own_tiles_.Put(key, item);
      } else {
        own_tiles_.Remove(key);
      }
    }
    robot.own_tiles_shown = show;
  }
  if (own_frame && !*own_frame) robot.own_tiles.clear();  // placed: the fused map holds them
}

void FleetViewModel::OnRobotEvent(const transport::RobotEvent& event, Timestamp now) {
  switch (event.kind) {
    case transport::RobotEvent::Kind::kStatus: {
      Robot* robot = RobotNamed(event.robot, transport::kRobotStatusTopic);
      if (robot == nullptr) return;
      robot->status = event.status;
      RefreshOwnTiles(*robot);
      robot->liveliness = Liveliness::kLive;
      robot->last_status = now;
      if (const std::optional<Pose2> pose = FleetPose(*robot)) {
        robot->path.Add(pose->translation(), FleetFromMap(*robot));
      }
      break;
    }
    case transport::RobotEvent::Kind::kLeft:
    case transport::RobotEvent::Kind::kLost: {
      // Only a robot the view knows can leave or be lost.
      const auto it = robot_state_.find(event.robot.value);
      if (it == robot_state_.end()) return;
      Liveliness& liveliness = it->second.liveliness;
      // As the server has it (ServerNode::OnRobotGone), only a robot still there can go: its end
      // stands until it sends a status again. An agent that exits cleanly disposes its status
      // (left), then its writer goes, which DDS reports too (lost): that is not news.
      if (liveliness == Liveliness::kLeft || liveliness == Liveliness::kLost) return;
      liveliness =
          event.kind == transport::RobotEvent::Kind::kLeft ? Liveliness::kLeft : Liveliness::kLost;
      break;
    }
    case transport::RobotEvent::Kind::kRejected:
      CountRejected(transport::kRobotStatusTopic);
      return;
  }
  RefreshRobot(event.robot.value, now);
}

void FleetViewModel::OnRobotFrame(const transport::RobotFrameEvent& event) {
  if (event.kind == transport::RobotFrameEvent::Kind::kRejected) {
    CountRejected(transport::kRobotFramesTopic);
    return;
  }
  Robot* robot = RobotNamed(event.message.robot, transport::kRobotFramesTopic);
  if (robot == nullptr) return;
  if (event.kind == transport::RobotFrameEvent::Kind::kSample) {
    robot->frame = event.message;
  } else {
    robot->frame.reset();
  }
  RefreshOwnTiles(*robot);
}

template <typename Message>
void FleetViewModel::ApplyKeyed(const transport::KeyedEvent<Message>& event, const std::string& key,
                                JsonDictionary& section, json (*to_json)(const Message&),
                                std::string_view topic) {
  switch (event.kind) {
    case transport::KeyedEvent<Message>::Kind::kSample:
      if (Admit(section, key, topic)) section.Put(key, to_json(event.message));
      break;
    case transport::KeyedEvent<Message>::Kind::kRemoved:
      section.Remove(key);
      break;
    case transport::KeyedEvent<Message>::Kind::kRejected:
      CountRejected(topic);
      break;
  }
}

void FleetViewModel::OnSubmap(const transport::SubmapEvent& event) {
  ApplyKeyed(event, std::to_string(event.message.submap.id), submaps_, &SubmapJson,
             transport::kSubmapGraphTopic);
}

void FleetViewModel::OnObject(const transport::ObjectModelEvent& event) {
  ApplyKeyed(event, std::to_string(event.message.object_id), objects_, &ObjectJson,
             transport::kObjectsTopic);
}

void FleetViewModel::OnTemplate(const transport::ObjectTemplateEvent& event) {
  ApplyKeyed(event, std::to_string(event.message.template_id), templates_, &TemplateJson,
             transport::kObjectTemplatesTopic);
}

void FleetViewModel::OnRouteGraph(const transport::RouteGraphEvent& event) {
  ApplyKeyed(event, event.message.graph_id, route_graphs_, &RouteGraphJson,
             transport::kRouteGraphTopic);
}

void FleetViewModel::OnFleetMap(const transport::MapMessage& map) {
  ++maps_received_;
  const grid::OccupancyGrid& grid = map.grid;
  grid_ = json{{"count", maps_received_},
               {"w", grid.width()},
               {"h", grid.height()},
               {"res", Rounded(grid.resolution(), 1e6)},  // the wire's float, not its noise
               {"ox", Millimetres(grid.origin().x)},
               {"oy", Millimetres(grid.origin().y)}};
}

void FleetViewModel::CountRejected(std::string_view topic) {
  auto it = rejected_by_topic_.find(topic);
  if (it == rejected_by_topic_.end()) it = rejected_by_topic_.emplace(std::string(topic), 0).first;
  ++it->second;
}

Pose2 FleetViewModel::FleetFromMap(const Robot& robot) {
  if (robot.frame && robot.frame->placed()) return robot.frame->fleet_from_map;
  return robot.status ? robot.status->fleet_from_map : Pose2{};
}

std::optional<Pose2> FleetViewModel::FleetPose(const Robot& robot) const {
  if (!robot.status) return std::nullopt;
  return Pose2::FromTransform(FleetFromMap(robot).ToTransform() *
                              robot.status->map_from_robot.ToTransform());
}

json FleetViewModel::RobotJson(const std::string& id, const Robot& robot, Timestamp now) const {
  json out = {{"id", id}, {"state", LivelinessName(static_cast<int>(robot.liveliness))}};
  // Where its map frame sits: as given, or as the server placed it (registration).
  std::string placement = "given";
  if (robot.frame) {
    placement = RobotFrameStateName(robot.frame->state);
  } else if (robot.status && robot.status->tiles_in_map_frame) {
    placement = "unplaced";
  }
  out["placement"] = placement;
  if (robot.frame && !robot.frame->placed() && !robot.frame->waiting_reason.empty()) {
    out["waiting_reason"] = robot.frame->waiting_reason;
  }
  // Whether the server fuses its tiles (docs/fleet.md, "Quarantine"), why not, and where.
  out["standing"] = robot.frame ? RobotStandingName(robot.frame->standing) : "trusted";
  if (robot.frame && robot.frame->standing != transport::RobotFrameMessage::Standing::kTrusted) {
    out["standing_reason"] = robot.frame->standing_reason;
  }
  if (robot.frame &&
      robot.frame->standing == transport::RobotFrameMessage::Standing::kQuarantined &&
      robot.frame->area_min.x() <= robot.frame->area_max.x()) {
    out["area"] = {Millimetres(robot.frame->area_min.x()), Millimetres(robot.frame->area_min.y()),
                   Millimetres(robot.frame->area_max.x()), Millimetres(robot.frame->area_max.y())};
  }
  if (const std::optional<Pose2> pose = FleetPose(robot)) {
    out["x"] = Millimetres(pose->x);
    out["y"] = Millimetres(pose->y);
    out["yaw"] = Millimetres(pose->yaw);
  }
  if (robot.status) {
    out["rev"] = robot.status->map_revision;
    out["tiles_published"] = robot.status->tiles_published;
  }
  // Rates over the window, or over the time the robot has been seen if that is shorter; rounded
  // so that an unchanged rate does not make a delta.
  double bytes = 0.0;
  std::vector<double> latencies;
  for (const TileSample& sample : robot.tiles) {
    bytes += static_cast<double>(sample.bytes);
    latencies.push_back(sample.latency_ms);
  }
  const double window = std::chrono::duration<double>(options_.rate_window).count();
  const double span =
      robot.tiles.empty()
          ? window
          : std::clamp(SecondsBetween(robot.tiles.front().received, now), 1.0, window);
  out["bps"] = Rounded(bytes / span, 1);
  out["ups"] = Rounded(static_cast<double>(robot.tiles.size()) / span, 10);
  out["latency_ms"] = latencies.empty() ? json(nullptr) : json(Rounded(Median(latencies), 10));
  return out;
}

void FleetViewModel::RefreshRobot(const std::string& id, Timestamp now) {
  const auto it = robot_state_.find(id);
  if (it == robot_state_.end() || !it->second.status) return;  // nothing to show yet
  robots_.Put(id, RobotJson(id, it->second, now));
}

void FleetViewModel::OnServer(const transport::FleetServerEvent& event, Timestamp now) {
  switch (event.kind) {
    case transport::FleetServerEvent::Kind::kSample:
      servers_[event.message.server_id] = Server{event.message, now};
      server_seen_ = true;
      break;
    case transport::FleetServerEvent::Kind::kRemoved:
      servers_.erase(event.message.server_id);
      break;
    case transport::FleetServerEvent::Kind::kRejected:
      CountRejected(transport::kServersTopic);
      break;
  }
}

const FleetViewModel::Server* FleetViewModel::ServingServer(const std::string& shard) const {
  const Server* best = nullptr;
  for (const auto& [id, server] : servers_) {
    if (server.last.shard != shard) continue;
    const auto rank = [](const Server& s) {
      return std::make_tuple(s.last.serving, s.last.ownership_strength);
    };
    if (best == nullptr || rank(server) > rank(*best)) best = &server;
  }
  return best;
}

void FleetViewModel::Tick(Timestamp now) {
  now_ = now;
  std::erase_if(servers_, [&](const auto& entry) {
    return now - entry.second.heard > transport::kServerSilenceLimit;
  });
  const bool no_server = server_seen_ && servers_.empty();
  for (auto& [id, robot] : robot_state_) {
    while (!robot.tiles.empty() && now - robot.tiles.front().received > options_.rate_window) {
      robot.tiles.pop_front();
    }
    const bool quiet = now - robot.last_status > options_.stale_after;
    if (robot.liveliness == Liveliness::kLive && (quiet || no_server)) {
      robot.liveliness = Liveliness::kStale;
    }
    RefreshRobot(id, now);
  }
}

json FleetViewModel::StatusJson() const {
  size_t live = 0;
  size_t lost = 0;
  double bytes_per_s = 0.0;
  double updates_per_s = 0.0;
  for (const auto& [id, robot] : robots_.items()) {
    live += robot["state"] == "live" ? 1 : 0;
    lost += robot["state"] == "lost" ? 1 : 0;
    bytes_per_s += robot["bps"].get<double>();
    updates_per_s += robot["ups"].get<double>();
  }
  std::map<std::string, size_t> submap_states;
  for (const auto& [id, submap] : submaps_.items()) ++submap_states[submap["state"]];
  uint64_t rejected = 0;
  for (const auto& [topic, count] : rejected_by_topic_) rejected += count;
  return {{"tiles", tiles_.size()},
          {"robots", robots_.size()},
          {"live", live},
          {"lost", lost},
          {"bytes_per_s", Rounded(bytes_per_s, 1)},
          {"updates_per_s", Rounded(updates_per_s, 10)},
          {"submaps", submap_states},
          {"objects", objects_.size()},
          {"templates", templates_.size()},
          {"rejected", rejected},
          {"rejected_by_topic", rejected_by_topic_},
          {"grid", grid_ ? *grid_ : json(nullptr)},
          {"server", ServerJson()}};
}

json FleetViewModel::ServerJson() const {
  const Server* serving = ServingServer("");
  json shards = ShardsJson();
  if (serving == nullptr && shards.empty()) return nullptr;
  json server = json::object();
  if (serving != nullptr) {
    const size_t unsharded =
        static_cast<size_t>(std::count_if(servers_.begin(), servers_.end(), [](const auto& s) {
          return s.second.last.shard.empty();
        }));
    server = {{"name", serving->last.name},
              {"strength", serving->last.ownership_strength},
              {"robots", serving->last.robots},
              {"standbys", unsharded - 1}};
  }
  if (!shards.empty()) server["shards"] = std::move(shards);
  return server;
}

json FleetViewModel::ShardsJson() const {
  std::map<std::string, size_t> servers_by_shard;
  for (const auto& [id, server] : servers_) {
    if (!server.last.shard.empty()) ++servers_by_shard[server.last.shard];
  }
  json shards = json::array();
  for (const auto& [shard, count] : servers_by_shard) {
    const Server* serving = ServingServer(shard);
    const std::array<double, 4>& r = serving->last.region;
    shards.push_back({{"name", shard},
                      {"server", serving->last.name},
                      {"robots", serving->last.robots},
                      {"standbys", count - 1},
                      {"region", {r[0], r[1], r[2], r[3]}}});
  }
  return shards;
}

std::string FleetViewModel::FullEvent() const {
  // Paths travel apart from the robots: whole here, then only the points they gain (a robot's
  // item changes several times a second; resending its path with it would be most of the stream).
  json paths = json::object();
  for (const auto& [id, robot] : robot_state_) {
    if (robots_.items().count(id) > 0) paths[id] = robot.path.Json();
  }
  return json{{"type", "full"},
              {"seq", seq_},
              {"tiles", tiles_.All()},
              {"own_tiles", own_tiles_.All()},
              {"robots", robots_.All()},
              {"paths", std::move(paths)},
              {"submaps", submaps_.All()},
              {"objects", objects_.All()},
              {"templates", templates_.All()},
              {"route_graphs", route_graphs_.All()},
              {"status", StatusJson()}}
      .dump();
}

std::optional<std::string> FleetViewModel::TakeDelta() {
  json delta = {{"type", "delta"}};
  bool changed = false;
  for (auto [name, section] : {std::pair<const char*, JsonDictionary*>{"tiles", &tiles_},
                               {"own_tiles", &own_tiles_},
                               {"robots", &robots_},
                               {"submaps", &submaps_},
                               {"objects", &objects_},
                               {"templates", &templates_},
                               {"route_graphs", &route_graphs_}}) {
    json changes = section->TakeChanges();
    if (changes.empty()) continue;
    delta[name] = std::move(changes);
    changed = true;
  }
  json gained = json::object();
  for (auto& [id, robot] : robot_state_) {
    if (std::optional<json> runs = robot.path.TakeGained()) gained[id] = *std::move(runs);
  }
  if (!gained.empty()) {
    delta["path_points"] = std::move(gained);
    changed = true;
  }
  json status = StatusJson();
  if (status != sent_status_) {
    sent_status_ = status;
    delta["status"] = std::move(status);
    changed = true;
  }
  if (!changed) return std::nullopt;
  delta["seq"] = ++seq_;
  return delta.dump();
}

}  // namespace fleetmap::view
