#include "view/fleet_view.hpp"

#include <fmt/format.h>

#include <utility>

#include "common/core/wake_up.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/robot_status_reader.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "common/vector_map/png.hpp"
#include "view/fleet_view_model.hpp"

namespace fleetmap::view {

// Everything the view reads, on one participant; the worker drains them all.
class FleetView::Readers {
 public:
  static StatusOr<std::unique_ptr<Readers>> Create(const transport::ParticipantOptions& options) {
    std::unique_ptr<Readers> readers(new Readers());
    FLEETMAP_ASSIGN_OR_RETURN(readers->participant, transport::Participant::Create(options));
    transport::Participant& participant = *readers->participant;
    const std::shared_ptr<WakeUp>& wake_up = readers->wake_up;
    FLEETMAP_ASSIGN_OR_RETURN(readers->statuses,
                              transport::RobotStatusReader::Create(participant, wake_up));
    FLEETMAP_ASSIGN_OR_RETURN(
        readers->fused_tiles,
        transport::VectorTileReader::Create(participant, transport::kFusedTilesTopic, wake_up));
    FLEETMAP_ASSIGN_OR_RETURN(
        readers->robot_tiles,
        transport::VectorTileReader::Create(participant, transport::kRobotTilesTopic, wake_up));
    FLEETMAP_ASSIGN_OR_RETURN(
        readers->fused_grid,
        transport::OccupancyGridReader::Create(participant, transport::kFleetMapTopic, wake_up));
    FLEETMAP_ASSIGN_OR_RETURN(readers->frames,
                              transport::RobotFrameReader::Create(participant, wake_up));
    FLEETMAP_ASSIGN_OR_RETURN(readers->submaps,
                              transport::SubmapReader::Create(participant, wake_up));
    FLEETMAP_ASSIGN_OR_RETURN(readers->objects,
                              transport::ObjectModelReader::Create(participant, wake_up));
    FLEETMAP_ASSIGN_OR_RETURN(readers->templates,
                              transport::ObjectTemplateReader::Create(participant, wake_up));
    FLEETMAP_ASSIGN_OR_RETURN(readers->route_graphs,
                              transport::RouteGraphReader::Create(participant, wake_up));
    FLEETMAP_ASSIGN_OR_RETURN(readers->servers,
                              transport::FleetServerReader::Create(participant, wake_up));
    return readers;
  }

  // Readers go before their participant.
  ~Readers() {
    statuses.reset();
    fused_tiles.reset();
    robot_tiles.reset();
    fused_grid.reset();
    frames.reset();
    submaps.reset();
    objects.reset();
    templates.reset();
    route_graphs.reset();
    servers.reset();
    participant.reset();
  }

  // Hands everything received to the model; returns the newest fused grid, if one came.
  std::optional<transport::MapMessage> DrainInto(FleetViewModel& model) {
    const Timestamp now = Clock::now();
    for (const transport::RobotEvent& event : statuses->Drain()) model.OnRobotEvent(event, now);
    for (const transport::RobotFrameEvent& event : frames->Drain()) model.OnRobotFrame(event);
    for (const transport::TileEvent& event : fused_tiles->Drain()) model.OnFusedTile(event);
    for (const transport::TileEvent& event : robot_tiles->Drain()) model.OnRobotTile(event);
    for (const transport::SubmapEvent& event : submaps->Drain()) model.OnSubmap(event);
    for (const transport::ObjectModelEvent& event : objects->Drain()) model.OnObject(event);
    for (const transport::ObjectTemplateEvent& event : templates->Drain()) model.OnTemplate(event);
    for (const transport::RouteGraphEvent& event : route_graphs->Drain()) {
      model.OnRouteGraph(event);
    }
    for (const transport::FleetServerEvent& event : servers->Drain()) model.OnServer(event, now);
    std::optional<transport::MapMessage> newest;
    for (StatusOr<transport::MapMessage>& map : fused_grid->Drain()) {
      if (!map.ok()) {
        model.CountRejected(transport::kFleetMapTopic);
        continue;
      }
      model.OnFleetMap(*map);
      newest = std::move(map).value();
    }
    return newest;
  }

