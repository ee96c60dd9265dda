#pragma once

// The CDR shapes of the wire types (see cdr_shape.hpp), one per .idl struct, in field order.
// Internal to transport. tests/unit/transport/idl_shapes_test.cpp checks each against the bytes
// fastcdr writes for a filled sample, so a changed .idl without a changed shape fails the build's
// tests.

#include "common/transport/internal/cdr_shape.hpp"

namespace fleetmap::transport {

const CdrShape& OccupancyGridShape();
const CdrShape& OccupancyGridUpdateShape();
const CdrShape& CompressedGridUpdateShape();
const CdrShape& RobotStatusShape();
const CdrShape& VectorTileShape();
const CdrShape& VectorMapShape();
// The first field of a VectorMap alone: the format string every .vmap version starts with, read
// before the rest so that a file of another version is named as such.
const CdrShape& VmapFormatShape();
const CdrShape& EntityShape();
const CdrShape& SubmapShape();
const CdrShape& ObjectTemplateShape();
const CdrShape& ObjectModelShape();
const CdrShape& RobotFrameShape();
const CdrShape& RobotAdmissionShape();
const CdrShape& FleetServerShape();
const CdrShape& RouteGraphShape();
const CdrShape& TfMessageShape();

}  // namespace fleetmap::transport
