#pragma once

// What the view's web server answers for a request path: the decision behind its routes, kept out
// of the cpp-httplib handlers so that unit tests and the fuzz target (fuzz/) can ask it directly.
//
// Thread-safety: stateless.

#include <cstdint>
#include <string_view>

namespace fleetmap::view {

enum class PathRoute : uint8_t {
  kEvents,      // /events: the event stream
  kMapImage,    // /map.png: the newest fused grid
  kStaticFile,  // a file of the static folder, if there is one by that name (else 404)
  kNotFound,    // a path that could name something outside the static folder: 404, like a
                // missing file
};

// `path` as the HTTP library hands it over: percent-escapes decoded, the query string removed.
// A static file's path starts with '/' and holds no "..", no backslash and no control character
// (a decoded %00 would cut the file name short where the library opens it).
PathRoute RoutePath(std::string_view path);

}  // namespace fleetmap::view
