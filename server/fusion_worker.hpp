#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/robot_frame.hpp"
#include "common/core/sample_queue.hpp"
#include "common/core/shard_regions.hpp"
#include "common/core/status.hpp"
#include "common/core/worker_thread.hpp"
#include "common/fusion/fleet_map.hpp"
#include "common/store/map_store.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/participant.hpp"
#include "server/fleet_map_store.hpp"
#include "server/fleet_publisher.hpp"
#include "server/refusal_log.hpp"
#include "server/registration_runner.hpp"
#include "server/robot_registry.hpp"
#include "server/session_keeper.hpp"
#include "server/shard_frames.hpp"
#include "server/tile_intake.hpp"

namespace fleetmap::server {

// How the fusion worker keeps, publishes and waits; what it fuses is FleetMapOptions.
struct FusionWorkerOptions {
  // SQLite map store (WAL): every robot tile and fused tile revision, and the robots. Empty: keep
  // nothing. On start the fused map is rebuilt from the robot tiles it holds.
  std::string store_path;
  // Tile revisions the store's history keeps, oldest dropped first (0: all). A fleet of 16
  // robots writes a few hundred revisions a minute; the default keeps days of them.
  int64_t history_rows = 2'000'000;
  // A store another server holds is waited for this long (the restart pattern: a new server
  // started while the old one closes), then refused.
  std::chrono::milliseconds store_lock_timeout{std::chrono::seconds(10)};
  // The fused grid goes out on rt/fleetmap/map at most this often (when it changed).
  std::chrono::milliseconds map_period{1000};
  // Tiles of a robot id that no live status claims yet wait this long for the claim.
  std::chrono::milliseconds unclaimed_wait{std::chrono::seconds(10)};
  // Finished mapping sessions kept in memory for the object learner (the newest; the store keeps
  // them all).
  size_t sessions_in_memory = 12;
  // A shard's server (docs/shards.md): it reads its region's robot tiles only and publishes its
  // grid on rt/fleetmap/<shard>/map; the fleet map fuses the region's tiles (FleetMapOptions).
  std::optional<ShardAssignment> shard;

  Status Validate() const;
  void Describe(OptionsPrinter& out) const;
};

// What the worker has done, per robot and in total. A snapshot; thread-safe to take.
struct FusionStats {
  struct Robot {
    uint64_t tiles = 0;
    uint64_t bytes = 0;
    uint64_t rejected = 0;
  };
  std::map<RobotId, Robot> robots;
  uint64_t rejected_unattributed = 0;                  // samples too broken to name their robot
  std::map<std::string, uint64_t> refusals_by_reason;  // every refused tile, by RefusalName
  uint64_t fused_tiles_published = 0;
  uint64_t fused_bytes_published = 0;
  uint64_t maps_published = 0;
  size_t fused_tiles = 0;
  uint64_t store_errors = 0;  // failed store writes (each retried) and refused records
  // The store is behind the fused map: a write failed and store_pending records wait for the
  // next attempt (once a second). Back to false when it caught up.
  bool store_behind = false;
  size_t store_pending = 0;
  size_t sessions_finished = 0;
  // A shard's server (docs/shards.md): robot tiles on no shard's region, and tiles of other
  // shards that writers which do not filter (another vendor's) sent it.
  uint64_t tiles_on_no_shard = 0;
  uint64_t tiles_of_other_shards = 0;  // mapping sessions archived (restored ones included)
  // Dropped because a queue was full (the worker fell behind): tile events from the reader,
  // grids from grid-wire robots, robot state changes for the store.
  uint64_t tile_events_dropped = 0;
  uint64_t grids_dropped = 0;
  uint64_t robot_records_dropped = 0;
  // The fleet map's frames table as rt/fleetmap/robot_frames last said it.
  std::map<RobotId, RobotFrame> frames;
  // Robots whose standing is not the default: quarantined, admitted, or released (with why).
  std::map<RobotId, fusion::TrustReport> standings;
  uint64_t quarantines = 0;  // times a robot entered quarantine
};

// The server's fusion worker, glue around one fusion::FleetMap on a thread of its own: it drains
// robot tiles (TileIntake), grids of robots on the grid wire, operators' admissions and robots'
// frames into the map, fuses turn by turn, runs the registrations the map asks for beside it
// (RegistrationRunner), and hands what changed to the publisher (FleetPublisher), the store
// (FleetMapStore) and the mapping sessions (SessionKeeper). Never on a DDS callback. Start() and
// Stop() from the owning thread; SubmitGrid(), NoteRobotFrame(), RecordRobot(), SetServing() and
// stats() from any thread. The listeners run on the worker's thread and must be set before
// Start(). Stop() lets the round in progress finish (and one more, if the thread was waiting),
// then writes what the store still lacks; samples queued after that are not fused.
class FusionWorker {
 public:
  static StatusOr<std::unique_ptr<FusionWorker>> Create(transport::Participant& participant,
                                                        const fusion::FleetMapOptions& map,
                                                        const FusionWorkerOptions& options,
                                                        std::shared_ptr<RobotRegistry> registry);
  ~FusionWorker();

