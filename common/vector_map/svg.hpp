#pragma once

// SVG picture of a vector map (for docs and eyeballing): free space filled light grey (holes cut
// with the even-odd rule), obstacle polylines stroked dark, optionally vertices as dots. The map
// frame's y axis points up, so the drawing flips y.

#include <string>

#include "common/vector_map/vector_map.hpp"

namespace fleetmap::vector_map {

struct SvgOptions {
  double pixels_per_metre = 20.0;
  double stroke_width_px = 1.5;
  bool draw_vertices = false;
};

std::string ToSvg(const VectorMap& map, const SvgOptions& options = {});

}  // namespace fleetmap::vector_map
