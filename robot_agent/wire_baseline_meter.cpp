#include "robot_agent/wire_baseline_meter.hpp"

#include <lz4.h>
#include <sched.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "common/core/check.hpp"
#include "common/transport/map_update_codec.hpp"
#include "common/transport/wire_sizes.hpp"
#include "robot_agent/tile_patches.hpp"

namespace fleetmap::agent {
namespace {

// The level a live agent affords (Wire::kGridUpdatesZstd), and zstd's strongest.
constexpr int kLiveZstdLevel = 3;
constexpr int kStrongestZstdLevel = 19;

// The patch in CompressedGridUpdate's shape with LZ4 (default acceleration) cells: its size is
// that of any LZ4 variant of the message.
StatusOr<transport::CompressedMapUpdate> Lz4Patch(const transport::MapUpdate& patch) {
  transport::CompressedMapUpdate out;
  out.x = patch.x;
  out.y = patch.y;
  out.width = patch.width;
  out.height = patch.height;
  out.raw_size = static_cast<uint32_t>(patch.data.size());
  out.stamp = patch.stamp;
  out.frame_id = patch.frame_id;
  const int source_size = static_cast<int>(patch.data.size());
  out.data.resize(static_cast<size_t>(LZ4_compressBound(source_size)));
  const int size = LZ4_compress_default(reinterpret_cast<const char*>(patch.data.data()),
                                        reinterpret_cast<char*>(out.data.data()), source_size,
                                        static_cast<int>(out.data.size()));
  if (size <= 0) return InternalError("LZ4 compression failed");
  out.data.resize(static_cast<size_t>(size));
  return out;
}

}  // namespace

StatusOr<std::unique_ptr<WireBaselineMeter>> WireBaselineMeter::Create(RobotId robot,
                                                                       Pose2 fleet_from_map,
                                                                       double tile_size) {
  std::unique_ptr<WireBaselineMeter> meter(
      new WireBaselineMeter(std::move(robot), fleet_from_map, tile_size));
  meter->thread_ = std::thread([self = meter.get()] { self->Run(); });
  return meter;
}

WireBaselineMeter::~WireBaselineMeter() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

Status WireBaselineMeter::Account(const grid::OccupancyGrid& grid) {
  const Transform2 fleet_from_map = fleet_from_map_.ToTransform();
  const bool fresh = !last_ || !SameGeometry(*last_, grid);
  FLEETMAP_ASSIGN_OR_RETURN(const std::vector<TileCells> tiles,
                            fresh ? KnownTiles(grid, fleet_from_map, tile_size_)
                                  : ChangedTiles(*last_, grid, fleet_from_map, tile_size_));
  if (!fresh && tiles.empty()) return Status::Ok();  // nothing changed: no wire sends anything
  const Timestamp stamp = Clock::now();
  const std::string frame_id = robot_.value + "/map";
  transport::MapMessage whole;
  whole.grid = grid;
  whole.frame_id = frame_id;
  whole.stamp = stamp;
  const size_t grid_bytes = transport::OccupancyGridPayloadBytes(whole);
  last_ = std::move(whole.grid);

  std::unique_lock lock(mutex_);
  ++totals_.events;
  totals_.grid_bytes += grid_bytes;
  for (const TileCells& tile : tiles) {
    transport::MapUpdate patch = PatchOf(grid, tile.rect);
    patch.stamp = stamp;
    patch.frame_id = frame_id;
    changed_.wait(lock, [this] { return pending_cells_ <= kMaxPendingCells; });
    pending_cells_ += patch.data.size();
    pending_.push_back(std::move(patch));
  }
  lock.unlock();
  changed_.notify_all();
  return Status::Ok();
}

WireBaselines WireBaselineMeter::totals() const {
  std::lock_guard lock(mutex_);
  WireBaselines totals = totals_;
  totals.patches_pending = static_cast<uint32_t>(pending_.size() + (measuring_ ? 1 : 0));
  return totals;
}

bool WireBaselineMeter::WaitUntilDone(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  return changed_.wait_for(lock, timeout, [this] { return pending_.empty() && !measuring_; });
}

void WireBaselineMeter::Hurry() {
  std::lock_guard lock(mutex_);
  const sched_param param{};
  if (thread_id_ != 0 && sched_setscheduler(thread_id_, SCHED_OTHER, &param) != 0) {
    spdlog::warn("{}: the byte accounting stays at idle priority: {}", robot_.value,
                 std::strerror(errno));
  }
}

void WireBaselineMeter::Run() {
  // Linux applies a policy set with pid 0 to the calling thread only.
  const sched_param param{};
  if (sched_setscheduler(0, SCHED_IDLE, &param) != 0) {
    spdlog::warn("{}: the byte accounting runs at normal priority (SCHED_IDLE: {})", robot_.value,
                 std::strerror(errno));
  }
  std::unique_lock lock(mutex_);
  thread_id_ = gettid();
  while (true) {
    changed_.wait(lock, [this] { return stop_ || !pending_.empty(); });
    if (stop_) return;
    transport::MapUpdate patch = std::move(pending_.front());
    pending_.pop_front();
    pending_cells_ -= patch.data.size();
    measuring_ = true;
    lock.unlock();
    changed_.notify_all();  // Account() may be waiting for room
    Measure(patch);
    lock.lock();
    measuring_ = false;
    changed_.notify_all();
  }
}

void WireBaselineMeter::Measure(const transport::MapUpdate& patch) {
  const size_t raw = transport::MapUpdatePayloadBytes(patch);
  const auto live = transport::CompressMapUpdate(patch, kLiveZstdLevel);
  const auto strongest = transport::CompressMapUpdate(patch, kStrongestZstdLevel);
  const auto fast = Lz4Patch(patch);
  // A patch cut from a valid grid always compresses.
  FLEETMAP_CHECK(live.ok() && strongest.ok() && fast.ok(), "compressing a patch failed");
  const size_t zstd3 = transport::CompressedMapUpdatePayloadBytes(*live);
  const size_t zstd19 = transport::CompressedMapUpdatePayloadBytes(*strongest);
  const size_t lz4 = transport::CompressedMapUpdatePayloadBytes(*fast);
  std::lock_guard lock(mutex_);
  totals_.patch_bytes += raw;
  totals_.zstd3_bytes += zstd3;
  totals_.zstd19_bytes += zstd19;
  totals_.lz4_bytes += lz4;
}

}  // namespace fleetmap::agent
