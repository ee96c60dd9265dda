#include "common/gis/georeference.hpp"

#include <proj.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "common/core/number_format.hpp"

namespace fleetmap::gis {
namespace {

Status CheckDegrees(const char* name, double value, double limit) {
  if (!std::isfinite(value)) {
    return InvalidArgumentError(std::string(name) + " " + ExactNumber(value) +
                                " is not a finite number of degrees");
  }
  if (value < -limit || value > limit) {
    return InvalidArgumentError(std::string(name) + " " + ExactNumber(value) + " is outside [" +
                                ExactNumber(-limit) + ", " + ExactNumber(limit) + "] degrees");
  }
  return Status::Ok();
}

// cos and sin of `degrees`, exact for quarter turns (a yaw of 90 gives 0 and 1, not 6.1e-17 and
// 1), so the pipeline a person reads says what they gave.
std::pair<double, double> CosSinDegrees(double degrees) {
  const double turn = std::fmod(degrees, 360.0);
  if (turn == 0.0) return {1.0, 0.0};
  if (turn == 90.0 || turn == -270.0) return {0.0, 1.0};
  if (turn == 180.0 || turn == -180.0) return {-1.0, 0.0};
  if (turn == 270.0 || turn == -90.0) return {0.0, -1.0};
  const double radians = turn * std::numbers::pi / 180.0;
  return {std::cos(radians), std::sin(radians)};
}

// A number for the pipeline string: the shortest decimal that reads back as it, never "-0".
std::string ProjNumber(double value) { return ExactNumber(value + 0.0); }

// Frame metres -> east / north metres (a rotation by the yaw: PROJ's affine step computes
// x' = s11 x + s12 y, y' = s21 x + s22 y) -> the inverse of the azimuthal equidistant projection
// centred on the origin (geographic radians) -> degrees, longitude first.
std::string PipelineOf(const GeoOrigin& origin) {
  const auto [c, s] = CosSinDegrees(origin.yaw);
  return "+proj=pipeline +step +proj=affine +s11=" + ProjNumber(c) + " +s12=" + ProjNumber(-s) +
         " +s21=" + ProjNumber(s) + " +s22=" + ProjNumber(c) +
         " +step +inv +proj=aeqd +lat_0=" + ProjNumber(origin.latitude) +
         " +lon_0=" + ProjNumber(origin.longitude) +
         " +ellps=WGS84 +step +proj=unitconvert +xy_in=rad +xy_out=deg";
}

}  // namespace

Status GeoOrigin::Validate() const {
  FLEETMAP_RETURN_IF_ERROR(CheckDegrees("latitude", latitude, 90.0));
  FLEETMAP_RETURN_IF_ERROR(CheckDegrees("longitude", longitude, 180.0));
  if (!std::isfinite(yaw)) {
    return InvalidArgumentError("yaw " + ExactNumber(yaw) + " is not a finite number of degrees");
  }
  return Status::Ok();
}

// A PROJ context of our own (so the object may move to another thread) and the pipeline in it.
struct Georeference::Proj {
  struct ContextDeleter {
    void operator()(PJ_CONTEXT* context) const { proj_context_destroy(context); }
  };
  struct PjDeleter {
    void operator()(PJ* pj) const { proj_destroy(pj); }
  };
  std::unique_ptr<PJ_CONTEXT, ContextDeleter> context;
  std::unique_ptr<PJ, PjDeleter> pipeline;  // declared after the context: destroyed before it
};

StatusOr<Georeference> Georeference::Create(const GeoOrigin& origin) {
  FLEETMAP_RETURN_IF_ERROR(origin.Validate());
  auto proj = std::make_unique<Proj>();
  proj->context.reset(proj_context_create());
  if (proj->context == nullptr) return InternalError("PROJ: cannot create a context");
  // Failures come back as Status values; PROJ's own log would print them a second time.
  proj_log_level(proj->context.get(), PJ_LOG_NONE);
  std::string pipeline = PipelineOf(origin);
  proj->pipeline.reset(proj_create(proj->context.get(), pipeline.c_str()));
  if (proj->pipeline == nullptr) {
    const int error = proj_context_errno(proj->context.get());
    return InternalError("PROJ cannot make " + pipeline + ": " +
                         proj_context_errno_string(proj->context.get(), error));
  }
  return Georeference(origin, std::move(pipeline), std::move(proj));
}

Georeference::Georeference(const GeoOrigin& origin, std::string pipeline,
                           std::unique_ptr<Proj> proj)
    : origin_(origin), pipeline_(std::move(pipeline)), proj_(std::move(proj)) {}

Georeference::Georeference(Georeference&&) noexcept = default;
Georeference& Georeference::operator=(Georeference&&) noexcept = default;
Georeference::~Georeference() = default;

StatusOr<LonLat> Georeference::ToLonLat(const Point2& p_frame) const {
  if (!(p_frame.norm() <= kMaxGeoreferencedDistance)) {  // NaN too
    return InvalidArgumentError("the point (" + FixedNumber(p_frame.x(), 3) + ", " +
                                FixedNumber(p_frame.y(), 3) + ") m of the frame is farther than " +
                                ExactNumber(kMaxGeoreferencedDistance / 1000.0) +
                                " km from the georeferenced origin");
  }
  PJ* pipeline = proj_->pipeline.get();
  proj_errno_reset(pipeline);
  const PJ_COORD out = proj_trans(pipeline, PJ_FWD, proj_coord(p_frame.x(), p_frame.y(), 0, 0));
  if (proj_errno(pipeline) != 0 || !std::isfinite(out.xy.x) || !std::isfinite(out.xy.y)) {
    const int error = proj_errno(pipeline);
    return InvalidArgumentError(
        "the point (" + FixedNumber(p_frame.x(), 3) + ", " + FixedNumber(p_frame.y(), 3) +
        ") m of the frame has no place on Earth from the origin (" + ExactNumber(origin_.latitude) +
        ", " + ExactNumber(origin_.longitude) + "): " +
        (error != 0 ? proj_context_errno_string(proj_->context.get(), error) : "not finite"));
  }
  // unitconvert gives degrees in x (longitude) and y (latitude).
  return LonLat{out.xy.x, out.xy.y};
}

}  // namespace fleetmap::gis
