// Hierarchical and flat EM on simulated mapping sessions: two chairs, a bin and a box in a lab,
// mapped 9 times by the exploring robot with the objects moved in between.

#include "common/object_learning/hierarchical_em.hpp"

#include <gtest/gtest.h>

#include <map>

#include "common/object_learning/em_problem.hpp"
#include "common/object_learning/flat_em.hpp"
#include "common/object_learning/model_selection.hpp"
#include "common/object_learning/snapshot_extractor.hpp"
#include "common/sim/mapping_sessions.hpp"
#include "common/sim/terrain_rasterizer.hpp"

namespace fleetmap::object_learning {
namespace {

struct Sessions {
  SnapshotSet snapshots;
  std::vector<int> snapshot_class;  // true shape of each snapshot's object (-1: none)
};

Sessions Simulate(uint32_t seed) {
  const sim::Terrain lab = sim::LabTerrain(10.0);
  const StatusOr<grid::OccupancyGrid> truth = sim::RasterizeTerrain(lab, 0.05);
  EXPECT_TRUE(truth.ok());
  sim::SessionPlanOptions plan_options;
  plan_options.seed = seed;
  const auto plan = sim::PlanSessions(*truth, lab.start, plan_options);
  EXPECT_TRUE(plan.ok()) << plan.status();
  sim::MappingSessionOptions mapping;
  mapping.exploration.seed = seed * 1000u;
  const auto sessions = sim::MapSessions(lab, *plan, mapping);
  EXPECT_TRUE(sessions.ok()) << sessions.status();
  std::vector<grid::OccupancyGrid> maps;
  for (const sim::MappedSession& s : *sessions) maps.push_back(s.map);
  Sessions out;
  StatusOr<SnapshotSet> set = ExtractSnapshots(maps, SnapshotOptions{});
  EXPECT_TRUE(set.ok()) << set.status();
  out.snapshots = std::move(*set);
  for (const Snapshot& snapshot : out.snapshots.snapshots) {
    int shape = -1;
    for (const sim::MovableObject& o : (*sessions)[snapshot.map_index].objects) {
      if ((o.pose.translation() - snapshot.centre).norm() <
          sim::MovableShapeRadius(o.shape) + 0.25) {
        shape = static_cast<int>(o.shape);
      }
    }
    out.snapshot_class.push_back(shape);
  }
  return out;
}

// Each learned object holds snapshots of one shape, and there are 2 chair objects, 1 bin, 1 box.
bool GoodObjects(const Sessions& data, const std::vector<int>& snapshot_object,
                 std::map<int, int>* object_class) {
  for (size_t s = 0; s < snapshot_object.size(); ++s) {
    if (data.snapshot_class[s] < 0) continue;
    const auto [it, inserted] = object_class->emplace(snapshot_object[s], data.snapshot_class[s]);
    if (it->second != data.snapshot_class[s]) return false;
  }
  std::map<int, int> count;
  for (const auto& [object, c] : *object_class) ++count[c];
  return count == std::map<int, int>{{0, 2}, {1, 1}, {2, 1}};
}

TEST(HierarchicalEmTest, RecoversFourObjectsAndThreeTemplatesOnSimulatedSessions) {
  const Sessions data = Simulate(1);
  ASSERT_GE(data.snapshots.snapshots.size(), 18u);
  for (int c : data.snapshot_class) EXPECT_GE(c, 0);  // no spurious snapshot
  const EmProblem problem = MakeEmProblem(data.snapshots);
  LearnOptions options;
  options.restarts = 3;
  const EmResult r = BestOfRestarts(problem, 4, 3, options);
  std::map<int, int> object_class;
  ASSERT_TRUE(GoodObjects(data, r.snapshot_object, &object_class));
  // The two chair objects share a template; the bin and the box have one each.
  std::map<int, int> template_class;
  for (const auto& [object, c] : object_class) {
    const auto [it, inserted] = template_class.emplace(r.object_template[object], c);
    EXPECT_EQ(it->second, c) << "template " << r.object_template[object] << " mixes shapes";
  }
  EXPECT_EQ(template_class.size(), 3u);
  // Mutual exclusion in the MAP assignment: no object twice in one map.
  for (const std::vector<int>& map : problem.maps) {
    for (size_t i = 0; i < map.size(); ++i) {
      for (size_t j = i + 1; j < map.size(); ++j) {
        EXPECT_NE(r.snapshot_object[map[i]], r.snapshot_object[map[j]]);
      }
    }
  }
}

TEST(HierarchicalEmTest, SameSeedSameModel) {
  const Sessions data = Simulate(2);
  const EmProblem problem = MakeEmProblem(data.snapshots);
  const EmResult a = RunHierarchicalEm(problem, 4, 3, EmOptions{}, 77);
  const EmResult b = RunHierarchicalEm(problem, 4, 3, EmOptions{}, 77);
  EXPECT_EQ(a.log_likelihood, b.log_likelihood);
  EXPECT_EQ(a.snapshot_object, b.snapshot_object);
  EXPECT_TRUE(a.objects == b.objects);
  const EmResult flat = RunFlatEm(problem, 4, EmOptions{}, 77);
  EXPECT_EQ(flat.templates.rows(), 0);
  EXPECT_EQ(flat.snapshot_object.size(), problem.snapshots.size());
}

}  // namespace
}  // namespace fleetmap::object_learning
