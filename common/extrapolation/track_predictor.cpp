#include "common/extrapolation/track_predictor.hpp"

#include <algorithm>
#include <cmath>

namespace fleetmap::extrapolation {
namespace {

// Least-squares velocity (m/s) of the points whose stamps lie within `window` of `points[anchor]`,
// taken from the anchor's end of the track; zero if they span no time.
Vector2 FitVelocity(const std::vector<scene::TrackPoint>& points, bool at_end, double window) {
  const double t0 = at_end ? points.back().stamp : points.front().stamp;
  double st = 0, stt = 0;
  Vector2 sp = Vector2::Zero(), stp = Vector2::Zero();
  int n = 0;
  for (const scene::TrackPoint& p : points) {
    if (std::abs(p.stamp - t0) > window) continue;
    const double t = p.stamp - t0;
    st += t;
    stt += t * t;
    sp += p.position;
    stp += t * p.position;
    ++n;
  }
  if (n < 2) {
    // The window holds one point: use the nearest pair.
    const scene::TrackPoint& a = at_end ? points[points.size() - 2] : points[0];
    const scene::TrackPoint& b = at_end ? points.back() : points[1];
    return (b.position - a.position) / (b.stamp - a.stamp);
  }
  const double denominator = n * stt - st * st;
  if (denominator <= 1e-12) return Vector2::Zero();
  return (n * stp - st * sp) / denominator;
}

void AppendSegment(const Point2& a, const Point2& b, double heading, bool predicted, double spacing,
                   std::vector<SweptPose>* out) {
  const double length = (b - a).norm();
  // Bounded: a segment never has more than 100 000 poses (a 10 km segment at 0.1 m).
  const int steps = static_cast<int>(std::clamp(std::ceil(length / spacing), 1.0, 100000.0));
  for (int i = 0; i < steps; ++i) {
    const double f = static_cast<double>(i) / steps;
    out->push_back({a + f * (b - a), heading, predicted});
  }
}

double LimitSpeed(Vector2* velocity, double max_speed) {
  const double speed = velocity->norm();
  if (speed > max_speed) *velocity *= max_speed / speed;
  return std::atan2(velocity->y(), velocity->x());
}

}  // namespace

std::vector<SweptPose> SweepTrack(const scene::PersonTrack& track,
                                  const TrackPredictorOptions& options) {
  std::vector<SweptPose> out;
  const std::vector<scene::TrackPoint>& points = track.points;
  if (points.size() < 2) return out;
  const double spacing = std::max(1e-3, options.sample_spacing);
  constexpr double kStill = 0.05;  // m/s: slower is standing still, nothing to extrapolate

  if (track.entered_view) {
    Vector2 velocity = FitVelocity(points, false, options.fit_window);
    const double heading = LimitSpeed(&velocity, options.max_speed);
    if (velocity.norm() > kStill) {
      const Point2 start = points.front().position - options.horizon * velocity;
      AppendSegment(start, points.front().position, heading, true, spacing, &out);
    }
  }
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    AppendSegment(points[i].position, points[i + 1].position, points[i].heading, false, spacing,
                  &out);
  }
  out.push_back({points.back().position, points.back().heading, false});
  if (track.left_view) {
    Vector2 velocity = FitVelocity(points, true, options.fit_window);
    const double heading = LimitSpeed(&velocity, options.max_speed);
    if (velocity.norm() > kStill) {
      const Point2 end = points.back().position + options.horizon * velocity;
      std::vector<SweptPose> forward;
      AppendSegment(points.back().position, end, heading, true, spacing, &forward);
      out.insert(out.end(), forward.begin() + 1, forward.end());
      out.push_back({end, heading, true});
    }
  }
  return out;
}

}  // namespace fleetmap::extrapolation
