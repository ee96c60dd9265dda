#include "view/web_server.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <sys/socket.h>

#include "view/gzip_stream.hpp"
#include "view/request_path.hpp"

namespace fleetmap::view {
namespace {

// One server-sent event: the JSON has no newlines (compact dump), so one data line holds it.
std::string SseFrame(const std::string& json) {
  std::string frame;
  frame.reserve(json.size() + 8);
  frame.append("data: ").append(json).append("\n\n");
  return frame;
}

constexpr char kKeepAliveFrame[] = ": keep-alive\n\n";

}  // namespace

WebServer::WebServer(const WebServerOptions& options, EventBroadcaster& broadcaster)
    : options_(options), broadcaster_(broadcaster), server_(std::make_unique<httplib::Server>()) {}

StatusOr<std::unique_ptr<WebServer>> WebServer::Start(const WebServerOptions& options,
                                                      EventBroadcaster& broadcaster) {
  std::unique_ptr<WebServer> web(new WebServer(options, broadcaster));
  httplib::Server& server = *web->server_;
  // Every event stream holds a thread for as long as its browser stays; static files and the
  // map image need threads beside them.
  const size_t threads = 2 * options.max_clients + 8;
  server.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server.set_write_timeout(options.write_timeout);
  server.set_read_timeout(std::chrono::seconds(5));
  server.set_keep_alive_timeout(2);
  server.set_payload_max_length(0);  // GET only: no request may carry a body
  server.set_socket_options([](int socket) {
    // Not the library's default SO_REUSEPORT: a second view on a taken port must fail, not
    // share it. A fixed send buffer (accepted sockets inherit it) bounds what the kernel holds
    // for a browser that stopped reading, so its stall shows within that much.
    const int yes = 1;
    const int send_buffer = 64 * 1024;
    ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    ::setsockopt(socket, SOL_SOCKET, SO_SNDBUF, &send_buffer, sizeof(send_buffer));
  });
  if (!server.set_mount_point("/", options.static_dir)) {
    return NotFoundError(
        fmt::format("the view's static folder {} is not a folder", options.static_dir));
  }
  web->AddRoutes();
  if (options.port == 0) {
    web->port_ = server.bind_to_any_port(options.bind);
  } else if (server.bind_to_port(options.bind, options.port)) {
    web->port_ = options.port;
  } else {
    web->port_ = -1;
  }
  if (web->port_ <= 0) {
    return UnavailableError(fmt::format(
        "cannot listen on {}:{} (is the port in use, or the address not this machine's?)",
        options.bind, options.port));
  }
  web->listener_ = std::thread([&server] { server.listen_after_bind(); });
  return web;
}

WebServer::~WebServer() {
  broadcaster_.Close();  // event streams end, so the pool's threads can be joined
  server_->stop();
  if (listener_.joinable()) listener_.join();
}

void WebServer::SetMapImage(std::shared_ptr<const std::string> png) {
  std::lock_guard lock(map_mutex_);
  map_png_ = std::move(png);
}

std::shared_ptr<const std::string> WebServer::MapImage() const {
  std::lock_guard lock(map_mutex_);
  return map_png_;
}

void WebServer::AddRoutes() {
  httplib::Server& server = *server_;
  server.Get("/events", [this](const httplib::Request& request, httplib::Response& response) {
    std::shared_ptr<EventBroadcaster::Client> client = broadcaster_.Connect();
    if (client == nullptr) {
      response.status = 503;
      response.set_content(
          fmt::format("this view serves at most {} browsers at once\n", options_.max_clients),
          "text/plain");
      return;
    }
    response.set_header("Cache-Control", "no-store");
    // Compressed for browsers that accept gzip (all do): the JSON shrinks several times.
    std::shared_ptr<GzipStream> gzip;
    if (request.get_header_value("Accept-Encoding").find("gzip") != std::string::npos) {
      gzip = GzipStream::Create();
      if (gzip != nullptr) response.set_header("Content-Encoding", "gzip");
    }
    response.set_chunked_content_provider(
        "text/event-stream",
        [this, client, gzip](size_t /*offset*/, httplib::DataSink& sink) {
          const std::optional<Event> event = broadcaster_.Next(*client, options_.keep_alive);
          if (!event) {
            sink.done();  // the view is stopping
            return true;
          }
          std::string frame = *event == nullptr ? std::string(kKeepAliveFrame) : SseFrame(**event);
          if (gzip != nullptr) frame = gzip->Compress(frame);
          bytes_sent_ += frame.size();
          // A false return (the socket stalled past the write timeout, or the browser left)
          // closes the connection; the releaser below then disconnects the client.
          return sink.write(frame.data(), frame.size());
        },
        [this, client](bool /*success*/) { broadcaster_.Disconnect(client); });
  });
  server.Get("/map.png", [this](const httplib::Request&, httplib::Response& response) {
    const std::shared_ptr<const std::string> png = MapImage();
    if (png == nullptr) {
      response.status = 404;
      response.set_content("no fused map has arrived yet\n", "text/plain");
      return;
    }
    response.set_header("Cache-Control", "no-store");
    response.set_content(*png, "image/png");
  });
  // A path that could leave the static folder is answered like any other missing file (the
  // library would refuse most of them too, with a 400).
  server.set_pre_routing_handler([](const httplib::Request& request, httplib::Response& response) {
    if (RoutePath(request.path) != PathRoute::kNotFound) {
      return httplib::Server::HandlerResponse::Unhandled;
    }
    response.status = 404;
    return httplib::Server::HandlerResponse::Handled;
  });
  server.set_error_handler([](const httplib::Request& request, httplib::Response& response) {
    if (response.status == 404 && response.body.empty()) {
      response.set_content(fmt::format("not found: {}\n", request.path), "text/plain");
    }
  });
}

}  // namespace fleetmap::view
