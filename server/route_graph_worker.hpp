#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>

#include "common/core/options_printer.hpp"
#include "common/core/status.hpp"
#include "common/core/worker_thread.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/route_graph/route_graph_builder.hpp"
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
};

// The route graph of the fused map on its own thread: each fused grid the fusion worker publishes
// is handed here (the newest replaces one not yet handled); the worker updates the graph in the
// windows of the cells that changed (a whole build when the map's extent changed) and, when the
// graph changed, writes it on rt/fleetmap/route_graph with the next revision.
//
// SubmitMap() and stats() may be called from any thread; Start() and Stop() from the owner's.
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
  RouteGraphStats stats() const;

 private:
  explicit RouteGraphWorker(const RouteGraphServiceOptions& options) : builder_(options.graph) {}

  // One round: the pending grid, if any, into the graph; the graph on the wire if it changed.
  void HandleMap();

  route_graph::RouteGraphBuilder builder_;       // worker thread only
  std::optional<grid::OccupancyGrid> last_;      // worker thread only: the grid built from
  std::optional<route_graph::RouteGraph> sent_;  // worker thread only
  uint64_t revision_ = 0;                        // worker thread only
  std::unique_ptr<transport::RouteGraphWriter> writer_;
  PublishedIds ids_;  // the graph's name

  mutable std::mutex mutex_;
  std::optional<grid::OccupancyGrid> pending_;  // guarded by mutex_
  RouteGraphStats stats_;                       // guarded by mutex_
  // Wakes on every grid, and at least every second. Last member: its thread stops first.
  WorkerThread thread_{std::chrono::milliseconds(1000)};
};

}  // namespace fleetmap::server
