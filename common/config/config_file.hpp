#pragma once

// A program's settings read from a YAML config file (docs/configuration.md). The keys are the
// program's long options without their dashes, so that what a user learns from --help is what
// they write in the file:
//
//   store: /var/lib/fleetmap/fleet.db
//   max-tiles-per-robot: 4000
//   placement:            # a nested map joins its keys: placement-confidence
//     confidence: 0.9
//   fleet-from-map: [2.0, -1.5, 90]   # an option of several values takes a sequence
//
// `_` and `.` in keys mean `-` (tile_size, placement.confidence), as ROS 2 parameter names are
// written. The same settings are also read from a ROS 2 params file, so that they can sit in a
// robot's existing one:
//
//   /**:                       # every node: keys fleetmap does not know are other nodes' business
//     ros__parameters: {use_sim_time: false}
//   fleetmap_server:           # also /fleetmap_server, /ns/fleetmap_server, /**/fleetmap_server
//     ros__parameters:
//       store: /var/lib/fleetmap/fleet.db
//
// Which key is an option of which program is the caller's business (ConfigurableCommand); this
// reader only turns the file into settings, each with the file and line it came from.
//
// Thread-safety: stateless.

#include <string>
#include <vector>

#include "common/core/status.hpp"

namespace fleetmap::config {

struct ConfigSetting {
  std::string key;                  // "placement-confidence": the long option without "--"
  std::vector<std::string> values;  // scalars as written; a sequence gives one per element
  std::string location;             // "FILE:LINE", for messages
  // From a ROS 2 wildcard section (/**): settings meant for every node, so a key that is not an
  // option of this program is skipped instead of refused.
  bool for_every_node = false;
};

// The settings of `path` for the program whose ROS 2 node name is `ros_node` ("fleetmap_server").
// A key set to null (`key: ~`) is left out: the option keeps its default. An empty file is no
// settings. A ROS 2 params file without a section for `ros_node` (nor /**) gives none either, as
// ROS 2 gives such a node no parameters; `note`, if given, then says so and lists the nodes the
// file has, for the program to warn. Errors (kInvalidArgument) name the file and, where there is
// one, the line: the file cannot be read, is not YAML, is not a map, a key is set twice, a value
// is a map inside a sequence.
StatusOr<std::vector<ConfigSetting>> ReadConfigFile(const std::string& path,
                                                    const std::string& ros_node,
                                                    std::string* note = nullptr);

}  // namespace fleetmap::config
