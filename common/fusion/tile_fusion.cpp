#include "common/fusion/tile_fusion.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "common/core/check.hpp"
#include "common/vector_map/rasterizer.hpp"
#include "common/vector_map/tiled_vector_map.hpp"

namespace fleetmap::fusion {
namespace {

using grid::kOccupiedValue;
using grid::kUnknownValue;

// Evidence times count deciseconds from 2020-01-01 UTC: 32 bits last until 2033.
constexpr auto kEvidenceEpoch = std::chrono::sys_days{std::chrono::year{2020} / 1 / 1};

const TileId kNeighbourOffsets[] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0},
                                    {1, 0},   {-1, 1}, {0, 1},  {1, 1}};

bool SameGeometry(const vector_map::VectorMap& a, const vector_map::VectorMap& b) {
  return a.obstacles == b.obstacles && a.free_space == b.free_space;
}

}  // namespace

StatusOr<TileFusion> TileFusion::Create(const FusionOptions& options) {
  FLEETMAP_RETURN_IF_ERROR(options.Validate());
  return TileFusion(options);
}

TileFusion::TileFusion(const FusionOptions& options)
    : options_(options),
      vectorizer_([&] {
        vector_map::VectorizerOptions vectorizer = options.vectorizer;
        // Windows are cut from the fleet frame, so the lattice starts at their frame's origin.
        vectorizer.quantum = vector_map::TileQuantum(options.FusedResolution());
        vectorizer.lattice_origin = Point2::Zero();
        vectorizer.frame_id = "fleet";
        return vector_map::Vectorizer(vectorizer);
      }()),
      epoch_(kEvidenceEpoch),
      trust_(options.quarantine, options.tile_size, options.FusedResolution()) {}

grid::OccupancyGrid TileFusion::EmptyTileGrid(const TileId& tile) const {
  const int cells = options_.CellsPerTile();
  return grid::OccupancyGrid(cells, cells, options_.FusedResolution(),
                             Pose2{tile.x * options_.tile_size, tile.y * options_.tile_size, 0.0},
                             kUnknownValue);
}

TileFusion::TileState& TileFusion::StateOf(const TileId& tile) {
  const auto [it, created] = tiles_.try_emplace(tile);
  if (created) {
    it->second.fused = EmptyTileGrid(tile);
    it->second.first_seen = ++tiles_created_;
  }
  return it->second;
}

TileFusion::Contribution& TileFusion::ContributionOf(TileState& state, const RobotId& robot) {
  const auto found = state.robots.find(robot);
  if (found != state.robots.end()) return found->second;
  // The smallest slot no other contribution of the tile has.
  std::vector<bool> taken(state.robots.size() + 1, false);
  for (const auto& [other, contribution] : state.robots) {
    if (contribution.slot < static_cast<int>(taken.size())) taken[contribution.slot] = true;
  }
  const int slot = static_cast<int>(std::find(taken.begin(), taken.end(), false) - taken.begin());
  Contribution& contribution = state.robots[robot];
  contribution.slot = slot;
  return contribution;
}

DatedCells TileFusion::Contribution::Dated() const {
  return DatedCells{slot, cells.data().data(), changed_at.data(), known_begin, known_end};
}

std::vector<DatedCells> TileFusion::TrustedCells(const TileState& state) const {
  std::vector<DatedCells> out;
  out.reserve(state.robots.size());
  for (const auto& [robot, contribution] : state.robots) {
    if (Fused(robot)) out.push_back(contribution.Dated());
  }
  return out;
}

const NewestEvidence* TileFusion::FreshEvidence(const TileId& tile, TileState& state) const {
  const std::vector<DatedCells> trusted = TrustedCells(state);
  if (trusted.size() < 2) {
    state.newest.reset();
    state.newest_stale = true;
    return nullptr;
  }
  if (!state.newest) state.newest.emplace(EmptyTileGrid(tile));
  if (state.newest_stale) {
    state.newest->Rebuild(trusted);
    state.newest_stale = false;
  }
  return &*state.newest;
}

