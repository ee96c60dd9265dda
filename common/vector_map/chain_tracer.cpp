#include "common/vector_map/chain_tracer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

#include "common/vector_map/skeleton.hpp"

namespace fleetmap::vector_map {
namespace {

// Bit k of kLinkTable[mask]: the m-adjacency link to neighbour k of a pixel whose skeleton
// 8-neighbourhood is `mask` (a 4-neighbour always; a diagonal one only if neither 4-neighbour
// beside it is skeleton).
constexpr std::array<uint8_t, 256> BuildLinkTable() {
  std::array<uint8_t, 256> table{};
  for (int mask = 0; mask < 256; ++mask) {
    int links = 0;
    for (int k = 0; k < 8; ++k) {
      if (!((mask >> k) & 1)) continue;
      const bool before = (mask >> ((k + 7) % 8)) & 1;
      const bool after = (mask >> ((k + 1) % 8)) & 1;
      if (k % 2 == 0 || (!before && !after)) links |= 1 << k;
    }
    table[mask] = static_cast<uint8_t>(links);
  }
  return table;
}
constexpr std::array<uint8_t, 256> kLinkTable = BuildLinkTable();
constexpr std::array<uint8_t, 256> BuildDegreeTable() {
  std::array<uint8_t, 256> table{};
  for (int mask = 0; mask < 256; ++mask) {
    table[mask] = static_cast<uint8_t>(std::popcount(static_cast<unsigned>(kLinkTable[mask])));
  }
  return table;
}
constexpr std::array<uint8_t, 256> kDegreeTable = BuildDegreeTable();

// A cached mask: the mask | kCachedMask (entries without the bit are not cached).
constexpr uint16_t kCachedMask = 0x100;

// A zeroed per-thread mask cache over the raster, reused across calls (callers restore the zeros).
std::vector<uint16_t>& ZeroedMaskCache(size_t size) {
  thread_local std::vector<uint16_t> cache;
  if (cache.size() < size) cache.resize(size, 0);
  return cache;
}

struct Neighbourhood {
  explicit Neighbourhood(const CellRaster& raster) : raster(raster) {
    for (int k = 0; k < 8; ++k) {
      offset[k] = kNeighbourDy[k] * raster.stride() + kNeighbourDx[k];
    }
  }
  bool Skeleton(int index) const { return raster.Has(index, CellRaster::kSkeleton); }
  // Bit k: m-adjacency link from `index` to its neighbour k.
  unsigned Links(int index) const { return kLinkTable[Mask(index)]; }
  int Degree(int index) const { return kDegreeTable[Mask(index)]; }
  // Bit k: neighbour k is skeleton. Tracing asks for each pixel's mask several times (its degree,
  // its links, its neighbours' degrees), so TraceChains caches the skeleton's masks.
  unsigned Mask(int index) const {
    if (cache != nullptr && (cache[index] & kCachedMask) != 0) return cache[index] & 0xFFu;
    return ComputeMask(index);
  }
  unsigned ComputeMask(int index) const {
    unsigned mask = 0;
    for (int k = 0; k < 8; ++k) mask |= (Skeleton(index + offset[k]) ? 1u : 0u) << k;
    return mask;
  }
  const CellRaster& raster;
  const uint16_t* cache = nullptr;
  std::array<int, 8> offset{};
};

// One end of a chain: chain id * 2 + (0: front, 1: back).
int EndPixel(const std::vector<PixelChain>& chains, int end) {
  const auto& pixels = chains[end / 2].pixels;
  return end % 2 == 0 ? pixels.front() : pixels.back();
}

// Unit direction from a chain end into the chain, looking a few pixels ahead.
std::pair<double, double> EndDirection(const CellRaster& raster,
                                       const std::vector<PixelChain>& chains, int end) {
  const auto& pixels = chains[end / 2].pixels;
  const int n = static_cast<int>(pixels.size());
  const int steps = std::min(4, n - 1);
  const int from = end % 2 == 0 ? pixels[0] : pixels[n - 1];
  const int to = end % 2 == 0 ? pixels[steps] : pixels[n - 1 - steps];
  const double dx = raster.X(to) - raster.X(from);
  const double dy = raster.Y(to) - raster.Y(from);
  const double length = std::hypot(dx, dy);
  return length > 0 ? std::make_pair(dx / length, dy / length) : std::make_pair(0.0, 0.0);
}

// Pairs the chain ends that meet at junction pixels, straightest pairs first.
std::vector<int> PairEndsAtJunctions(const CellRaster& raster, const Neighbourhood& nb,
                                     const std::vector<PixelChain>& chains) {
  std::vector<int> partner(2 * chains.size(), -1);
  std::vector<std::pair<int, int>> ends;  // (pixel, end)
  for (size_t c = 0; c < chains.size(); ++c) {
    if (chains[c].pixels.size() < 2 || chains[c].ring()) continue;
    for (int side = 0; side < 2; ++side) {
      const int end = static_cast<int>(2 * c) + side;
      const int pixel = EndPixel(chains, end);
      if (nb.Degree(pixel) >= 3) ends.emplace_back(pixel, end);
    }
  }
  std::sort(ends.begin(), ends.end());
  struct Candidate {
    double dot;
    int a;
    int b;
  };
  std::vector<Candidate> candidates;
  for (size_t begin = 0; begin < ends.size();) {
    size_t stop = begin;
    while (stop < ends.size() && ends[stop].first == ends[begin].first) ++stop;
    candidates.clear();
    for (size_t i = begin; i < stop; ++i) {
      const auto [ax, ay] = EndDirection(raster, chains, ends[i].second);
      for (size_t j = i + 1; j < stop; ++j) {
        const auto [bx, by] = EndDirection(raster, chains, ends[j].second);
        candidates.push_back({ax * bx + ay * by, ends[i].second, ends[j].second});
      }
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& l, const Candidate& r) { return l.dot < r.dot; });
    for (const Candidate& candidate : candidates) {
      if (partner[candidate.a] >= 0 || partner[candidate.b] >= 0) continue;
      partner[candidate.a] = candidate.b;
      partner[candidate.b] = candidate.a;
    }
    begin = stop;
  }
  return partner;
}

// Concatenates chains along the paired ends.
std::vector<PixelChain> MergeThroughJunctions(std::vector<PixelChain> chains,
                                              const std::vector<int>& partner) {
  const int n = static_cast<int>(chains.size());
  std::vector<PixelChain> merged;
  merged.reserve(chains.size());
  std::vector<bool> used(n, false);
  // A merged chain is built in a reused buffer, then stored with one allocation; a chain that
  // continues into no other (most of them) is moved over as it is, reversed if walked from its
  // back, and no other walk reads it again (it is used).
  thread_local std::vector<int> buffer;
  auto walk = [&](int start_end) {
    const int first = start_end / 2;
    used[first] = true;
    const int first_next = partner[start_end % 2 == 0 ? 2 * first + 1 : 2 * first];
    if (first_next < 0 || used[first_next / 2]) {
      auto& pixels = chains[first].pixels;
      if (start_end % 2 != 0) std::reverse(pixels.begin(), pixels.end());
      merged.push_back(std::move(chains[first]));
      return;
    }
    buffer.clear();
    int end = start_end;
    while (true) {
      const int c = end / 2;
      used[c] = true;
      const auto& pixels = chains[c].pixels;
      const bool forward = end % 2 == 0;
      const size_t skip = buffer.empty() ? 0 : 1;
      for (size_t k = skip; k < pixels.size(); ++k) {
        buffer.push_back(forward ? pixels[k] : pixels[pixels.size() - 1 - k]);
      }
      const int exit_end = forward ? 2 * c + 1 : 2 * c;
      const int next = partner[exit_end];
      if (next < 0 || used[next / 2]) break;
      end = next;
    }
    merged.push_back({std::vector<int>(buffer.begin(), buffer.end())});
  };
  for (int c = 0; c < n; ++c) {
    if (used[c]) continue;
    if (partner[2 * c] < 0) {
      walk(2 * c);
    } else if (partner[2 * c + 1] < 0) {
      walk(2 * c + 1);
    }
  }
  for (int c = 0; c < n; ++c) {
    if (!used[c]) walk(2 * c);  // cycles through junctions: they close on a junction pixel
  }
  return merged;
}

}  // namespace