  std::unique_ptr<transport::Participant> participant;
  std::shared_ptr<WakeUp> wake_up = std::make_shared<WakeUp>();
  std::unique_ptr<transport::RobotStatusReader> statuses;
  std::unique_ptr<transport::VectorTileReader> fused_tiles;
  std::unique_ptr<transport::VectorTileReader> robot_tiles;
  std::unique_ptr<transport::OccupancyGridReader> fused_grid;
  std::unique_ptr<transport::RobotFrameReader> frames;
  std::unique_ptr<transport::SubmapReader> submaps;
  std::unique_ptr<transport::ObjectModelReader> objects;
  std::unique_ptr<transport::ObjectTemplateReader> templates;
  std::unique_ptr<transport::RouteGraphReader> route_graphs;
  std::unique_ptr<transport::FleetServerReader> servers;

 private:
  Readers() = default;
};

StatusOr<std::unique_ptr<FleetView>> FleetView::Start(FleetViewOptions options) {
  std::unique_ptr<FleetView> view(new FleetView());
  view->options_ = std::move(options);
  const FleetViewOptions& o = view->options_;
  view->broadcaster_ = std::make_unique<EventBroadcaster>(
      BroadcastLimits{.max_clients = o.max_clients, .max_queued_events = o.max_queued_events});
  FLEETMAP_ASSIGN_OR_RETURN(view->readers_, Readers::Create(o.dds));
  WebServerOptions web;
  web.bind = o.bind;
  web.port = o.port;
  web.static_dir = o.static_dir;
  web.max_clients = o.max_clients;
  FLEETMAP_ASSIGN_OR_RETURN(view->web_, WebServer::Start(web, *view->broadcaster_));
  view->worker_ = std::thread([raw = view.get()] { raw->Work(); });
  return view;
}

FleetView::~FleetView() {
  stop_ = true;
  if (readers_ != nullptr) readers_->wake_up->Notify();
  if (worker_.joinable()) worker_.join();
  web_.reset();
  readers_.reset();
}

std::string FleetView::url() const { return fmt::format("http://{}:{}/", options_.bind, port()); }
int FleetView::port() const { return web_->port(); }
ViewTraffic FleetView::traffic() const {
  std::lock_guard lock(traffic_mutex_);
  ViewTraffic traffic = traffic_;
  traffic.bytes_to_browsers = web_->bytes_sent();
  traffic.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  return traffic;
}

int FleetView::domain_id() const { return readers_->participant->domain_id(); }

void FleetView::Work() {
  FleetViewModel model;
  auto next_publish = std::chrono::steady_clock::now();
  while (!stop_) {
    readers_->wake_up->WaitFor(options_.publish_period);
    if (std::optional<transport::MapMessage> map = readers_->DrainInto(model)) {
      // A grid that cannot be encoded (empty) leaves the previous picture up.
      if (auto png = vector_map::EncodeGridPng(map->grid); png.ok()) {
        web_->SetMapImage(std::make_shared<const std::string>(png->begin(), png->end()));
        std::lock_guard lock(traffic_mutex_);
        ++traffic_.grids;
        traffic_.grid_png_bytes += png->size();
      }
    }
    // Samples are drained as they come; deltas go out at most once a period, so a burst of
    // tiles makes one event rather than hundreds.
    const auto now = std::chrono::steady_clock::now();
    if (now < next_publish) continue;
    next_publish = now + options_.publish_period;
    model.Tick(Clock::now());
    std::optional<std::string> delta = model.TakeDelta();
    const Event delta_event =
        delta ? std::make_shared<const std::string>(std::move(*delta)) : nullptr;
    const Event full_event = broadcaster_->WantsFullState()
                                 ? std::make_shared<const std::string>(model.FullEvent())
                                 : nullptr;
    if (delta_event != nullptr || full_event != nullptr) {
      broadcaster_->Publish(delta_event, full_event);
    }
    std::lock_guard lock(traffic_mutex_);
    if (delta_event != nullptr) {
      ++traffic_.deltas;
      traffic_.delta_bytes += delta_event->size();
    }
    if (full_event != nullptr) traffic_.last_full_bytes = full_event->size();
  }
}

}  // namespace fleetmap::view
