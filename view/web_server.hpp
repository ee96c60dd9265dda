#pragma once

// The view's HTTP side (cpp-httplib): the page's static files, the event stream and the fused grid
// as a PNG. Read-only by construction: it answers GET only and nothing it serves reaches DDS.
//   GET /            index.html, and any file of the static folder (nothing outside it: the
//                    library refuses paths with ".." and the like)
//   GET /events      text/event-stream: the whole state, then deltas (docs/view.md)
//   GET /map.png     the newest fused grid, 404 before the first
//   anything else    404
// Each browser's event stream runs on its own thread of a bounded pool; the broadcaster bounds the
// clients, and a socket that accepts nothing for `write_timeout` is closed.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "common/core/status.hpp"
#include "view/event_broadcaster.hpp"

namespace httplib {
class Server;
}

namespace fleetmap::view {

struct WebServerOptions {
  std::string bind = "127.0.0.1";
  int port = 8080;  // 0: any free port (port() tells which)
  std::string static_dir;
  size_t max_clients = 32;  // event streams; static files have threads of their own
  std::chrono::seconds write_timeout{5};
  // A comment line on a quiet stream: a browser that closed its connection is noticed at the
  // second write after it left, so within two of these, and its place freed.
  std::chrono::seconds keep_alive{2};
};

class WebServer {
 public:
  // Binds and starts serving on a thread of its own; fails (kUnavailable) naming the address when
  // it cannot bind.
  static StatusOr<std::unique_ptr<WebServer>> Start(const WebServerOptions& options,
                                                    EventBroadcaster& broadcaster);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  int port() const { return port_; }
  // Bytes written to browsers' event streams (after compression), since start.
  uint64_t bytes_sent() const { return bytes_sent_; }
  // The PNG GET /map.png answers with from now on.
  void SetMapImage(std::shared_ptr<const std::string> png);

 private:
  WebServer(const WebServerOptions& options, EventBroadcaster& broadcaster);
  void AddRoutes();
  std::shared_ptr<const std::string> MapImage() const;

  WebServerOptions options_;
  EventBroadcaster& broadcaster_;
  std::unique_ptr<httplib::Server> server_;
  std::thread listener_;
  int port_ = 0;
  std::atomic<uint64_t> bytes_sent_{0};
  mutable std::mutex map_mutex_;
  std::shared_ptr<const std::string> map_png_;
};

}  // namespace fleetmap::view