int SkeletonDegree(const CellRaster& raster, int index) {
  return Neighbourhood(raster).Degree(index);
}

std::vector<PixelChain> TraceChains(CellRaster& raster, const std::vector<int>& skeleton) {
  // The skeleton does not change while it is traced (only kVisited does, which masks ignore).
  Neighbourhood nb(raster);
  std::vector<uint16_t>& cache = ZeroedMaskCache(raster.size());
  for (const int p : skeleton) cache[p] = static_cast<uint16_t>(kCachedMask | nb.ComputeMask(p));
  nb.cache = cache.data();
  std::vector<PixelChain> chains;
  auto terminal = [&](int index) { return nb.Degree(index) != 2; };
  auto visited = [&](int index) { return raster.Has(index, CellRaster::kVisited); };
  auto visit = [&](int index) { raster.at(index) |= CellRaster::kVisited; };
  // Each chain is traced into a reused buffer, then stored with one allocation.
  thread_local std::vector<int> chain;
  for (const int p : skeleton) {
    if (!terminal(p)) continue;
    if (nb.Degree(p) == 0) {
      chains.push_back({{p}});
      continue;
    }
    const unsigned p_links = nb.Links(p);
    for (int k = 0; k < 8; ++k) {
      if (!((p_links >> k) & 1u)) continue;
      const int q = p + nb.offset[k];
      if (terminal(q)) {
        if (p < q) chains.push_back({{p, q}});
        continue;
      }
      if (visited(q)) continue;
      chain.assign(1, p);
      int previous = p;
      int current = q;
      while (!terminal(current) && !visited(current)) {
        visit(current);
        chain.push_back(current);
        int next = -1;
        const unsigned links = nb.Links(current);
        for (int j = 0; j < 8; ++j) {
          if (!((links >> j) & 1u)) continue;
          const int r = current + nb.offset[j];
          if (r != previous && (terminal(r) || !visited(r) || r == p)) {
            next = r;
            break;
          }
        }
        if (next < 0) break;
        previous = current;
        current = next;
      }
      if (terminal(current)) chain.push_back(current);
      chains.push_back({std::vector<int>(chain.begin(), chain.end())});
    }
  }
  for (const int p : skeleton) {  // rings of degree-2 pixels
    if (terminal(p) || visited(p)) continue;
    chain.assign(1, p);
    visit(p);
    int previous = -1;
    int current = p;
    while (true) {
      int next = -1;
      const unsigned links = nb.Links(current);
      for (int j = 0; j < 8; ++j) {
        if (!((links >> j) & 1u)) continue;
        const int r = current + nb.offset[j];
        if (r == previous) continue;
        if (r == p && chain.size() > 2) {
          next = r;
          break;
        }
        if (!visited(r)) {
          next = r;
          break;
        }
      }
      if (next < 0) break;
      chain.push_back(next);
      if (next == p) break;
      visit(next);
      previous = current;
      current = next;
    }
    chains.push_back({std::vector<int>(chain.begin(), chain.end())});
  }
  raster.Clear(skeleton, CellRaster::kVisited);
  const std::vector<int> partner = PairEndsAtJunctions(raster, nb, chains);
  for (const int p : skeleton) cache[p] = 0;
  return MergeThroughJunctions(std::move(chains), partner);
}

}  // namespace fleetmap::vector_map