uint32_t TileFusion::Deciseconds(Timestamp stamp) const {
  const auto ticks =
      std::chrono::duration_cast<std::chrono::milliseconds>(stamp - epoch_).count() / 100;
  return static_cast<uint32_t>(std::clamp<int64_t>(ticks, 1, std::numeric_limits<uint32_t>::max()));
}

void TileFusion::Contribution::SetCells(grid::OccupancyGrid known) {
  cells = std::move(known);
  const std::vector<int8_t>& values = cells.data();
  const auto is_known = [](int8_t value) { return value != kUnknownValue; };
  const auto first = std::find_if(values.begin(), values.end(), is_known);
  const auto last = std::find_if(values.rbegin(), values.rend(), is_known);
  known_begin = static_cast<size_t>(first - values.begin());
  known_end = first == values.end() ? known_begin : static_cast<size_t>(values.rend() - last);
}

Status TileFusion::UpdateRobotTile(const RobotId& robot, const TileId& tile,
                                   const vector_map::VectorMap& map, Timestamp stamp) {
  FLEETMAP_RETURN_IF_ERROR(options_.CheckTileInRange(tile));
  const grid::OccupancyGrid geometry = EmptyTileGrid(tile);
  FLEETMAP_ASSIGN_OR_RETURN(grid::OccupancyGrid cells,
                            vector_map::Rasterizer().Rasterize(map, geometry));
  TileState& state = StateOf(tile);
  Contribution& contribution = ContributionOf(state, robot);
  const uint32_t now = Deciseconds(stamp);
  // The tile's newest evidence follows the cells that changed, unless it is built again anyway.
  NewestEvidence* newest =
      Fused(robot) && state.newest && !state.newest_stale ? &*state.newest : nullptr;
  const int8_t* values = cells.data().data();
  if (contribution.cells.empty()) {
    contribution.changed_at.assign(static_cast<size_t>(cells.cell_count()), now);
    if (newest != nullptr) {
      for (size_t i = 0; i < contribution.changed_at.size(); ++i) {
        if (values[i] != kUnknownValue) {
          newest->Change(contribution.slot, i, kUnknownValue, 0, values[i], now);
        }
      }
    }
  } else {
    const int8_t* before = contribution.cells.data().data();
    for (size_t i = 0; i < contribution.changed_at.size(); ++i) {
      if (values[i] == before[i]) continue;
      if (newest != nullptr) {
        newest->Change(contribution.slot, i, before[i], contribution.changed_at[i], values[i], now);
      }
      contribution.changed_at[i] = now;
    }
  }
  contribution.SetCells(std::move(cells));
  if (newest != nullptr) newest->Settle(TrustedCells(state));
  contribution.stamp = std::max(contribution.stamp, stamp);
  state.newest_input = std::max(state.newest_input, stamp);
  to_fuse_again_.insert(tile);
  to_review_.insert({tile, robot});
  return Status::Ok();
}

void TileFusion::RemoveRobotTile(const RobotId& robot, const TileId& tile) {
  const auto it = tiles_.find(tile);
  if (it == tiles_.end() || it->second.robots.erase(robot) == 0) return;
  it->second.newest_stale = true;
  to_fuse_again_.insert(tile);
  trust_.ForgetTile(robot, tile);
  to_decide_.insert(robot);
}

std::optional<ContributionEvidence> TileFusion::ExportContribution(const RobotId& robot,
                                                                   const TileId& tile) const {
  const auto state = tiles_.find(tile);
  if (state == tiles_.end()) return std::nullopt;
  const auto it = state->second.robots.find(robot);
  if (it == state->second.robots.end()) return std::nullopt;
  const Contribution& contribution = it->second;
  return ContributionEvidence{contribution.cells.data(), contribution.changed_at,
                              contribution.stamp};
}

