#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "palpa/report/images.hpp"
#include "palpa/scene/scene.hpp"
#include "palpa/io/case_file.hpp"
#include "report_fixture.hpp"

namespace palpa::report {
namespace {

using testing::cell_x;
using testing::cell_y;

cv::Vec3b pixel(const cv::Mat& image, const TopView& view, double x, double y) {
  const auto p = view.to_pixel(x, y);
  return image.at<cv::Vec3b>(static_cast<int>(std::lround(p.y)), static_cast<int>(std::lround(p.x)));
}

cv::Vec3b bgr(const cv::Scalar& s) {
  return {static_cast<std::uint8_t>(s[0]), static_cast<std::uint8_t>(s[1]), static_cast<std::uint8_t>(s[2])};
}

TEST(MapImages, ViewKeepsXRightYUpAndOneScale) {
  const auto view = map_view(testing::synthetic_score());
  const auto a = view.to_pixel(0.0, 0.0), b = view.to_pixel(0.01, 0.0), c = view.to_pixel(0.0, 0.01);
  EXPECT_GT(b.x, a.x);
  EXPECT_DOUBLE_EQ(b.y, a.y);
  EXPECT_LT(c.y, a.y);  // y up: a larger y is higher in the image
  EXPECT_NEAR(b.x - a.x, a.y - c.y, 1e-9);
  // Every cell, tumour and mark lies inside the drawing area.
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const auto p = view.to_pixel(cell_x(i), cell_y(j));
      EXPECT_TRUE(view.area.contains(cv::Point(static_cast<int>(p.x), static_cast<int>(p.y))));
    }
}

TEST(MapImages, HeatmapColoursCellsByDwellAndSkipsCellsOutsideTheRegion) {
  const auto score = testing::synthetic_score();
  const auto image = coverage_heatmap(score);
  ASSERT_EQ(image.type(), CV_8UC3);
  const auto view = map_view(score);
  // The cell with the longest dwell has the top colour of OpenCV's viridis map.
  cv::Mat top(1, 1, CV_8UC1, cv::Scalar(255)), top_colour;
  cv::applyColorMap(top, top_colour, cv::COLORMAP_VIRIDIS);
  EXPECT_EQ(pixel(image, view, cell_x(1), cell_y(2)), top_colour.at<cv::Vec3b>(0, 0));
  // A quarter of the longest dwell: the colour at 64 of 255.
  cv::Mat quarter(1, 1, CV_8UC1, cv::Scalar(64)), quarter_colour;
  cv::applyColorMap(quarter, quarter_colour, cv::COLORMAP_VIRIDIS);
  EXPECT_EQ(pixel(image, view, cell_x(0), cell_y(0)), quarter_colour.at<cv::Vec3b>(0, 0));
  // Untouched cells of the region are grey; the cell outside it (area 0) stays white.
  EXPECT_EQ(pixel(image, view, cell_x(2), cell_y(1)), bgr(untouched_colour()));
  EXPECT_EQ(pixel(image, view, cell_x(3), cell_y(3)), cv::Vec3b(255, 255, 255));
  // Cells are filled edge to edge: half-way between two cell centres is still coloured.
  EXPECT_EQ(pixel(image, view, (cell_x(1) + cell_x(2)) / 2 + 0.001, cell_y(1)), bgr(untouched_colour()));
}

TEST(MapImages, TumoursShowFoundGreenAndMissedRed) {
  const auto score = testing::synthetic_score();
  for (const auto& image : {coverage_heatmap(score), pressure_map(score)}) {
    const auto view = map_view(score);
    const auto missed = pixel(image, view, -0.025, 0.025);
    EXPECT_GT(missed[2], 180);  // red
    EXPECT_LT(missed[1], 80);
    EXPECT_LT(missed[0], 80);
    const auto found = pixel(image, view, 0.01, 0.01);
    EXPECT_GT(found[1], 140);  // green
    EXPECT_LT(found[2], 80);
    EXPECT_LT(found[0], 80);
    // The circle has the tumour's radius: its outline is red 4 mm left of the missed centre.
    const auto edge = pixel(image, view, -0.025 - 0.004, 0.025);
    EXPECT_GT(edge[2], 150);
    EXPECT_LT(edge[1], 100);
    // The false-positive mark's cross is dark at its centre.
    const auto mark = pixel(image, view, 0.03, -0.03);
    EXPECT_LT(mark[0] + mark[1] + mark[2], 200);
  }
}

TEST(MapImages, PressureMapColoursTheDeepestLevel) {
  const auto score = testing::synthetic_score();
  const auto image = pressure_map(score);
  const auto view = map_view(score);
  EXPECT_EQ(pixel(image, view, cell_x(1), cell_y(2)), bgr(level_colour(3)));
  EXPECT_EQ(pixel(image, view, cell_x(0), cell_y(0)), bgr(level_colour(1)));
  EXPECT_EQ(pixel(image, view, cell_x(2), cell_y(1)), bgr(level_colour(0)));
  EXPECT_EQ(pixel(image, view, cell_x(3), cell_y(3)), cv::Vec3b(255, 255, 255));
}

/// A session of `case_file` with one sample resting on the body, scored: its maps cover
/// the case's exam region.
score::Score scored_case(const std::string& case_file) {
  session::Session s;
  std::ifstream in(std::string(PALPA_SOURCE_DIR) + "/data/cases/" + case_file);
  std::stringstream text;
  text << in.rdbuf();
  s.info.case_document = nlohmann::json::parse(text.str());
  s.info.case_source = case_file;
  engine::Sample x;
  x.body = 0;
  x.u = x.v = 0.5;
  s.samples.push_back(x);
  return score::score_session(s, case_file);
}

// The imported breast rests on its chest wall with its free side towards +y: its maps look
// down the support's normal (the body's press axis) and show its footprint, the exam
// region's extent across that normal, not its side profile (x against y, the thickness).
TEST(MapImages, ABodyOnASupportIsSeenFromItsFreeSide) {
  const auto score = scored_case("victre-breast.json");
  const auto view = map_view(score);
  const auto file = io::load_case(std::string(PALPA_SOURCE_DIR) + "/data/cases/victre-breast.json");
  const auto scene = scene::Scene::build(file, "victre-breast.json");
  const Vec3 up = scene.body(0).press_axis.up;
  EXPECT_GT(up.y(), 0.95);
  EXPECT_GT(view.normal[0] * up.x() + view.normal[1] * up.y() + view.normal[2] * up.z(), 0.99);
  // The region's extent along the picture's axes, against its extent across and along the normal.
  double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (std::size_t k = 0; k < score.maps[0].area.size(); ++k) {
    if (!(score.maps[0].area[k] > 0.0)) continue;
    const auto& c = score.maps[0].center[k];
    const double p[3] = {TopView::along(c, view.right), TopView::along(c, view.up), TopView::along(c, view.normal)};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  }
  const double wide = hi[0] - lo[0], tall = hi[1] - lo[1], deep = hi[2] - lo[2];
  EXPECT_GT(tall, 2.0 * deep) << "the picture's height is the footprint's, not the thickness";
  EXPECT_GT(wide, 2.0 * deep);
  // Drawn: most of the map area is coloured (a side profile is a thin band).
  const auto image = coverage_heatmap(score);
  const cv::Mat area = image(view.area);
  int coloured = 0;
  for (int r = 0; r < area.rows; ++r)
    for (int c = 0; c < area.cols; ++c) coloured += area.at<cv::Vec3b>(r, c) != cv::Vec3b(255, 255, 255) ? 1 : 0;
  EXPECT_GT(coloured, area.rows * area.cols / 3);
  // The flat bundled cases (normal +z) keep x to the right and y up.
  const auto flat = map_view(scored_case("default.json"));
  EXPECT_NEAR(flat.right[0], 1.0, 1e-6);
  EXPECT_NEAR(flat.up[1], 1.0, 1e-3);
}

TEST(MapImages, EmptyScoreStillDraws) {
  const score::Score empty;
  EXPECT_FALSE(coverage_heatmap(empty).empty());
  EXPECT_FALSE(pressure_map(empty).empty());
  score::Score ragged = testing::synthetic_score();
  ragged.maps[0].center.pop_back();  // inconsistent sizes: the map is left out, no crash
  EXPECT_FALSE(coverage_heatmap(ragged).empty());
}

session::Session pressing_session(bool with_case) {
  session::Session s;
  if (with_case) {
    std::ifstream in(std::string(PALPA_SOURCE_DIR) + "/data/cases/flat-5x5.json");
    std::stringstream text;
    text << in.rdbuf();
    s.info.case_document = nlohmann::json::parse(text.str());
    s.info.case_source = "flat-5x5.json";
  }
  // 6 s at 1 kHz over the body's centre (radius 20 mm there): pressing 0 to 12 mm and back.
  for (int i = 0; i < 6000; ++i) {
    engine::Sample x;
    x.t = i * 1e-3;
    const double depth = 0.012 * std::sin(3.141592653589793 * x.t / 6.0);
    x.body = 0;
    x.u = x.v = 0.5;
    x.depth = depth;
    x.force = {0.0, 0.0, 200.0 * depth};
    s.samples.push_back(x);
  }
  return s;
}

TEST(ForcePlot, DrawsTwoPanelsWithOrWithoutTheCase) {
  const auto score = testing::synthetic_score();
  for (const bool with_case : {true, false}) {
    const auto image = force_plot(pressing_session(with_case), score);
    EXPECT_EQ(image.cols, 1000);
    EXPECT_EQ(image.rows, 660);
    // Both panels carry a curve in the first series' colour (blue, anti-aliased into the
    // white background), not only axes: count clearly blue pixels in each panel.
    for (const int panel : {0, 1}) {
      const cv::Mat half = image.rowRange(panel * 330, panel * 330 + 330);
      int blue = 0;
      for (int r = 0; r < half.rows; ++r)
        for (int c = 0; c < half.cols; ++c) {
          const auto p = half.at<cv::Vec3b>(r, c);
          if (p[0] > p[2] + 80 && p[0] > p[1] + 30) ++blue;
        }
      EXPECT_GT(blue, 800) << "panel " << panel << " with case " << with_case;
    }
  }
  EXPECT_FALSE(force_plot(session::Session{}, score).empty());
}

TEST(Png, EncodesAndDecodes) {
  const cv::Mat image(20, 30, CV_8UC3, cv::Scalar(1, 2, 3));
  const auto bytes = png_bytes(image);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes[1], 'P');
  const auto back = cv::imdecode(bytes, cv::IMREAD_COLOR);
  EXPECT_EQ(back.size(), image.size());
  EXPECT_EQ(back.at<cv::Vec3b>(5, 5), cv::Vec3b(1, 2, 3));
}

}  // namespace
}  // namespace palpa::report
