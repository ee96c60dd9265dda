#pragma once

// The learner's memory, estimated before each stage, and the steps that bring it under
// LearnOptions::memory_budget_mb (issue 22). The estimates count the learner's own tables, which
// since issue 22 grow linearly: extraction in maps x map cells, learning in snapshots x patch
// cells plus objects x patch cells (aligned snapshots are streamed pair by pair, never held as a
// snapshots x objects x cells table), plus the exact E-step's 2^K subset table per object.
// They count the learner's own tables, not the caller's maps nor the process around it: on the
// real-plan benchmark (4 maps of 800 x 544 cells, 160 snapshots) the estimate is 7 MB, and
// `fleetmap learn-objects` peaks at 73 MB, of which the program itself and its maps take about
// 60 MB (docs/results.md).
//
// Thread-safety: stateless.

#include <cstdint>

#include "common/object_learning/snapshot_extractor.hpp"

namespace fleetmap::object_learning {

// Bytes of differencing `maps` maps of `map_cells` cells each.
double ExtractionBytes(int maps, int64_t map_cells);

// Bytes of learning from `snapshots` patches of `patch_cells` cells with up to `max_objects`
// objects (and as many templates), the exact E-step up to `exact_snapshots` snapshots per map
// (its table has 2^K entries per object; `per_map` is the largest K).
double LearningBytes(int snapshots, int64_t patch_cells, int max_objects, int per_map,
                     int exact_snapshots);

// Coarsens every snapshot patch by 2 (cell side doubled, values and weights low-pass filtered
// with a [1 2 1] / 4 kernel before the decimation), keeping each patch's centre cell on the same
// map point: a quarter of the cells, at the price of coarser alignment.
void CoarsenSnapshots(SnapshotSet* set);

}  // namespace fleetmap::object_learning
