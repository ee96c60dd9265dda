#pragma once

// ROS 2's transform tree on rt/tf (/tf, tf2_msgs/TFMessage), planar: what RViz and every tf2
// listener read. The server writes fleet -> <robot>/map for each robot whose map frame it knows;
// a reader is for tools and tests.

#include <memory>
#include <string>
#include <vector>

#include "common/core/status.hpp"
#include "common/core/types.hpp"
#include "common/core/wake_up.hpp"
#include "common/transport/participant.hpp"

namespace fleetmap::transport {

class ReaderEndpoint;
class WriterEndpoint;

// One planar transform: the pose of `child` in `parent` (p_parent = parent_from_child * p_child).
struct FrameTransform {
  Timestamp stamp{};
  std::string parent;
  std::string child;
  Pose2 parent_from_child;
};

// ROS 2's frame name of a robot's map frame: "<robot>/map".
std::string RobotMapFrame(const std::string& robot);

// Writes transforms on rt/tf with ROS 2's /tf QoS (reliable, volatile, keep last 100). Call from
// one thread.
class TfWriter {
 public:
  static StatusOr<std::unique_ptr<TfWriter>> Create(Participant& participant);
  ~TfWriter();

  // One TFMessage with every transform; returns its serialized bytes. Fails (kInvalidArgument)
  // for a non-finite pose or empty frame names.
  StatusOr<size_t> Write(const std::vector<FrameTransform>& transforms);

 private:
  TfWriter() = default;
  std::unique_ptr<WriterEndpoint> endpoint_;
};

// Reads rt/tf. Transforms that are not planar (a rotation not about z, z != 0 within 1 mm) or not
// finite are counted and dropped; Drain() may be called from one thread.
class TfReader {
 public:
  static StatusOr<std::unique_ptr<TfReader>> Create(Participant& participant,
                                                    std::shared_ptr<WakeUp> wake_up = nullptr);
  ~TfReader();

  std::vector<FrameTransform> Drain();
  uint64_t refused() const;

 private:
  class Listener;
  TfReader() = default;
  std::unique_ptr<Listener> listener_;
  std::unique_ptr<ReaderEndpoint> endpoint_;
};

}  // namespace fleetmap::transport
