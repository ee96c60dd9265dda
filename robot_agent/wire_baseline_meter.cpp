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
  stop_.store(true);
  thread_.join();
  delete inbox_.exchange(nullptr);
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
  grid_bytes_ += transport::OccupancyGridPayloadBytes(whole);
  ++events_;
  last_ = std::move(whole.grid);

  auto batch = std::make_unique<Batch>();
  size_t cells = 0;
  for (const TileCells& tile : tiles) {
    transport::MapUpdate patch = PatchOf(grid, tile.rect);
    patch.stamp = stamp;
    patch.frame_id = frame_id;
    cells += patch.data.size();
    batch->push_back(std::move(patch));
  }
  while (pending_cells_.load() > kMaxPendingCells && !stop_.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  pending_ += static_cast<uint32_t>(batch->size());
  pending_cells_ += cells;
  Hand(std::move(batch));
  return Status::Ok();
}

void WireBaselineMeter::Hand(std::unique_ptr<Batch> batch) {
  // The thread takes the whole inbox with one exchange; what it has not taken yet joins the new
  // batch, oldest first. No step waits for the thread.
  if (std::unique_ptr<Batch> untaken{inbox_.exchange(nullptr)}) {
    untaken->insert(untaken->end(), std::make_move_iterator(batch->begin()),
                    std::make_move_iterator(batch->end()));
    batch = std::move(untaken);
  }
  inbox_.store(batch.release());
}

WireBaselines WireBaselineMeter::totals() const {
  WireBaselines totals;
  totals.events = events_.load();
  totals.grid_bytes = grid_bytes_.load();
  totals.patch_bytes = patch_bytes_.load();
  totals.zstd3_bytes = zstd3_bytes_.load();
  totals.zstd19_bytes = zstd19_bytes_.load();
  totals.lz4_bytes = lz4_bytes_.load();
  totals.patches_pending = pending_.load();
  return totals;
}

bool WireBaselineMeter::WaitUntilDone(std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (pending_.load() > 0) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

void WireBaselineMeter::Hurry() {
  const pid_t thread = thread_id_.load();
  const sched_param param{};
  if (thread != 0 && sched_setscheduler(thread, SCHED_OTHER, &param) != 0) {
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
  thread_id_.store(gettid());
  while (!stop_.load()) {
    const std::unique_ptr<Batch> batch{inbox_.exchange(nullptr)};
    if (!batch) {
      // Polling keeps the agent's thread free of any wake-up that could wait on this one.
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    for (const transport::MapUpdate& patch : *batch) {
      if (stop_.load()) return;
      Measure(patch);
      pending_cells_ -= patch.data.size();
      --pending_;
    }
  }
}

void WireBaselineMeter::Measure(const transport::MapUpdate& patch) {
  const auto live = transport::CompressMapUpdate(patch, kLiveZstdLevel);
  const auto strongest = transport::CompressMapUpdate(patch, kStrongestZstdLevel);
  const auto fast = Lz4Patch(patch);
  // A patch cut from a valid grid always compresses.
  FLEETMAP_CHECK(live.ok() && strongest.ok() && fast.ok(), "compressing a patch failed");
  patch_bytes_ += transport::MapUpdatePayloadBytes(patch);
  zstd3_bytes_ += transport::CompressedMapUpdatePayloadBytes(*live);
  zstd19_bytes_ += transport::CompressedMapUpdatePayloadBytes(*strongest);
  lz4_bytes_ += transport::CompressedMapUpdatePayloadBytes(*fast);
}

}  // namespace fleetmap::agent
