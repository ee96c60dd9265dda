// Fuzz target: what a browser (or anything that reaches the view's port) sends: request lines and
// headers, one request after another on one connection, parsed by Debian's cpp-httplib (header
// only, so compiled here with the sanitizers) and routed as the view routes them (RoutePath, the
// static folder as the mount point, GET only, no body).
//
// Besides crashes, two properties: a path RoutePath gives to the static folder stays inside it,
// lexically; and no response ever carries the file that sits beside the static folder.

#include <httplib.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "common/core/check.hpp"
#include "fuzz/fuzz_support.hpp"
#include "view/request_path.hpp"

namespace {

using fleetmap::view::PathRoute;

constexpr char kSecret[] = "fleetmap-fuzz: outside the static folder";

// One connection's bytes: reads come from the input, writes are kept.
class BytesStream : public httplib::Stream {
 public:
  explicit BytesStream(std::string_view input) : input_(input) {}

  bool is_readable() const override { return true; }
  bool is_writable() const override { return true; }
  ssize_t read(char* ptr, size_t size) override {
    const size_t count = std::min(size, input_.size());
    std::copy_n(input_.data(), count, ptr);
    input_.remove_prefix(count);
    return static_cast<ssize_t>(count);
  }
  ssize_t write(const char* ptr, size_t size) override {
    output_.append(ptr, size);
    return static_cast<ssize_t>(size);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 40000;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 8080;
  }
  socket_t socket() const override { return 0; }

  bool done() const { return input_.empty(); }
  const std::string& output() const { return output_; }

 private:
  std::string_view input_;
  std::string output_;
};

// The view's routes (view/web_server.cpp) over a folder of its own; the event stream and the map
// image answer with fixed text, since what they serve does not depend on the request.
class ViewLikeServer : public httplib::Server {
 public:
  explicit ViewLikeServer(const std::filesystem::path& static_dir) : static_dir_(static_dir) {
    set_payload_max_length(0);
    FLEETMAP_CHECK(set_mount_point("/", static_dir.string()));
    Get("/events", [](const httplib::Request&, httplib::Response& response) {
      response.set_content("data: {}\n\n", "text/event-stream");
    });
    Get("/map.png", [](const httplib::Request&, httplib::Response& response) {
      response.set_content("png", "image/png");
    });
    set_pre_routing_handler([this](const httplib::Request& request, httplib::Response& response) {
      const PathRoute route = fleetmap::view::RoutePath(request.path);
      if (route == PathRoute::kStaticFile) CheckInside(request.path);
      if (route != PathRoute::kNotFound) return HandlerResponse::Unhandled;
      response.status = 404;
      return HandlerResponse::Handled;
    });
  }

  // One request of the connection; false when the connection ends.
  bool ServeOne(httplib::Stream& stream) {
    bool closed = false;
    const bool ok = process_request(stream, false, closed, nullptr);
    return ok && !closed;
  }

 private:
  void CheckInside(const std::string& path) const {
    const std::filesystem::path target = (static_dir_ / ("." + path)).lexically_normal();
    const std::filesystem::path relative = target.lexically_relative(static_dir_);
    FLEETMAP_CHECK(!relative.empty() && *relative.begin() != "..",
                   "a static path leaves the folder");
  }

  std::filesystem::path static_dir_;
};

ViewLikeServer& Server() {
  static ViewLikeServer* server = [] {
    const std::filesystem::path root = fleetmap::fuzz::ScratchFolder() / "http";
    const std::filesystem::path page = root / "view";
    std::filesystem::create_directories(page / "leaflet");
    fleetmap::fuzz::WriteScratchFile(page / "index.html", "<html>fleetmap</html>\n");
    fleetmap::fuzz::WriteScratchFile(page / "view.js", "// view\n");
    fleetmap::fuzz::WriteScratchFile(page / "leaflet" / "leaflet.js", "// leaflet\n");
    fleetmap::fuzz::WriteScratchFile(root / "secret.txt", kSecret);
    return new ViewLikeServer(page);
  }();
  return *server;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  BytesStream stream(fleetmap::fuzz::AsText(data, size));
  for (int request = 0; request < 8 && !stream.done(); ++request) {
    if (!Server().ServeOne(stream)) break;
  }
  FLEETMAP_CHECK(stream.output().find(kSecret) == std::string::npos,
                 "a response carries a file outside the static folder");
  return 0;
}
