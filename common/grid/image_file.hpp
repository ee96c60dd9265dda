#pragma once

// Pictures written with OpenCV's encoders, whole or not at all.

#include <opencv2/core.hpp>
#include <string>

#include "common/core/status.hpp"

namespace fleetmap::grid {

// Encodes `image` in the format the extension of `path` names (".png", ".pgm"...), with the same
// encoder and defaults as cv::imwrite, and writes it with WriteFileAtomically. Errors name the
// path: kInvalidArgument when OpenCV cannot encode the image in that format, kUnavailable when the
// file cannot be written ("<path>: cannot write: <reason>").
Status WriteImageFile(const std::string& path, const cv::Mat& image);

}  // namespace fleetmap::grid