  void SetListeners(FleetPublisher::MapListener on_fused_map, SessionKeeper::Listener on_sessions);
  void Start();
  void Stop();
  // Whether this server serves the fleet (docs/standby.md): only then does it write
  // rt/fleetmap/map and rt/tf, shared topics on which every reader would take both servers'
  // samples. It fuses and writes its fused tiles either way. Serving until told otherwise.
  void SetServing(bool serving);

  // A whole grid from a robot on the grid wire, with its fleet_from_map (nullopt: not known, the
  // fleet map places the robot's map frame).
  void SubmitGrid(const RobotId& robot, transport::MapMessage map,
                  std::optional<Pose2> fleet_from_map);
  // A robot joined: its map frame is given (fleet_from_map) or must be placed (nullopt).
  void NoteRobotFrame(const RobotId& robot, std::optional<Pose2> fleet_from_map);
  // A robot's state for the store ("active", "left", "lost").
  void RecordRobot(store::RobotRecord robot);
  FusionStats stats() const;
  // Where the fleet map placed (or was given) a robot's map frame; nullopt while unplaced.
  std::optional<Pose2> PlacementOf(const RobotId& robot) const;

 private:
  struct GridUpdate {
    RobotId robot;
    transport::MapMessage map;
    std::optional<Pose2> fleet_from_map;
  };
  struct RobotFrameNote {
    RobotId robot;
    std::optional<Pose2> fleet_from_map;
  };

  FusionWorker(const FusionWorkerOptions& options, fusion::FleetMap map,
               std::shared_ptr<RobotRegistry> registry)
      : options_(options), map_(std::move(map)), registry_(std::move(registry)) {}

  // One round: drain, fuse for a slice, place, publish, persist. True while tiles wait.
  bool Round();
  void AtStop();
  void HandleAdmissions();
  void HandleFrameNotes();
  // Fuses queued tiles turn by turn, fairly between senders, for at most `budget`.
  void FuseQueuedTiles(std::chrono::steady_clock::duration budget);
  void HandleGrids();
  void HandlePlacements(std::chrono::steady_clock::time_point now);
  void HandleRobotRecords();
  // Publishes, keeps and logs what the fleet map changed since the last call.
  void Publish();
  void ReportStandings(const std::vector<fusion::TrustReport>& standings);
  // `sender`: the participant that sent it, when known (the log is rate-limited per sender).
  void Refuse(const RobotId& robot, fusion::Refusal reason, const std::string& detail,
              const std::string& sender = {});

  FusionWorkerOptions options_;
  fusion::FleetMap map_;  // worker thread only
  std::shared_ptr<RobotRegistry> registry_;
  std::unique_ptr<TileIntake> intake_;                 // worker thread only
  std::unique_ptr<ShardFrames> shard_frames_;          // a shard of several: others' placements
  std::unique_ptr<FleetPublisher> publisher_;          // worker thread only
  std::unique_ptr<FleetMapStore> store_;               // worker thread only; may be null
  std::unique_ptr<SessionKeeper> sessions_;            // worker thread only
  std::unique_ptr<RegistrationRunner> registrations_;  // results wake the worker
  std::unique_ptr<transport::RobotAdmissionReader> admission_reader_;
  SampleQueue<GridUpdate> grids_{64};
  SampleQueue<RobotFrameNote> frame_notes_{1024};
  SampleQueue<store::RobotRecord> robot_records_{1024};
  RefusalLog refusals_{"server"};  // worker thread only
  std::atomic<bool> serving_{true};
  // How long one loop fuses before it drains the readers again.
  static constexpr std::chrono::milliseconds kFusionSlice{50};
  mutable std::mutex stats_mutex_;
  FusionStats stats_;  // guarded by stats_mutex_
  // Wakes on new tiles (the reader's listener), grids, robot records and registration results;
  // fuses at least every 50 ms. Last member: its thread stops before the rest goes.
  WorkerThread thread_{std::chrono::milliseconds(50)};
};

}  // namespace fleetmap::server
