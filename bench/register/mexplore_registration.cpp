#include "bench/register/mexplore_registration.hpp"

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/stitching/detail/matchers.hpp>
#include <opencv2/stitching/detail/motion_estimators.hpp>
#include <vector>

namespace fleetmap::bench {
namespace {

// m-explore hands the grid's int8 cells to OpenCV as they are: -1 reads as 255.
cv::Mat GridImage(const grid::OccupancyGrid& map) {
  cv::Mat image(map.height(), map.width(), CV_8U);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      image.at<uint8_t>(y, x) = static_cast<uint8_t>(map.at(x, y));
    }
  }
  return image;
}

// Pixel (u, v) of a grid image is cell (u, v), whose centre is ((u + 0.5) r, (v + 0.5) r) in the
// grid's frame (the origin's).
Eigen::Affine2d GridFromPixel(double resolution) {
  Eigen::Affine2d t = Eigen::Affine2d::Identity();
  t.scale(resolution);
  t.translate(Point2(0.5, 0.5));
  return t;
}

// The pipeline; OpenCV may throw.
MexploreRegistration Estimate(const grid::OccupancyGrid& a, const grid::OccupancyGrid& b,
                              const MexploreOptions& options) {
  MexploreRegistration result;
  const std::vector<cv::Mat> images{GridImage(a), GridImage(b)};
  std::vector<cv::detail::ImageFeatures> features(images.size());
  const cv::Ptr<cv::Feature2D> finder = cv::AKAZE::create();
  for (size_t i = 0; i < images.size(); ++i) {
    cv::detail::computeImageFeatures(finder, images[i], features[i]);
    features[i].img_idx = static_cast<int>(i);
  }
  std::vector<cv::detail::MatchesInfo> pairwise;
  cv::detail::AffineBestOf2NearestMatcher matcher;
  matcher(features, pairwise);
  matcher.collectGarbage();
  for (const cv::detail::MatchesInfo& m : pairwise) {
    if (m.src_img_idx == 0 && m.dst_img_idx == 1) result.match_confidence = m.confidence;
  }
  const std::vector<int> kept =
      cv::detail::leaveBiggestComponent(features, pairwise, static_cast<float>(options.confidence));
  if (kept.size() < 2) return result;

  std::vector<cv::detail::CameraParams> cameras;
  cv::detail::AffineBasedEstimator estimator;
  if (!estimator(features, pairwise, cameras)) return result;
  for (cv::detail::CameraParams& camera : cameras) camera.R.convertTo(camera.R, CV_32F);
  cv::detail::BundleAdjusterAffinePartial adjuster;
  adjuster.setConfThresh(options.confidence);
  if (!adjuster(features, pairwise, cameras)) return result;

  // Each camera's R takes the common (reference image's) pixels into its image's pixels: the
  // estimator chains R_to = R_from * H(from -> to) from the reference, and m-explore's warper
  // places an image by R's inverse.
  cv::Mat r_a, r_b;
  cameras[0].R.convertTo(r_a, CV_64F);
  cameras[1].R.convertTo(r_b, CV_64F);
  const cv::Mat pixel_a_from_b = r_a * r_b.inv();
  if (!cv::checkRange(pixel_a_from_b)) return result;
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m(r, c) = pixel_a_from_b.at<double>(r, c);
  }
  const double yaw = std::atan2(m(1, 0), m(0, 0));
  result.scale = std::hypot(m(0, 0), m(1, 0));
  if (!(result.scale > 0.0)) return result;
  // The rigid transform that agrees with the similarity at B's known centroid.
  Eigen::Affine2d similarity;
  similarity.matrix() = m;
  const Eigen::Affine2d grid_a_from_b =
      GridFromPixel(a.resolution()) * similarity * GridFromPixel(b.resolution()).inverse();
  const Transform2 map_a_from_grid_a = a.origin().ToTransform();
  const Transform2 map_b_from_grid_b = b.origin().ToTransform();
  Point2 centroid_grid_b(0, 0);
  int n = 0;
  for (int y = 0; y < b.height(); ++y) {
    for (int x = 0; x < b.width(); ++x) {
      if (b.StateAt(x, y) == grid::CellState::kUnknown) continue;
      centroid_grid_b += Point2((x + 0.5) * b.resolution(), (y + 0.5) * b.resolution());
      ++n;
    }
  }
  if (n > 0) centroid_grid_b /= n;
  const Point2 target = grid_a_from_b * centroid_grid_b;  // the similarity at the centroid
  Transform2 rigid = Transform2::Identity();
  rigid.translate(target);
  rigid.rotate(yaw);
  rigid.translate(-centroid_grid_b);
  result.a_from_b = Pose2::FromTransform(map_a_from_grid_a * rigid * map_b_from_grid_b.inverse());
  result.found = true;
  return result;
}

}  // namespace

MexploreRegistration RegisterLikeMexplore(const grid::OccupancyGrid& a,
                                          const grid::OccupancyGrid& b,
                                          const MexploreOptions& options) {
  // OpenCV asserts (throws) when a grid yields too few features to match (FLANN's k nearest of
  // fewer than k); m-explore would then merge nothing, so that is "not found".
  try {
    return Estimate(a, b, options);
  } catch (const cv::Exception&) {
    return {};
  }
}

}  // namespace fleetmap::bench
