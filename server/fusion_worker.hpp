#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include "common/core/ids.hpp"
#include "common/core/options_printer.hpp"
#include "common/core/robot_status.hpp"
#include "common/core/sample_queue.hpp"
#include "common/core/status.hpp"
#include "common/core/worker_thread.hpp"
#include "common/fusion/tile_fusion.hpp"
#include "common/store/map_store.hpp"
#include "common/transport/keyed_state_topic.hpp"
#include "common/transport/map_message.hpp"
#include "common/transport/occupancy_grid_writer.hpp"
#include "common/transport/participant.hpp"
#include "common/transport/vector_tile_reader.hpp"
#include "common/transport/vector_tile_writer.hpp"
#include "server/fair_tile_queue.hpp"
#include "server/held_tiles.hpp"
#include "server/map_frame_robots.hpp"
#include "server/refusal_log.hpp"
#include "server/robot_placer.hpp"
#include "server/robot_registry.hpp"
#include "server/session_archive.hpp"
#include "server/store_sync.hpp"
#include "server/tile_admission.hpp"

namespace fleetmap::server {

struct FusionWorkerOptions {
  fusion::FusionOptions fusion;
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
  // What a robot's tiles must satisfy, and its quotas.
  AdmissionOptions admission;
  // Tiles of a robot id that no live status claims yet wait this long for the claim.
  std::chrono::milliseconds unclaimed_wait{std::chrono::seconds(10)};
  // How robots whose tiles come in their own map frame are placed.
  PlacementOptions placement;
  // Finished mapping sessions kept in memory for the object learner (the newest; the store keeps
  // them all).
  size_t sessions_in_memory = 12;

  // The fusion and admission options' own checks.
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
  size_t sessions_finished = 0;  // mapping sessions archived (restored ones included)
  // Dropped because a queue was full (the worker fell behind): tile events from the reader,
  // grids from grid-wire robots, robot state changes for the store.
  uint64_t tile_events_dropped = 0;
  uint64_t grids_dropped = 0;
  uint64_t robot_records_dropped = 0;
  // Every robot's map frame as rt/fleetmap/robot_frames last said.
  std::map<RobotId, transport::RobotFrameMessage> frames;
  // Robots whose standing is not the default: quarantined, admitted, or released (with why).
  std::map<RobotId, fusion::TrustReport> standings;
  uint64_t quarantines = 0;  // times a robot entered quarantine
};

// The server's fusion worker: drains robot tiles (and grids of robots on the grid wire), fuses
// them, publishes changed fused tiles on rt/fleetmap/fused_tiles and the fused grid on
// rt/fleetmap/map, and archives each robot's mapping session when it leaves or is lost.
// Everything runs on its own thread, never on a DDS callback. Start() and Stop() from the owning
// thread; SubmitGrid(), RecordRobot() and stats() from any thread. The listeners run on the
// worker's thread and must be set before Start(). Stop() lets the round in progress finish (and
// one more, if the thread was waiting), then writes what the store still lacks; samples queued
// after that are not fused.
class FusionWorker {
 public:
  static StatusOr<std::unique_ptr<FusionWorker>> Create(transport::Participant& participant,
                                                        const FusionWorkerOptions& options,
                                                        std::shared_ptr<RobotRegistry> registry);
  ~FusionWorker();

  // Called with every fused grid published on rt/fleetmap/map.
  using FusedMapListener = std::function<void(const grid::OccupancyGrid& fused)>;
  // Called with all finished sessions (oldest first) when one more finished, and at start when
  // the store held some.
  using SessionsListener = std::function<void(std::vector<MappingSession> finished)>;
  void SetListeners(FusedMapListener on_fused_map, SessionsListener on_sessions);

  void Start();
  void Stop();
  // Whether this server serves the fleet (docs/standby.md): only then does it write
  // rt/fleetmap/map and rt/tf, shared topics on which every reader would take both servers'
  // samples. It fuses and writes its fused tiles either way. From any thread; a server that
  // starts serving writes its fused map at once. Serving until told otherwise.
  void SetServing(bool serving);

