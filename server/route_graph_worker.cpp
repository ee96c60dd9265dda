#include "server/route_graph_worker.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace fleetmap::server {
namespace {

// The fused map's tiles are 10 m: the update is handed the grid's cells in rectangles of that
// size, and looks for what changed in each.
constexpr double kTileSize = 10.0;

bool SameGeometry(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b) {
  return a.width() == b.width() && a.height() == b.height() &&
         grid::SameResolution(a.resolution(), b.resolution()) && a.origin() == b.origin();
}

bool SameGraph(const route_graph::RouteGraph& a, const route_graph::RouteGraph& b) {
  if (a.nodes.size() != b.nodes.size() || a.edges.size() != b.edges.size() ||
      a.message != b.message) {
    return false;
  }
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    if (a.nodes[i].id != b.nodes[i].id || a.nodes[i].position != b.nodes[i].position ||
        a.nodes[i].kind != b.nodes[i].kind || a.nodes[i].predicted != b.nodes[i].predicted) {
      return false;
    }
  }
  for (size_t i = 0; i < a.edges.size(); ++i) {
    if (a.edges[i].id != b.edges[i].id || a.edges[i].start != b.edges[i].start ||
        a.edges[i].end != b.edges[i].end || a.edges[i].predicted != b.edges[i].predicted ||
        a.edges[i].blocking_object != b.edges[i].blocking_object) {
      return false;
    }
  }
  return true;
}

std::vector<grid::CellRect> TileRects(const grid::OccupancyGrid& grid) {
  const int cells = std::max(1, static_cast<int>(std::lround(kTileSize / grid.resolution())));
  std::vector<grid::CellRect> rects;
  for (int y = 0; y < grid.height(); y += cells) {
    for (int x = 0; x < grid.width(); x += cells) {
      rects.push_back(
          {x, y, std::min(cells, grid.width() - x), std::min(cells, grid.height() - y)});
    }
  }
  return rects;
}

}  // namespace

Status RouteGraphServiceOptions::Validate() const {
  return graph.Validate().WithContext("route graph");
}

void RouteGraphServiceOptions::Describe(OptionsPrinter& out) const {
  out.Add("enabled", enabled);
  out.Nested("graph", graph);
}

StatusOr<std::unique_ptr<RouteGraphWorker>> RouteGraphWorker::Create(
    transport::Participant& participant, const RouteGraphServiceOptions& options,
    PublishedIds ids) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  std::unique_ptr<RouteGraphWorker> worker(new RouteGraphWorker(options));
  worker->ids_ = std::move(ids);
  FLEETMAP_ASSIGN_OR_RETURN(worker->writer_, transport::RouteGraphWriter::Create(participant));
  return worker;
}

RouteGraphWorker::~RouteGraphWorker() {
  Stop();
  writer_.reset();
}

void RouteGraphWorker::Start() {
  thread_.Start([this] {
    HandleMap();
    return false;
  });
}

void RouteGraphWorker::Stop() { thread_.Stop(); }

void RouteGraphWorker::SubmitMap(grid::OccupancyGrid map) {
  {
    std::lock_guard lock(mutex_);
    if (pending_) ++stats_.grids_replaced;
    pending_ = std::move(map);
  }
  thread_.Wake();
}

void RouteGraphWorker::SubmitSubmap(const scene::SubmapNode& node, const scene::DoorEntity* door,
                                    bool withdrawn) {
  {
    std::lock_guard lock(mutex_);
    if (withdrawn) {
      submaps_.erase(node.submap.id);
    } else {
      submaps_[node.submap.id] = {node, door != nullptr ? std::optional(*door) : std::nullopt};
    }
    context_changed_ = true;
  }
  thread_.Wake();
}

