#pragma once

// The rigid alignment that maps one patch (scene::Patch: snapshots, objects and templates, all of
// one common size, centred on the patch centre) onto another.

#include "common/scene/patch.hpp"

namespace fleetmap::object_learning {

// A rigid transform of a patch about its centre: rotate by dphi, then shift by (dx, dy).
struct Alignment {
  double dx = 0.0;    // metres
  double dy = 0.0;    // metres
  double dphi = 0.0;  // radians, counter-clockwise
};

}  // namespace fleetmap::object_learning
