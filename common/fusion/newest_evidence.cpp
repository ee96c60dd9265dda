#include "common/fusion/newest_evidence.hpp"

#include <algorithm>
#include <utility>

#include "common/core/check.hpp"

namespace fleetmap::fusion {

NewestEvidence::NewestEvidence(grid::OccupancyGrid empty)
    : cells_(std::move(empty)),
      dates_(cells_.data().size(), 0),
      holders_(cells_.data().size(), 0),
      runner_up_values_(cells_.data().size(), grid::kUnknownValue),
      runner_up_dates_(cells_.data().size(), 0) {
  std::fill(cells_.mutable_data().begin(), cells_.mutable_data().end(), grid::kUnknownValue);
}

size_t NewestEvidence::HeldBytes() const {
  return cells_.data().capacity() + dates_.capacity() * sizeof(uint32_t) + holders_.capacity() +
         runner_up_values_.capacity() + runner_up_dates_.capacity() * sizeof(uint32_t) +
         to_settle_.capacity() * sizeof(size_t);
}

void NewestEvidence::Set(size_t i, const Fused& fused) {
  cells_.mutable_data()[i] = ValueOf(fused.best);
  dates_[i] = DateOf(fused.best);
  holders_[i] = fused.best == 0 ? 0 : fused.holder;
  runner_up_values_[i] = ValueOf(fused.runner_up);
  runner_up_dates_[i] = DateOf(fused.runner_up);
}

void NewestEvidence::Rebuild(const std::vector<DatedCells>& contributions) {
  const size_t count = dates_.size();
  // Contribution by contribution, each over its known span: the reads stay sequential.
  std::vector<Fused> fused(count);
  for (const DatedCells& contribution : contributions) {
    FLEETMAP_CHECK(contribution.end <= count, "NewestEvidence: a contribution past the tile");
    const uint8_t holder = HolderOf(contribution.slot);
    for (size_t i = contribution.begin; i < contribution.end; ++i) {
      fused[i].Take(Key(contribution.values[i], contribution.dates[i]), holder);
    }
  }
  for (size_t i = 0; i < count; ++i) Set(i, fused[i]);
  to_settle_.clear();
}

void NewestEvidence::Change(int slot, size_t i, int8_t old_value, uint32_t old_date, int8_t value,
                            uint32_t date) {
  const uint64_t key = Key(value, date);
  const uint64_t best = BestKey(i);
  const uint64_t runner_up = RunnerUpKey(i);
  const uint8_t mark = HolderOf(slot);
  if (best != 0 && holders_[i] == mark) {
    // The holder (or, past kSharedHolder, maybe not: fused again to be sure).
    if (mark == kSharedHolder || key < runner_up) {
      to_settle_.push_back(i);
    } else {
      cells_.mutable_data()[i] = ValueOf(key);
      dates_[i] = DateOf(key);
    }
    return;
  }
  if (key > best) {
    // The old holder's evidence is the others' newest now.
    runner_up_values_[i] = ValueOf(best);
    runner_up_dates_[i] = DateOf(best);
    cells_.mutable_data()[i] = ValueOf(key);
    dates_[i] = DateOf(key);
    holders_[i] = mark;
  } else if (key >= runner_up) {
    runner_up_values_[i] = ValueOf(key);
    runner_up_dates_[i] = DateOf(key);
  } else if (Key(old_value, old_date) == runner_up) {
    // It was the runner-up and says less now: another may be, or none.
    to_settle_.push_back(i);
  }
}

std::vector<NewestEvidence::Fused> NewestEvidence::FuseAgain(
    const std::vector<size_t>& cells, const std::vector<DatedCells>& contributions, int skip) {
  std::vector<Fused> fused(cells.size());
  for (const DatedCells& contribution : contributions) {
    if (contribution.slot == skip) continue;
    const uint8_t holder = HolderOf(contribution.slot);
    const auto first = std::lower_bound(cells.begin(), cells.end(), contribution.begin);
    const auto last = std::lower_bound(first, cells.end(), contribution.end);
    for (auto it = first; it != last; ++it) {
      fused[static_cast<size_t>(it - cells.begin())].Take(
          Key(contribution.values[*it], contribution.dates[*it]), holder);
    }
  }
  return fused;
}

void NewestEvidence::Settle(const std::vector<DatedCells>& contributions) {
  if (to_settle_.empty()) return;
  std::sort(to_settle_.begin(), to_settle_.end());
  to_settle_.erase(std::unique(to_settle_.begin(), to_settle_.end()), to_settle_.end());
  const std::vector<Fused> fused = FuseAgain(to_settle_, contributions, -1);
  for (size_t k = 0; k < to_settle_.size(); ++k) Set(to_settle_[k], fused[k]);
  to_settle_.clear();
}

void NewestEvidence::Without(int slot, const std::vector<DatedCells>& contributions,
                             grid::OccupancyGrid* cells, std::vector<uint32_t>* dates) const {
  *cells = cells_;
  *dates = dates_;
  // Elsewhere another contribution holds the cell's newest evidence: leaving `slot` out changes
  // nothing there. Where it holds it, the runner-up is what the others say.
  const uint8_t mark = HolderOf(slot);
  const int8_t* fused = cells_.data().data();
  int8_t* values = cells->mutable_data().data();
  std::vector<size_t> shared;  // held by a shared mark: fused again without `slot`
  for (size_t i = 0; i < holders_.size(); ++i) {
    if (holders_[i] != mark || fused[i] == grid::kUnknownValue) continue;
    if (mark == kSharedHolder) {
      shared.push_back(i);
      continue;
    }
    values[i] = runner_up_values_[i];
    (*dates)[i] = runner_up_dates_[i];
  }
  if (shared.empty()) return;
  const std::vector<Fused> again = FuseAgain(shared, contributions, slot);
  for (size_t k = 0; k < shared.size(); ++k) {
    values[shared[k]] = ValueOf(again[k].best);
    (*dates)[shared[k]] = DateOf(again[k].best);
  }
}

}  // namespace fleetmap::fusion