void RouteGraphWorker::SubmitObjects(const std::vector<transport::ObjectModelMessage>& objects) {
  std::vector<route_graph::MovableObject> movable;
  for (const transport::ObjectModelMessage& object : objects) {
    route_graph::MovableObject entry{object.object_id, object.patch, {}};
    for (const transport::ObjectSighting& sighting : object.sightings) {
      entry.sightings.push_back(sighting.fleet_from_object);
    }
    movable.push_back(std::move(entry));
  }
  {
    std::lock_guard lock(mutex_);
    objects_ = std::move(movable);
    context_changed_ = true;
  }
  thread_.Wake();
}

void RouteGraphWorker::MakeContext(const grid::OccupancyGrid& grid, scene::SubmapGraph* rooms,
                                   route_graph::RouteOverlay* overlay) {
  std::vector<route_graph::PredictedSpace> predicted;
  std::vector<route_graph::MovableObject> objects;
  {
    std::lock_guard lock(mutex_);
    for (const auto& [id, entry] : submaps_) {
      const auto& [node, door] = entry;
      if (node.submap.kind == scene::SubmapKind::kObserved) {
        rooms->submaps.push_back(node.submap);
        continue;
      }
      // Predictions behind doors still unobserved; not those up stairs (another floor), nor
      // confirmed ones (observed: the grid has them).
      if (node.submap.kind != scene::SubmapKind::kPredictedDoor ||
          node.state != scene::SubmapState::kPredicted) {
        continue;
      }
      route_graph::PredictedSpace space{node.submap, std::nullopt};
      if (door) space.door = std::array<Point2, 2>{door->hinge, door->latch};
      predicted.push_back(std::move(space));
    }
    objects = objects_;
    context_changed_ = false;
  }
  *overlay =
      route_graph::RouteOverlay::Make(grid, predicted, objects, builder_.options().thresholds);
}

RouteGraphStats RouteGraphWorker::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void RouteGraphWorker::HandleMap() {
  std::optional<grid::OccupancyGrid> map;
  {
    std::lock_guard lock(mutex_);
    map.swap(pending_);
    // Only the sub-maps or objects changed: the same grid again, in their new context.
    if (!map && context_changed_ && last_) map = *last_;
  }
  if (!map || map->empty()) return;
  scene::SubmapGraph rooms;
  route_graph::RouteOverlay overlay;
  MakeContext(*map, &rooms, &overlay);
  const route_graph::MapContext context{&rooms, &overlay};
  const bool update = last_ && SameGeometry(*last_, *map);
  StatusOr<route_graph::RouteGraph> graph =
      update ? builder_.Update(*map, TileRects(*map), context) : builder_.Build(*map, context);
  if (!graph.ok()) {
    spdlog::warn("server: route graph: {}", graph.status().message());
    return;
  }
  last_ = std::move(map);
  {
    std::lock_guard lock(mutex_);
    ++(update ? stats_.updates : stats_.builds);
    stats_.rooms = rooms.submaps.size();
    stats_.predicted_cells = overlay.predicted_cells();
    stats_.object_cells = overlay.object_cells();
  }
  if (sent_ && SameGraph(*sent_, *graph)) return;
  transport::RouteGraphMessage message;
  message.graph_id = ids_.graph_id;
  message.revision = revision_ + 1;
  message.graph = *graph;
  message.stamp = Clock::now();
  if (StatusOr<size_t> written = writer_->Write(message); !written.ok()) {
    spdlog::warn("server: route graph: {}", written.status().message());
    return;
  }
  revision_ = message.revision;
  sent_ = std::move(graph).value();
  std::lock_guard lock(mutex_);
  stats_.revision = revision_;
  stats_.nodes = sent_->nodes.size();
  stats_.edges = sent_->edges.size();
  stats_.predicted_edges = static_cast<size_t>(
      std::count_if(sent_->edges.begin(), sent_->edges.end(),
                    [](const route_graph::RouteEdge& edge) { return edge.predicted; }));
  stats_.blocked_edges = static_cast<size_t>(
      std::count_if(sent_->edges.begin(), sent_->edges.end(),
                    [](const route_graph::RouteEdge& edge) { return edge.blocking_object; }));
}

}  // namespace fleetmap::server
