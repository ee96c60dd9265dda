#pragma once

#include <memory>
#include <optional>
#include <string>

#include "common/core/status.hpp"
#include "common/grid/map_io.hpp"
#include "common/grid/occupancy_grid.hpp"
#include "common/transport/map_update_reader.hpp"
#include "common/transport/occupancy_grid_reader.hpp"
#include "common/transport/participant.hpp"
#include "robot_agent/file_signature.hpp"

namespace fleetmap::agent {

// Where an agent's grid comes from. Poll() is called from the agent's loop; it returns the grid
// when it changed since the last call. A source never stops the agent: a broken update is logged
// and the previous map stays.
class MapSource {
 public:
  virtual ~MapSource() = default;
  virtual std::optional<grid::OccupancyGrid> Poll() = 0;
  virtual std::string Describe() const = 0;
};

// A ROS map_server YAML and the image it names, followed as an editor or map_saver writes them:
// both are re-read when either changes (FileSignature: size, times, inode), whether the files are
// replaced atomically (temp + rename) or rewritten in place, and in either order. A read that fails
// (a YAML naming an image that does not exist yet, a half-written image) keeps the previous map,
// is logged once per distinct problem, and is tried again when a file changes; a read during which
// a file changed is thrown away and tried again at the next poll. Create fails when the map cannot
// be loaded at start (that is the user's error to fix, exit code 2). Single-threaded: the agent's
// loop calls Poll.
class FileMapSource : public MapSource {
 public:
  static StatusOr<std::unique_ptr<FileMapSource>> Create(std::string path,
                                                         grid::MapLoadOptions options = {});
  std::optional<grid::OccupancyGrid> Poll() override;
  std::string Describe() const override { return path_; }

 private:
  // The two files a map is read from, as they were when read.
  struct Signatures {
    FileSignature yaml;
    FileSignature image;
    friend bool operator==(const Signatures&, const Signatures&) = default;
  };

  FileMapSource(std::string path, grid::MapLoadOptions options)
      : path_(std::move(path)), options_(std::move(options)) {}

  Signatures Now() const;
  // Reads the YAML and its image. Sets `read_` to the files' signatures, or to nothing when a
  // file changed during the read (the result may mix two versions).
  StatusOr<grid::OccupancyGrid> Read();

  std::string path_;
  grid::MapLoadOptions options_;
  std::string image_path_;                      // named by the last YAML that could be read
  std::optional<Signatures> read_;              // of the last read, good or not
  std::string problem_;                         // the last failure logged, until a read succeeds
  std::optional<grid::OccupancyGrid> pending_;  // loaded at Create, handed out by the first Poll
};

// nav_msgs/OccupancyGrid samples on a DDS topic (a ROS 2 SLAM's /map is rt/map), patched by the
// map_msgs/OccupancyGridUpdate samples on <topic>_updates (/map_updates) between full maps.
class TopicMapSource : public MapSource {
 public:
  static StatusOr<std::unique_ptr<TopicMapSource>> Create(transport::Participant& participant,
                                                          const std::string& topic);
  std::optional<grid::OccupancyGrid> Poll() override;
  std::string Describe() const override { return topic_; }

 private:
  explicit TopicMapSource(std::string topic) : topic_(std::move(topic)) {}

  std::string topic_;
  std::unique_ptr<transport::OccupancyGridReader> reader_;
  std::unique_ptr<transport::MapUpdateReader> updates_;
  std::optional<grid::OccupancyGrid> current_;  // the last full map with its updates applied
};

}  // namespace fleetmap::agent
