#include "common/vector_map/wall_pockets.hpp"

#include <algorithm>
#include <utility>

namespace fleetmap::vector_map {
namespace {

class PocketFinder {
 public:
  explicit PocketFinder(CellRaster& raster)
      : raster_(raster), stride_(raster.stride()), near_rect_(GrownByOne(raster.rect())) {}

  std::vector<int> Run() {
    for (const int i : raster_.occupied_near_rect()) {
      const int x = raster_.X(i);
      const int y = raster_.Y(i);
      for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int start = i + dy * stride_ + dx;
        // The flag test first: most neighbours of an occupied cell are occupied or visited. A
        // start that is not sandwiched would end its flood at once, so it is not flooded (nor
        // marked visited: a later flood that reaches it ends there all the same).
        if (raster_.Has(start, kStop) || !near_rect_.Contains(x + dx, y + dy) ||
            !Sandwiched(start)) {
          continue;
        }
        Flood(start);
      }
    }
    raster_.Clear(visited_, CellRaster::kVisited);
    std::sort(pockets_.begin(), pockets_.end());
    return std::move(pockets_);
  }

 private:
  static constexpr uint8_t kStop = CellRaster::kOccupied | CellRaster::kVisited;

  static CellRect GrownByOne(const CellRect& rect) {
    return CellRect{rect.x0 - 1, rect.y0 - 1, rect.width + 2, rect.height + 2};
  }
  bool InNearRect(int i) const { return near_rect_.Contains(raster_.X(i), raster_.Y(i)); }
  // Cells whose 8 neighbours all lie in the image (a pocket may reach into the margin).
  bool Interior(int i) const {
    const int x = raster_.X(i);
    const int y = raster_.Y(i);
    return raster_.Contains(x - 1, y - 1) && raster_.Contains(x + 1, y + 1);
  }

  // Whether a cell lies between two occupied cells on opposite sides (E-W, N-S or either
  // diagonal): a line through it then stays within a cell of the wall on both sides.
  bool Sandwiched(int i) const {
    auto occupied = [&](int o) { return raster_.Has(i + o, CellRaster::kOccupied); };
    return (occupied(1) && occupied(-1)) || (occupied(stride_) && occupied(-stride_)) ||
           (occupied(stride_ + 1) && occupied(-stride_ - 1)) ||
           (occupied(stride_ - 1) && occupied(-stride_ + 1));
  }

  // Floods the non-occupied 4-component of `start` breadth first and keeps its cells near the
  // rectangle if it is a pocket. Every cell reached is marked visited and stays so: a later flood
  // that meets a visited cell it did not reach itself has met a region found open, so it is open.
  void Flood(int start) {
    current_.assign(1, start);
    Visit(start);
    for (size_t head = 0; head < current_.size(); ++head) {
      const int i = current_[head];
      if (!Interior(i) || !Sandwiched(i) ||
          current_.size() > static_cast<size_t>(kMaxWallPocketCells)) {
        return;
      }
      for (const int o : {1, -1, stride_, -stride_}) {
        const int n = i + o;
        if (raster_.Has(n, CellRaster::kOccupied)) continue;
        if (raster_.Has(n, CellRaster::kVisited)) {
          if (std::find(current_.begin(), current_.end(), n) == current_.end()) return;
          continue;
        }
        Visit(n);
        current_.push_back(n);
      }
    }
    for (const int i : current_) {
      if (InNearRect(i)) pockets_.push_back(i);
    }
  }

  void Visit(int i) {
    raster_.at(i) |= CellRaster::kVisited;
    visited_.push_back(i);
  }

  CellRaster& raster_;
  const int stride_;
  const CellRect near_rect_;
  std::vector<int> current_;  // the cells of the flood under way, in the order reached
  std::vector<int> visited_;
  std::vector<int> pockets_;
};

}  // namespace

std::vector<int> WallPocketCells(CellRaster& raster) { return PocketFinder(raster).Run(); }

}  // namespace fleetmap::vector_map
