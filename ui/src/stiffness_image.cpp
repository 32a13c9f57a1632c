#include <algorithm>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "palpa/ui/instructor_stiffness_image.hpp"

namespace palpa::ui {

std::optional<author::StiffnessMap> read_stiffness_image(const std::string& path, std::string& error) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    error = path + ": no such image file";
    return std::nullopt;
  }
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    error = path + ": cannot be read as an image: " + e.what();
    return std::nullopt;
  }
  if (image.empty() || image.depth() != CV_8U) {
    error = path + ": cannot be read as an image (use PNG, JPEG, BMP or TIFF)";
    return std::nullopt;
  }
  const int side = std::max(image.cols, image.rows);
  if (side > kMaxStiffnessMapSide) {
    const double scale = static_cast<double>(kMaxStiffnessMapSide) / side;
    cv::Mat small;
    cv::resize(image, small, cv::Size(std::max(1, static_cast<int>(image.cols * scale)),
                                      std::max(1, static_cast<int>(image.rows * scale))),
               0, 0, cv::INTER_AREA);
    image = small;
  }
  // Seen from above: map row a (along u, x) is image column a; map column b (along v, y)
  // is image row (rows - 1 - b), the image's bottom row at the body's first column.
  author::StiffnessMap map;
  map.rows = image.cols;
  map.cols = image.rows;
  map.values.resize(static_cast<std::size_t>(map.rows) * static_cast<std::size_t>(map.cols));
  for (int a = 0; a < map.rows; ++a) {
    for (int b = 0; b < map.cols; ++b) {
      map.values[static_cast<std::size_t>(a) * static_cast<std::size_t>(map.cols) + static_cast<std::size_t>(b)] =
          image.at<unsigned char>(image.rows - 1 - b, a) / 255.0;
    }
  }
  return map;
}

}  // namespace palpa::ui