  // A whole grid from a robot on the grid wire, with its fleet_from_map (nullopt: not known, the
  // server places the robot's map frame).
  void SubmitGrid(const RobotId& robot, transport::MapMessage map,
                  std::optional<Pose2> fleet_from_map);
  // A robot joined: its map frame is given (fleet_from_map) or must be placed (nullopt).
  void NoteRobotFrame(const RobotId& robot, std::optional<Pose2> fleet_from_map);
  // A robot's state for the store ("active", "left", "lost").
  void RecordRobot(store::RobotRecord robot);
  FusionStats stats() const;
  // Where the worker placed (or was given) a robot's map frame; nullopt while unplaced.
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
  // An admitted robot tile waiting for its robot's turn.
  struct PendingTile {
    transport::VectorTileMessage tile;
    Timestamp evidence_stamp;
    size_t bytes = 0;
  };

  FusionWorker(const FusionWorkerOptions& options, fusion::TileFusion fusion,
               std::shared_ptr<RobotRegistry> registry)
      : options_(options),
        fusion_(std::move(fusion)),
        registry_(std::move(registry)),
        admission_(options.admission, options.fusion),
        held_(HeldLimits(options)) {}
  static HeldTiles::Limits HeldLimits(const FusionWorkerOptions& options);

  // Rebuilds the fused map from the robot tiles in the store.
  Status Restore();
  // One round of the worker: drain, fuse for a slice, publish, persist. True while tiles wait.
  bool Round();
  // The last attempt to store what the store lacks.
  void AtStop();
  // Drains the tile reader: admission, then the fair queue (or the unclaimed hold).
  void HandleTileEvents();
  void Admit(transport::TileEvent event, Timestamp now,
             std::chrono::steady_clock::time_point steady);
  // Operators' admissions of quarantined robots (rt/fleetmap/admissions).
  void HandleAdmissions();
  // Robots that entered or left quarantine in the last fusion: log, robot_frames, stats.
  void ReportStandings();
  // Robots of one participant never confirm each other's changes (quarantine).
  void NoteSource(const RobotId& robot);
  // `participant`: who sent it, when known (the log is rate-limited per participant).
  void Refuse(const RobotId& robot, Refusal reason, const std::string& detail,
              const std::string& participant = {});
  // Why the robot's mapping session, ending now, is not a map of the place to learn objects
  // from (empty: it is kept).
  std::string WhySessionIsNotKept(const RobotId& robot) const;
  // Keeps an operator's admission in the store, so that it outlives a restart.
  void StoreAdmission(const transport::RobotAdmissionMessage& admission);
  void RemoveTile(const RobotId& robot, const TileId& tile);
  // The robot's tile leaves fusion, its session and (as a removal) the store.
  void DropTileData(const RobotId& robot, const TileId& tile);
  // Every tile of `robot`, queued or fused, to make room for an older robot's (global budget).
  void EvictRobot(const RobotId& robot);
  // Tiles held for robot ids that a status has claimed since, or that waited too long.
  void ReleaseHeldTiles(std::chrono::steady_clock::time_point steady);
  // Fuses queued tiles turn by turn, fairly between robots, for at most `budget`.
  void FuseQueuedTiles(std::chrono::steady_clock::duration budget);
  void ApplyTile(const RobotId& robot, PendingTile pending);
  void Persist();
  // Robot state changes: a robot that left or was lost ends its mapping session.
  void HandleRobotRecords();
  // Queues a tile revision for the store (and, for a robot's tile, its changed contribution).
  // `owner` is the store's owner key: the robot id's string, or store::kFleetOwner.
  void Remember(const std::string& owner, const transport::VectorTileMessage& tile);
  // Queues a robot contribution that changed or was removed for the store.
  void RememberContribution(const RobotId& robot, const TileId& tile);
  // Persist() at `now`; a final attempt at stop ignores the retry period and says what is lost.
  void Persist(std::chrono::steady_clock::time_point now);
  void HandleGrids();
  // A tile of a robot whose tiles are in its own map frame: kept, and fused once placed.
  void ApplyMapFrameTile(const RobotId& robot, const transport::VectorTileMessage& tile,
                         Timestamp stamp);
  // The map-frame tiles the store held, back in map_frames_ (unplaced).
  void RestoreMapFrameTiles(const std::vector<store::TileRecord>& rows);
  // Placement: frames of new robots, registration results, due registrations, rt/tf.
  void HandlePlacements(std::chrono::steady_clock::time_point now);
  // The robot's frame is given: published as such, and its map-frame tiles (if any) placed there.
  void GiveFrame(const RobotId& robot, const Pose2& fleet_from_map);
  // The maps of a group's members merged in its root's map frame.
  vector_map::VectorMap GroupMap(const PlacementGroup& group) const;
  // Submits the next due registration, round robin over the robots.
  void ScheduleRegistration(std::chrono::steady_clock::time_point now);
  // The registration due for `robot`, if any: its own map on the fleet map, its group's merged
  // map on the fleet map (the group's root only), or its map on another unplaced robot's.
  std::optional<PlacementJob> NextRegistration(const RobotId& robot,
                                               std::chrono::steady_clock::time_point now) const;
  // A job for `robot` without its maps (they are copied only once it is due).
  PlacementJob MakePlacementJob(const RobotId& robot) const;
  // Fuses `robot`'s contributions to the fleet tiles `changed` anew from map_frames_.
  void RefuseMapFrameRobot(const RobotId& robot, const std::set<TileId>& changed);
  void PublishFused(std::chrono::steady_clock::time_point now);