Status TileFusion::ImportContribution(const RobotId& robot, const TileId& tile,
                                      ContributionEvidence evidence) {
  FLEETMAP_RETURN_IF_ERROR(options_.CheckTileInRange(tile));
  grid::OccupancyGrid cells = EmptyTileGrid(tile);
  const size_t count = static_cast<size_t>(cells.cell_count());
  if (evidence.cells.size() != count || evidence.changed_at.size() != count) {
    return InvalidArgumentError(
        "evidence of " + robot.value + " for tile (" + std::to_string(tile.x) + ", " +
        std::to_string(tile.y) + ") has " + std::to_string(evidence.cells.size()) + " cells and " +
        std::to_string(evidence.changed_at.size()) + " dates, not " + std::to_string(count));
  }
  for (size_t i = 0; i < count; ++i) {
    const int8_t value = evidence.cells[i];
    if (value != kUnknownValue && value != grid::kFreeValue && value != kOccupiedValue) {
      return InvalidArgumentError("evidence of " + robot.value + " for tile (" +
                                  std::to_string(tile.x) + ", " + std::to_string(tile.y) +
                                  "): cell " + std::to_string(i) + " has value " +
                                  std::to_string(value));
    }
  }
  cells.mutable_data() = std::move(evidence.cells);
  TileState& state = StateOf(tile);
  Contribution& contribution = ContributionOf(state, robot);
  contribution.SetCells(std::move(cells));
  contribution.changed_at = std::move(evidence.changed_at);
  state.newest_stale = true;  // its dates may be anything: fused from scratch
  contribution.stamp = evidence.stamp;
  state.newest_input = std::max(state.newest_input, evidence.stamp);
  to_fuse_again_.insert(tile);
  to_review_.insert({tile, robot});
  return Status::Ok();
}

grid::OccupancyGrid TileFusion::FuseCells(const TileId& tile, const TileState& state,
                                          const Evidence& evidence,
                                          std::vector<uint32_t>* dates) const {
  grid::OccupancyGrid fused = EmptyTileGrid(tile);
  std::vector<uint32_t> own_dates;
  std::vector<uint32_t>& best = dates != nullptr ? *dates : own_dates;
  best.assign(static_cast<size_t>(fused.cell_count()), 0);
  for (const auto& [robot, contribution] : state.robots) {
    if (evidence.without != nullptr && robot == *evidence.without) continue;
    if (!evidence.with_quarantined && !Fused(robot)) continue;
    if (evidence.corroborated_only && !trust_.corroborated(robot)) continue;
    const std::string& source = SourceOf(robot);
    if (evidence.skip_source != nullptr && source == *evidence.skip_source) continue;
    const bool walls_only =
        evidence.walls_only_source != nullptr && source == *evidence.walls_only_source;
    const int8_t* values = contribution.cells.data().data();
    for (size_t i = contribution.known_begin; i < contribution.known_end; ++i) {
      const int8_t value = values[i];
      if (value == kUnknownValue || (walls_only && value != kOccupiedValue)) continue;
      const uint32_t at = contribution.changed_at[i];
      // Newer evidence wins; at equal age an obstacle wins over free space.
      if (at > best[i] || (at == best[i] && value == kOccupiedValue)) {
        best[i] = at;
        fused.mutable_data()[i] = value;
      }
    }
  }
  return fused;
}

