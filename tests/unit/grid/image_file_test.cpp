#include "common/grid/image_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "tests/scratch_dir.hpp"

namespace fleetmap::grid {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

cv::Mat Gradient(int type) {
  cv::Mat image(7, 5, type);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      if (type == CV_8UC1) {
        image.at<uint8_t>(y, x) = static_cast<uint8_t>(30 * y + x);
      } else {
        image.at<cv::Vec3b>(y, x) = cv::Vec3b(30 * y, 40 * x, 7);
      }
    }
  }
  return image;
}

// Callers moved from cv::imwrite: the files must stay the same byte for byte.
TEST(ImageFileTest, WritesWhatImwriteWrites) {
  const testing::ScratchDir dir("image_file");
  for (const auto& [name, type] : {std::pair<std::string, int>{"grey.png", CV_8UC1},
                                   {"colour.png", CV_8UC3},
                                   {"grey.pgm", CV_8UC1}}) {
    const cv::Mat image = Gradient(type);
    ASSERT_TRUE(cv::imwrite(dir.Path("imwrite_" + name), image));
    const Status status = WriteImageFile(dir.Path(name), image);
    ASSERT_TRUE(status.ok()) << status;
    EXPECT_EQ(testing::ReadFile(dir.Path(name)), testing::ReadFile(dir.Path("imwrite_" + name)))
        << name;
  }
}

TEST(ImageFileTest, ErrorsNameThePath) {
  const testing::ScratchDir dir("image_file");
  const std::string unknown = dir.Path("picture.unknown");
  const Status encode = WriteImageFile(unknown, Gradient(CV_8UC1));
  EXPECT_EQ(encode.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(encode.message(), HasSubstr(unknown + ": cannot encode"));
  EXPECT_FALSE(fs::exists(unknown));

  const std::string missing = dir.Path("no_such_dir/x.png");
  const Status write = WriteImageFile(missing, Gradient(CV_8UC1));
  EXPECT_EQ(write.code(), StatusCode::kUnavailable);
  EXPECT_EQ(write.message(), missing + ": cannot write: No such file or directory");
}

}  // namespace
}  // namespace fleetmap::grid