  FusionWorkerOptions options_;
  fusion::TileFusion fusion_;  // worker thread only
  std::shared_ptr<RobotRegistry> registry_;
  std::unique_ptr<transport::VectorTileReader> tile_reader_;
  std::unique_ptr<transport::VectorTileWriter> fused_writer_;
  std::unique_ptr<transport::OccupancyGridWriter> map_writer_;
  std::unique_ptr<transport::RobotAdmissionReader> admission_reader_;
  SampleQueue<GridUpdate> grids_{64};
  SampleQueue<RobotFrameNote> frame_notes_{1024};
  MapFrameRobots map_frames_{options_.fusion.tile_size};  // worker thread only
  std::unique_ptr<RobotPlacer> placer_;                   // worker thread only (after Create)
  SampleQueue<store::RobotRecord> robot_records_{1024};
  std::unique_ptr<store::MapStore> store_;    // worker thread only (after Create)
  std::unique_ptr<SessionArchive> sessions_;  // worker thread only (after Create)
  FusedMapListener on_fused_map_;
  SessionsListener on_sessions_;
  TileAdmission admission_;  // worker thread only
  // Served fairly by participant (its robot ids share one place), keyed by robot and tile.
  FairTileQueue<PendingTile, std::string, std::pair<RobotId, TileId>> queue_;  // worker thread

  HeldTiles held_;  // worker thread only: tiles whose robot's status has not come yet
  // Robots whose open session lost tiles to a budget (CutsTheMap): not kept when it ends.
  std::set<RobotId> cut_sessions_;
  RefusalLog refusals_{"server"};    // worker thread only
  std::unique_ptr<StoreSync> sync_;  // worker thread only (after Create)
  bool map_dirty_ = false;           // worker thread only
  uint64_t fused_revisions_ = 0;     // fused tile revisions made: the fleet map changed
  RobotId last_registered_;          // whose map the placer registered last (round robin)
  size_t tiles_outside_map_ = 0;     // worker thread only
  std::chrono::steady_clock::time_point last_window_warning_{};  // worker thread only
  static constexpr std::chrono::seconds kWindowWarningPeriod{30};
  // What one robot's turn may take before the next robot's (FairTileQueue sizes turns by cost),
  // and how long one loop fuses before it drains the readers again.
  static constexpr size_t kMaxTilesPerTurn = 16;
  // Tile events admitted per drain of the reader (HandleTileEvents): a flood's backlog is decoded
  // and admitted this much at a time, between fusion turns.
  static constexpr size_t kTileEventsPerDrain = 512;
  static constexpr std::chrono::milliseconds kTurnTarget{20};
  static constexpr std::chrono::milliseconds kFusionSlice{50};
  std::chrono::steady_clock::time_point last_map_{};
  std::atomic<bool> serving_{true};
  bool was_serving_ = true;  // at the last round (the worker's thread)
  mutable std::mutex stats_mutex_;
  FusionStats stats_;  // guarded by stats_mutex_
  // Wakes on new tiles (the reader's listener), grids and robot records; fuses at least every
  // 50 ms. Last member: its thread stops before the rest goes.
  WorkerThread thread_{std::chrono::milliseconds(50)};
};

}  // namespace fleetmap::server
