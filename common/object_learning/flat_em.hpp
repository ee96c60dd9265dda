#pragma once

// One run of the flat model (Biswas, Limketkai, Sanner and Thrun, IROS 2002): objects only, no
// template level. The same E-step (mutual exclusion), alignment step, annealing of sigma and
// random start as hierarchical EM; the M-step makes each object the weighted mean of its aligned
// snapshots. Its log joint is the data term alone (no object level).
//
// Thread-safety: stateless; runs may go concurrently.

#include <cstdint>
#include <functional>

#include "common/object_learning/em_problem.hpp"
#include "common/object_learning/learn_options.hpp"

namespace fleetmap::object_learning {

// Requires N >= problem.max_per_map() and N <= number of snapshots.
// `on_iteration`, when set, is called after each EM iteration with the iterations done.
EmResult RunFlatEm(const EmProblem& problem, int num_objects, const EmOptions& options,
                   uint64_t seed, const std::function<void(int)>& on_iteration = {});

}  // namespace fleetmap::object_learning
