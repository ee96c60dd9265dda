#pragma once

// Where the page's files are: the folder the build fills (build/share/fleetmap/view) and `make
// install` installs (<prefix>/share/fleetmap/view), both found from the running program's own
// path, so the build tree and an installed tree work alike.

#include <string>

#include "common/core/status.hpp"

namespace fleetmap::view {

// `requested` if given, else $FLEETMAP_VIEW_DIR if set, else <program dir>/../share/fleetmap/view.
// The folder must hold index.html; the error names every place tried.
StatusOr<std::string> FindStaticFolder(const std::string& requested = "");

}  // namespace fleetmap::view
