#include "common/vector_map/cell_frame.hpp"

namespace fleetmap::vector_map {

CellFrame::CellFrame(double resolution, const Pose2& origin)
    : resolution_(resolution),
      map_from_grid_(origin.ToTransform()),
      grid_from_map_(origin.ToTransform().inverse()) {}

}  // namespace fleetmap::vector_map
