#pragma once

// `fleetmap view`'s engine: a DDS subscriber of the fleet (like RViz: it runs anywhere on the
// fleet's domain, the server stays headless) that keeps the page's state and pushes it to
// browsers through the web server. One worker thread drains the readers, updates the model and
// publishes a delta every `publish_period`; the web server's threads only send.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "common/core/status.hpp"
#include "common/transport/participant.hpp"
#include "view/event_broadcaster.hpp"
#include "view/web_server.hpp"

namespace fleetmap::view {

struct FleetViewOptions {
  transport::ParticipantOptions dds;
  std::string bind = "127.0.0.1";
  int port = 8080;          // 0: any free port
  std::string static_dir;   // the page's files (FindStaticFolder)
  size_t max_clients = 32;  // browsers at once
  size_t max_queued_events = 64;
  std::chrono::milliseconds publish_period{200};
};

// What the view has sent, against what the same updates would have cost as whole pictures of the
// fused grid (GET /map.png at every rt/fleetmap/map update, or rosbridge's PNG-compressed
// OccupancyGrid): the figures `fleetmap view` prints when it stops (docs/results.md).
struct ViewTraffic {
  uint64_t deltas = 0;
  uint64_t delta_bytes = 0;        // one browser's stream, keep-alives aside
  uint64_t last_full_bytes = 0;    // the whole state, as a browser connecting now would get it
  uint64_t grids = 0;              // rt/fleetmap/map updates received
  uint64_t grid_png_bytes = 0;     // their PNGs, summed
  uint64_t bytes_to_browsers = 0;  // written to every browser's stream, compressed, summed
  double seconds = 0.0;
};

class FleetView {
 public:
  // Joins the fleet and starts serving. Errors name what failed: DDS, the address, the folder.
  static StatusOr<std::unique_ptr<FleetView>> Start(FleetViewOptions options);
  // Stops the web server, then leaves DDS.
  ~FleetView();
  FleetView(const FleetView&) = delete;
  FleetView& operator=(const FleetView&) = delete;

  // http://<bind>:<port>/
  std::string url() const;
  int port() const;
  int domain_id() const;
  BroadcastCounters counters() const { return broadcaster_->counters(); }
  ViewTraffic traffic() const;

 private:
  class Readers;
  FleetView() = default;
  void Work();

  FleetViewOptions options_;
  std::unique_ptr<EventBroadcaster> broadcaster_;
  std::unique_ptr<Readers> readers_;
  std::unique_ptr<WebServer> web_;
  std::atomic<bool> stop_{false};
  mutable std::mutex traffic_mutex_;
  ViewTraffic traffic_;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
  std::thread worker_;
};

}  // namespace fleetmap::view
