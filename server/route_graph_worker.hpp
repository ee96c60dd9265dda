#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/core/worker_thread.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/route_graph/route_graph_builder.hpp"
#include "common/route_graph/route_overlay.hpp"
#include "common/scene/entities.hpp"
#include "common/scene/submap_node.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/participant.hpp"
#include "server/published_ids.hpp"

namespace fleetmap::server {

// Whether and how the server publishes the fused map as a route graph (docs/route-graph.md).
struct RouteGraphServiceOptions {
  bool enabled = false;
  route_graph::RouteGraphOptions graph;  // robot_radius: the fleet's robots'

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// What the route graph worker has done. A snapshot; thread-safe to take.
struct RouteGraphStats {
  uint64_t revision = 0;  // of the graph last published (0: none yet)
  uint64_t builds = 0;    // whole builds (the first grid, or the fused map's extent changed)
  uint64_t updates = 0;   // windowed updates (the same extent, some cells changed)
  size_t nodes = 0;
  size_t edges = 0;
  uint64_t grids_replaced = 0;  // fused grids replaced by a newer one before they were handled
  size_t rooms = 0;             // observed sub-maps given room-centre nodes (when they fit)
  size_t predicted_cells = 0;   // unknown cells opened as predicted free space
  size_t object_cells = 0;      // occupied cells opened as learned movable objects
  size_t predicted_edges = 0;
  size_t blocked_edges = 0;
};

// The route graph of the fused map on its own thread: each fused grid the fusion worker publishes
// is handed here (the newest replaces one not yet handled); the worker updates the graph in the
// windows of the cells that changed (a whole build when the map's extent changed) and, when the
// graph changed, writes it on rt/fleetmap/route_graph with the next revision. The sub-map graph
// (observed rooms get a centre node; predicted free space is opened, its edges marked predicted)
// and the learned objects (their cells opened, the edges through them marked blocked) come from
// the prediction and object-learning workers; a change to either updates the graph on the last
// grid.
//
// SubmitMap(), SubmitSubmap(), SubmitObjects() and stats() may be called from any thread; Start()
// and Stop() from the owner's.
class RouteGraphWorker {
 public:
  static StatusOr<std::unique_ptr<RouteGraphWorker>> Create(transport::Participant& participant,
                                                            const RouteGraphServiceOptions& options,
                                                            PublishedIds ids = {});
  ~RouteGraphWorker();

  void Start();
  void Stop();

  // The newest fused grid (fleet frame).
  void SubmitMap(grid::OccupancyGrid map);
  // A sub-map of the sub-map graph written or withdrawn (fleet frame); `door`, when the sub-map
  // is predicted behind one (else null).
  void SubmitSubmap(const scene::SubmapNode& node, const scene::DoorEntity* door, bool withdrawn);
  // The learned objects of the newest learning run (all of them: they replace the last run's).
  void SubmitObjects(const std::vector<transport::ObjectModelMessage>& objects);
  RouteGraphStats stats() const;

 private:
  explicit RouteGraphWorker(const RouteGraphServiceOptions& options) : builder_(options.graph) {}

  // One round: the pending grid (or the last one, when only the sub-maps or objects changed)
  // into the graph; the graph on the wire if it changed.
  void HandleMap();
  // The rooms and the overlay of `grid` from the sub-maps and objects known now.
  void MakeContext(const grid::OccupancyGrid& grid, scene::SubmapGraph* rooms,
                   route_graph::RouteOverlay* overlay);

  route_graph::RouteGraphBuilder builder_;       // worker thread only
  std::optional<grid::OccupancyGrid> last_;      // worker thread only: the grid built from
  std::optional<route_graph::RouteGraph> sent_;  // worker thread only
  uint64_t revision_ = 0;                        // worker thread only
  std::unique_ptr<transport::RouteGraphWriter> writer_;
  PublishedIds ids_;  // the graph's name

  mutable std::mutex mutex_;
  std::optional<grid::OccupancyGrid> pending_;  // guarded by mutex_
  // The sub-maps by id, each with the door it was predicted behind.
  std::map<uint32_t, std::pair<scene::SubmapNode, std::optional<scene::DoorEntity>>>
      submaps_;                                      // guarded by mutex_
  std::vector<route_graph::MovableObject> objects_;  // guarded by mutex_
  bool context_changed_ = false;                     // guarded by mutex_
  RouteGraphStats stats_;                            // guarded by mutex_
  // Wakes on every grid, and at least every second. Last member: its thread stops first.
  WorkerThread thread_{std::chrono::milliseconds(1000)};
};

}  // namespace fleetmap::server
