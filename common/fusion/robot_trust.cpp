#include "common/fusion/robot_trust.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace fleetmap::fusion {

const char* StandingName(Standing standing) {
  switch (standing) {
    case Standing::kTrusted:
      return "trusted";
    case Standing::kQuarantined:
      return "quarantined";
    case Standing::kAdmitted:
      return "admitted";
  }
  return "unknown";
}

RobotTrust::RobotTrust(const QuarantineOptions& options, double tile_size, double resolution)
    : options_(options),
      tile_size_(tile_size),
      resolution_(resolution),
      min_cells_(std::max<int64_t>(1, std::llround(options.min_contradicted_m / resolution))),
      max_cells_(std::max<int64_t>(1, std::llround(options.max_contradicted_m / resolution))) {}

void RobotTrust::Record(const RobotId& robot, const TileId& tile,
                        const TileContradiction& counted) {
  Book& book = books_[robot];
  if (counted.established_seen == 0 && counted.contradicted == 0 && counted.walls_known == 0) {
    book.tiles.erase(tile);
  } else {
    book.tiles[tile] = counted;
  }
}

void RobotTrust::ForgetTile(const RobotId& robot, const TileId& tile) {
  const auto it = books_.find(robot);
  if (it != books_.end()) it->second.tiles.erase(tile);
}

RobotTrust::Totals RobotTrust::TotalsOf(const Book& book) const {
  Totals totals;
  for (const auto& [tile, counted] : book.tiles) {
    totals.contradicted += counted.contradicted;
    totals.established_seen += counted.established_seen;
    totals.walls_known += counted.walls_known;
    totals.walls_confirmed += counted.walls_confirmed;
  }
  return totals;
}

std::string RobotTrust::Describe(const Totals& totals) const {
  const double share = totals.established_seen > 0
                           ? static_cast<double>(totals.contradicted) / totals.established_seen
                           : 0.0;
  return fmt::format(
      "its map calls free {:.1f} m of walls other robots established ({:.0f} % of "
      "the {:.1f} m it sees)",
      totals.contradicted * resolution_, 100.0 * share, totals.established_seen * resolution_);
}

bool RobotTrust::Decide(const RobotId& robot) {
  if (!options_.enabled) return false;
  const auto it = books_.find(robot);
  if (it == books_.end()) return false;
  Book& book = it->second;
  if (book.standing == Standing::kAdmitted) return false;
  const Totals totals = TotalsOf(book);
  const double share = totals.established_seen > 0
                           ? static_cast<double>(totals.contradicted) / totals.established_seen
                           : 0.0;
  if (book.standing == Standing::kTrusted) {
    const bool enters = totals.contradicted >= max_cells_ ||
                        (totals.contradicted >= min_cells_ && share >= options_.enter_share);
    if (!enters) return false;
    book.standing = Standing::kQuarantined;
    book.reason = Describe(totals);
    return true;
  }
  const bool leaves = totals.contradicted < min_cells_ ||
                      (share < options_.leave_share && totals.contradicted < max_cells_);
  if (!leaves) {
    book.reason = Describe(totals);  // the figures move while it waits
    return false;
  }
  book.standing = Standing::kTrusted;
  book.reason = "left quarantine: its map agrees with the fleet again (" + Describe(totals) + ")";
  return true;
}

bool RobotTrust::Corroborate(const RobotId& robot) {
  const auto it = books_.find(robot);
  if (it == books_.end()) return false;
  Book& book = it->second;
  if (book.corroborated) return false;
  const Totals totals = TotalsOf(book);
  book.corroborated = totals.walls_confirmed >= min_cells_ &&
                      static_cast<double>(totals.walls_confirmed) >=
                          options_.corroborate_share * static_cast<double>(totals.walls_known);
  return book.corroborated;
}

bool RobotTrust::corroborated(const RobotId& robot) const {
  const auto it = books_.find(robot);
  return it != books_.end() && it->second.corroborated;
}

bool RobotTrust::Admit(const RobotId& robot) {
  Book& book = books_[robot];
  const bool changed = book.standing != Standing::kAdmitted;
  book.standing = Standing::kAdmitted;
  book.reason = "admitted by an operator";
  return changed;
}

void RobotTrust::Forget(const RobotId& robot) { books_.erase(robot); }

bool RobotTrust::FiguresMoved(const RobotId& robot) const {
  const auto it = books_.find(robot);
  if (it == books_.end() || it->second.standing != Standing::kQuarantined) return false;
  const int64_t reported = it->second.reported_contradicted;
  const int64_t moved = std::abs(TotalsOf(it->second).contradicted - reported);
  return moved >= std::max(min_cells_, reported / 4);
}

TrustReport RobotTrust::TakeReport(const RobotId& robot) {
  TrustReport report = Report(robot);
  if (const auto it = books_.find(robot); it != books_.end()) {
    it->second.reported_contradicted = report.contradicted_cells;
  }
  return report;
}

Standing RobotTrust::standing(const RobotId& robot) const {
  const auto it = books_.find(robot);
  return it == books_.end() ? Standing::kTrusted : it->second.standing;
}

TrustReport RobotTrust::Report(const RobotId& robot) const {
  TrustReport report;
  report.robot = robot;
  const auto it = books_.find(robot);
  if (it == books_.end()) return report;
  const Book& book = it->second;
  const Totals totals = TotalsOf(book);
  report.standing = book.standing;
  report.reason = book.reason;
  report.contradicted_cells = totals.contradicted;
  report.established_seen = totals.established_seen;
  report.contradicted_m = static_cast<double>(totals.contradicted) * resolution_;
  report.share = totals.established_seen > 0
                     ? static_cast<double>(totals.contradicted) / totals.established_seen
                     : 0.0;
  bool first = true;
  for (const auto& [tile, counted] : book.tiles) {
    if (!counted.any()) continue;
    const Point2 origin(tile.x * tile_size_, tile.y * tile_size_);
    const Point2 lo = origin + resolution_ * Point2(counted.min_x, counted.min_y);
    const Point2 hi = origin + resolution_ * Point2(counted.max_x + 1, counted.max_y + 1);
    report.area_min = first ? lo : Point2(report.area_min.cwiseMin(lo));
    report.area_max = first ? hi : Point2(report.area_max.cwiseMax(hi));
    first = false;
  }
  return report;
}

std::vector<RobotId> RobotTrust::quarantined_robots() const {
  std::vector<RobotId> out;
  for (const auto& [robot, book] : books_) {
    if (book.standing == Standing::kQuarantined) out.push_back(robot);
  }
  return out;
}

}  // namespace fleetmap::fusion
