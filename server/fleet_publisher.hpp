#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/core/robot_frame.hpp"
#include "common/core/status.hpp"
#include "common/fusion/fleet_map.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/occupancy_grid_writer.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/tf_topic.hpp"
#include "common/transport/topics.hpp"
#include "common/transport/vector_tile_writer.hpp"

namespace fleetmap::server {

// Writes the fleet map out: fused tiles on rt/fleetmap/fused_tiles, the frames table on
// rt/fleetmap/robot_frames, the fused grid on rt/fleetmap/map (at most every map period, when it
// changed) and the placed frames on rt/tf. The map and rt/tf are shared topics every reader
// would take from both servers of a hot pair: they go out only while this server serves
// (docs/standby.md). Not thread-safe: the fusion worker's.
class FleetPublisher {
 public:
  struct Options {
    double tile_size = 10.0;
    int64_t max_grid_cells = 0;  // for the warning when the map leaves tiles out
    std::chrono::milliseconds map_period{1000};
    std::chrono::milliseconds tf_period{500};
    // rt/fleetmap/map; a shard's server writes its region's grid on rt/fleetmap/<shard>/map.
    std::string map_topic = transport::kFleetMapTopic;
  };
  // Called with every fused grid published on rt/fleetmap/map.
  using MapListener = std::function<void(const grid::OccupancyGrid& fused)>;

  static StatusOr<std::unique_ptr<FleetPublisher>> Create(transport::Participant& participant,
                                                          const Options& options);
  ~FleetPublisher();
  void SetMapListener(MapListener listener) { on_map_ = std::move(listener); }

  // Writes the fused tiles; returns them as written (what the store keeps).
  std::vector<transport::VectorTileMessage> PublishTiles(std::vector<fusion::FusedTile> fused);
  void PublishFrames(const std::vector<RobotFrame>& frames);
  // Writes what a round made due: the fused grid (changed since the last one, and the period
  // passed; at once when this server just started serving) and rt/tf.
  void PublishDue(const fusion::FleetMap& map, bool serving,
                  std::chrono::steady_clock::time_point now);

  uint64_t tiles_published() const { return tiles_published_; }
  uint64_t tile_bytes_published() const { return tile_bytes_published_; }
  uint64_t maps_published() const { return maps_published_; }

 private:
  explicit FleetPublisher(const Options& options) : options_(options) {}
  void PublishMap(const fusion::FleetMap& map, std::chrono::steady_clock::time_point now);
  void PublishTf(const std::map<RobotId, RobotFrame>& frames,
                 std::chrono::steady_clock::time_point now);

  Options options_;
  std::unique_ptr<transport::VectorTileWriter> fused_writer_;
  std::unique_ptr<transport::OccupancyGridWriter> map_writer_;
  std::unique_ptr<transport::RobotFrameWriter> frame_writer_;
  std::unique_ptr<transport::TfWriter> tf_writer_;
  MapListener on_map_;
  bool map_dirty_ = false;
  bool was_serving_ = false;
  std::chrono::steady_clock::time_point last_map_{};
  std::chrono::steady_clock::time_point last_tf_{};
  size_t tiles_outside_map_ = 0;
  std::chrono::steady_clock::time_point last_window_warning_{};
  static constexpr std::chrono::seconds kWindowWarningPeriod{30};
  uint64_t tiles_published_ = 0;
  uint64_t tile_bytes_published_ = 0;
  uint64_t maps_published_ = 0;
};

}  // namespace fleetmap::server