bool TileFusion::FuseAgain(const TileId& tile, TileState* state) {
  const int cells = options_.CellsPerTile();
  const NewestEvidence* newest = FreshEvidence(tile, *state);
  grid::OccupancyGrid alone;  // a tile of one trusted contribution keeps no NewestEvidence
  if (newest == nullptr) alone = FuseCells(tile, *state, Evidence{});
  const grid::OccupancyGrid& fused = newest != nullptr ? newest->cells() : alone;
  // Which borders the change reached decides which neighbours must be re-vectorized too.
  int min_x = cells, min_y = cells, max_x = -1, max_y = -1;
  for (int y = 0; y < cells; ++y) {
    for (int x = 0; x < cells; ++x) {
      if (fused.at(x, y) == state->fused.at(x, y)) continue;
      min_x = std::min(min_x, x);
      max_x = std::max(max_x, x);
      min_y = std::min(min_y, y);
      max_y = std::max(max_y, y);
    }
  }
  if (max_x < 0) return false;
  state->fused = fused;
  // Every tile re-vectorized because of this change carries the change's stamp.
  const auto mark = [&](const TileId& id) {
    Timestamp& trigger = to_vectorize_[id];
    trigger = std::max(trigger, state->newest_input);
  };
  mark(tile);
  const int margin = options_.margin_cells + 2;  // the vectorizer looks a little past its rect
  for (const TileId& offset : kNeighbourOffsets) {
    const bool reaches_x = (offset.x < 0 && min_x < margin) ||
                           (offset.x > 0 && max_x >= cells - margin) || offset.x == 0;
    const bool reaches_y = (offset.y < 0 && min_y < margin) ||
                           (offset.y > 0 && max_y >= cells - margin) || offset.y == 0;
    const TileId neighbour{tile.x + offset.x, tile.y + offset.y};
    if (reaches_x && reaches_y && tiles_.count(neighbour) > 0) mark(neighbour);
  }
  return true;
}

StatusOr<vector_map::VectorMap> TileFusion::VectorizeWithContext(const TileId& tile) const {
  const int cells = options_.CellsPerTile();
  const int margin = options_.margin_cells;
  const double resolution = options_.FusedResolution();
  const int side = cells + 2 * margin;
  grid::OccupancyGrid window(side, side, resolution,
                             Pose2{tile.x * options_.tile_size - margin * resolution,
                                   tile.y * options_.tile_size - margin * resolution, 0.0},
                             kUnknownValue);
  // Copy the 3 x 3 block of tiles around `tile` into the window, where they overlap it.
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const auto it = tiles_.find(TileId{tile.x + dx, tile.y + dy});
      if (it == tiles_.end() || it->second.fused.empty()) continue;
      const grid::OccupancyGrid& source = it->second.fused;
      // The source's columns that fall in the window, row by row (this runs for every tile
      // vectorized: cell by cell it was 4 % of the fusion's time).
      const int x_begin = std::max(0, -(margin + dx * cells));
      const int x_end = std::min(cells, side - (margin + dx * cells));
      if (x_begin >= x_end) continue;
      for (int y = 0; y < cells; ++y) {
        const int wy = margin + dy * cells + y;
        if (wy < 0 || wy >= side) continue;
        std::memcpy(&window.at(margin + dx * cells + x_begin, wy),
                    &source.data()[static_cast<size_t>(y) * cells + x_begin],
                    static_cast<size_t>(x_end - x_begin));
      }
    }
  }
  return vectorizer_.VectorizeTile(window, grid::CellRect{margin, margin, cells, cells});
}

const std::string& TileFusion::SourceOf(const RobotId& robot) const {
  const auto it = sources_.find(robot);
  return it == sources_.end() ? robot.value : it->second;
}

void TileFusion::SetRobotSource(const RobotId& robot, std::string source) {
  sources_[robot] = std::move(source);
}

TileFusion::TileReview TileFusion::MakeTileReview(const TileId& tile, TileState& state) const {
  TileReview review;
  review.evidence = FreshEvidence(tile, state);
  if (review.evidence == nullptr) review.alone = FuseCells(tile, state, {}, &review.alone_dates);
  const size_t cells = review.trusted_dates().size();
  for (const auto& [other, contribution] : state.robots) {
    if (Fused(other)) continue;
    if (review.free_first.empty()) {
      review.free_first.assign(cells, 0);
      review.free_second.assign(cells, 0);
      review.free_first_source.assign(cells, nullptr);
    }
    const std::string* source = &SourceOf(other);
    for (size_t i = contribution.known_begin; i < contribution.known_end; ++i) {
      if (contribution.cells.data()[i] != grid::kFreeValue) continue;
      const uint32_t date = contribution.changed_at[i];
      const std::string*& first_source = review.free_first_source[i];
      if (date > review.free_first[i]) {
        if (first_source != nullptr && *first_source != *source) {
          review.free_second[i] = review.free_first[i];
        }
        review.free_first[i] = date;
        first_source = source;
      } else if (date > review.free_second[i] && first_source != nullptr &&
                 *first_source != *source) {
        review.free_second[i] = date;
      }
    }
  }
  return review;
}

