#pragma once

// The state a fleetmap-server serves, and how a hot standby takes it over (docs/standby.md).
//
// rt/fleetmap/fused_tiles, robot_frames, submap_graph, object_templates and objects have EXCLUSIVE
// ownership: every server writes them, with the strength it was given (--ownership-strength), and
// a reader takes each instance from the strongest live writer only. When that server dies, its
// writers miss their liveliness lease and the readers take the next server's samples. Samples
// the next server wrote meanwhile were refused by the readers, so a server writes its whole state
// again when it starts serving (Participant::RepublishServedState). rt/fleetmap/map and rt/tf keep
// ROS 2's shared ownership (RViz and Nav2 would not match an exclusive writer): only the serving
// server writes them. Servers tell each other, and the view and agents, on rt/fleetmap/servers.

#include <chrono>

namespace fleetmap::transport {

// The liveliness lease of a server's writers on the exclusive topics, and what their readers
// request: a reader leaves a dead server about this long after it was last heard.
inline constexpr std::chrono::milliseconds kServedLivelinessLease{1000};
// A server writes its rt/fleetmap/servers sample this often; one not heard for
// kServerSilenceLimit is gone.
inline constexpr std::chrono::milliseconds kServerHeartbeatPeriod{500};
inline constexpr std::chrono::milliseconds kServerSilenceLimit{1500};

}  // namespace fleetmap::transport