bool TileFusion::TakesWholeTrusted(const TileState& state, const RobotId& robot) const {
  const bool walls_only = Fused(robot);
  const bool corroborated = trust_.corroborated(robot);
  const std::string& source = SourceOf(robot);
  for (const auto& [other, contribution] : state.robots) {
    if (other == robot || !Fused(other)) continue;
    if (walls_only && SourceOf(other) == source) return false;
    if (corroborated && !trust_.corroborated(other)) return false;
  }
  return true;
}

TileContradiction TileFusion::CountOn(const TileId& tile, const TileState& state,
                                      const RobotId& robot, const TileReview& review) const {
  const Contribution& mine = state.robots.at(robot);
  const std::string& source = SourceOf(robot);
  // The others' cells. For a robot being fused, robots of its own participant add their walls,
  // never their free space (they cannot confirm its changes). A quarantined robot is not in the
  // trusted cells already, and they serve all the quarantined robots of the tile at once.
  // A corroborated robot is weighed against corroborated robots only (QuarantineOptions).
  const bool corroborated = trust_.corroborated(robot);
  std::vector<uint32_t> own_dates;
  std::optional<grid::OccupancyGrid> others;
  if (Fused(robot) || corroborated) {
    others.emplace();
    if (review.evidence != nullptr && TakesWholeTrusted(state, robot)) {
      // The trusted cells without the robot's: its cells' runners-up.
      review.evidence->Without(mine.slot, TrustedCells(state), &*others, &own_dates);
    } else {
      *others = FuseCells(tile, state,
                          Evidence{.without = &robot,
                                   .walls_only_source = Fused(robot) ? &source : nullptr,
                                   .corroborated_only = corroborated},
                          &own_dates);
    }
  }
  // What quarantined robots of other participants saw free: not fused, but it confirms a change.
  std::vector<uint32_t> confirmed;
  if (!review.free_first.empty()) {
    confirmed.resize(review.free_first.size());
    for (size_t i = 0; i < confirmed.size(); ++i) {
      const std::string* first_source = review.free_first_source[i];
      confirmed[i] = first_source != nullptr && *first_source != source ? review.free_first[i]
                                                                        : review.free_second[i];
    }
  }
  const int tolerance =
      static_cast<int>(std::lround(options_.quarantine.tolerance_m / options_.FusedResolution()));
  const EstablishedCells established =
      others ? EstablishedCells{&*others, &own_dates, &confirmed}
             : EstablishedCells{&review.trusted(), &review.trusted_dates(), &confirmed};
  TileContradiction counted =
      CountContradiction(mine.cells, mine.changed_at, established, tolerance);
  // What robots of other participants say of its walls: whether it is corroborated. Quarantined
  // ones too: two robots that disagree on a shelf still corroborate each other's walls, so which
  // one is weighed against the other does not depend on the order of their reviews. A robot
  // corroborated once stays so (RobotTrust::Corroborate): its agreement is not counted again.
  if (!corroborated) {
    CountAgreement(
        mine.cells,
        FuseCells(tile, state, Evidence{.skip_source = &source, .with_quarantined = true}),
        tolerance, &counted);
  }
  return counted;
}

void TileFusion::StandingChanged(const RobotId& robot) {
  trust_changed_.insert(robot);
  for (auto& [tile, state] : tiles_) {
    if (state.robots.count(robot) == 0) continue;
    to_fuse_again_.insert(tile);
    state.newest_stale = true;  // the robot's evidence joined or left the trusted cells
    // Its evidence joined or left the fleet's: the quarantined robots here are weighed again.
    for (const auto& [other, contribution] : state.robots) {
      if (other != robot && !Fused(other)) to_review_.insert({tile, other});
    }
  }
}

void TileFusion::CorroborationChanged(const RobotId& robot) {
  // What it is weighed against changed, and what the others on its tiles are weighed against
  // (its evidence counts against a corroborated robot now, or no longer does).
  for (const auto& [tile, state] : tiles_) {
    if (state.robots.count(robot) == 0) continue;
    for (const auto& [other, contribution] : state.robots) to_review_.insert({tile, other});
  }
}

void TileFusion::ReviewTrust() {
  if (!options_.quarantine.enabled) {
    to_review_.clear();
    to_decide_.clear();
    return;
  }
  // Changed tiles may confirm (or no longer contradict) a quarantined robot's view there.
  for (const TileId& tile : to_fuse_again_) {
    for (const auto& [robot, contribution] : tiles_.at(tile).robots) {
      if (!Fused(robot)) to_review_.insert({tile, robot});
    }
  }
  // A change of standing changes what the others are weighed against; a few passes settle it
  // (each pass only follows robots whose standing just changed).
  constexpr int kMaxPasses = 6;
  for (int pass = 0; pass < kMaxPasses && !(to_review_.empty() && to_decide_.empty()); ++pass) {
    std::set<RobotId> decide = std::move(to_decide_);
    to_decide_.clear();
    const auto reviews = std::move(to_review_);
    to_review_.clear();
    // One review of each tile per pass, however many robots are weighed on it (a peer's many
    // quarantined ids on one tile cost their number, not its square).
    std::map<TileId, TileReview> tile_reviews;
    for (const auto& [tile, robot] : reviews) {
      const auto state = tiles_.find(tile);
      if (state == tiles_.end() || state->second.robots.count(robot) == 0) {
        trust_.ForgetTile(robot, tile);
      } else {
        auto review = tile_reviews.find(tile);
        if (review == tile_reviews.end()) {
          review = tile_reviews.emplace(tile, MakeTileReview(tile, state->second)).first;
        }
        trust_.Record(robot, tile, CountOn(tile, state->second, robot, review->second));
      }
      decide.insert(robot);
    }
    for (const RobotId& robot : decide) {
      // Newly (un)corroborated, it is weighed against other evidence: counted again, then decided.
      if (trust_.Corroborate(robot)) {
        CorroborationChanged(robot);
        continue;
      }
      if (trust_.Decide(robot)) {
        StandingChanged(robot);
      } else if (trust_.FiguresMoved(robot)) {
        figures_moved_.insert(robot);
      }
    }
  }
  to_review_.clear();
  to_decide_.clear();
}

bool TileFusion::AdmitRobot(const RobotId& robot) {
  const bool was_quarantined = trust_.quarantined(robot);
  if (!trust_.Admit(robot)) return false;
  if (was_quarantined) {
    StandingChanged(robot);
  } else {
    trust_changed_.insert(robot);
  }
  return true;
}

std::vector<TrustReport> TileFusion::TakeTrustChanges() {
  std::vector<TrustReport> out;
  for (const RobotId& robot : trust_changed_) out.push_back(trust_.TakeReport(robot));
  for (const RobotId& robot : figures_moved_) {
    if (trust_changed_.count(robot) > 0 || !trust_.quarantined(robot)) continue;
    TrustReport report = trust_.TakeReport(robot);
    report.standing_changed = false;
    out.push_back(std::move(report));
  }
  trust_changed_.clear();
  figures_moved_.clear();
  return out;
}

void TileFusion::ContinueRevisionsFrom(const std::map<TileId, uint32_t>& revisions) {
  for (const auto& [tile, revision] : revisions) {
    uint32_t& before = revisions_before_[tile];
    before = std::max(before, revision);
  }
}

StatusOr<std::vector<FusedTile>> TileFusion::FuseChanged() {
  ReviewTrust();
  for (const TileId& tile : to_fuse_again_) FuseAgain(tile, &tiles_.at(tile));
  to_fuse_again_.clear();
  std::vector<FusedTile> changed;
  for (const auto& [tile, trigger] : to_vectorize_) {
    FLEETMAP_ASSIGN_OR_RETURN(vector_map::VectorMap map, VectorizeWithContext(tile));
    FusedTile& fused = vector_tiles_[tile];
    if (fused.revision > 0 && SameGeometry(fused.map, map)) continue;
    fused.tile = tile;
    if (fused.revision == 0) {
      const auto before = revisions_before_.find(tile);
      if (before != revisions_before_.end()) fused.revision = before->second;
    }
    ++fused.revision;
    fused.map = std::move(map);
    fused.source_stamp = trigger;
    changed.push_back(fused);
  }
  to_vectorize_.clear();
  return changed;
}

grid::OccupancyGrid TileFusion::FusedGrid(GridWindow* shown, const RobotId* without) const {
  if (tiles_.empty()) {
    if (shown != nullptr) *shown = GridWindow{};
    return grid::OccupancyGrid();
  }
  std::vector<SourcedTile> sourced;
  sourced.reserve(tiles_.size());
  std::map<RobotId, int> robot_numbers;
  for (const auto& [tile, state] : tiles_) {
    SourcedTile& entry = sourced.emplace_back(SourcedTile{tile, {}, state.first_seen});
    for (const auto& [robot, contribution] : state.robots) {
      entry.robots.push_back(
          robot_numbers.emplace(robot, static_cast<int>(robot_numbers.size())).first->second);
    }
  }
  const int cells = options_.CellsPerTile();
  const int64_t cells_per_tile = int64_t{cells} * cells;
  const GridWindow window = ChooseGridWindow(sourced, options_.max_grid_cells / cells_per_tile);
  if (shown != nullptr) *shown = window;
  const TileRect& rect = window.rect;
  grid::OccupancyGrid out(
      static_cast<int>(rect.width() * cells), static_cast<int>(rect.height() * cells),
      options_.FusedResolution(),
      Pose2{rect.min.x * options_.tile_size, rect.min.y * options_.tile_size, 0.0}, kUnknownValue);
  for (const auto& [tile, state] : tiles_) {
    if (state.fused.empty() || !rect.Contains(tile)) continue;
    std::optional<grid::OccupancyGrid> others;  // the tile without `without`, when it is there
    if (without != nullptr && state.robots.count(*without) > 0) {
      others = FuseCells(tile, state, Evidence{.without = without});
    }
    const grid::OccupancyGrid& fused = others ? *others : state.fused;
    const int x0 = static_cast<int>((int64_t{tile.x} - rect.min.x) * cells);
    const int y0 = static_cast<int>((int64_t{tile.y} - rect.min.y) * cells);
    for (int y = 0; y < cells; ++y) {
      std::memcpy(&out.at(x0, y0 + y), &fused.data()[static_cast<size_t>(y) * cells],
                  static_cast<size_t>(cells));
    }
  }
  return out;
}

const FusedTile* TileFusion::FindFusedTile(const TileId& tile) const {
  const auto it = vector_tiles_.find(tile);
  return it == vector_tiles_.end() ? nullptr : &it->second;
}

std::vector<std::pair<RobotId, TileId>> TileFusion::contributions() const {
  std::vector<std::pair<RobotId, TileId>> out;
  for (const auto& [tile, state] : tiles_) {
    for (const auto& [robot, contribution] : state.robots) out.emplace_back(robot, tile);
  }
  return out;
}

size_t TileFusion::contribution_count() const {
  size_t count = 0;
  for (const auto& [tile, state] : tiles_) count += state.robots.size();
  return count;
}

uint64_t TileFusion::SharedEvidenceBytes() const {
  uint64_t bytes = 0;
  for (const auto& [tile, state] : tiles_) {
    if (state.newest) bytes += state.newest->HeldBytes();
  }
  return bytes;
}

}  // namespace fleetmap::fusion
