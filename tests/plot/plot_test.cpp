#include "palpa/plot/line_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <unistd.h>

namespace palpa::plot {
namespace {

cv::Vec3b bgr(const cv::Scalar& s) {
  return {cv::saturate_cast<uchar>(s[0]), cv::saturate_cast<uchar>(s[1]), cv::saturate_cast<uchar>(s[2])};
}

cv::Vec3b pixel(const cv::Mat& image, cv::Point2d p) { return image.at<cv::Vec3b>(cvRound(p.y), cvRound(p.x)); }

/// True if some pixel within `radius` of p has `colour` (each channel within `tolerance`).
bool colour_near(const cv::Mat& image, cv::Point2d p, const cv::Scalar& colour, int radius, int tolerance = 0) {
  const cv::Vec3b want = bgr(colour);
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const cv::Vec3b got = image.at<cv::Vec3b>(cvRound(p.y) + dy, cvRound(p.x) + dx);
      bool same = true;
      for (int c = 0; c < 3; ++c) same = same && std::abs(got[c] - want[c]) <= tolerance;
      if (same) return true;
    }
  }
  return false;
}

int count_colour(const cv::Mat& image, const cv::Scalar& colour) {
  cv::Mat mask;
  cv::inRange(image, colour, colour, mask);
  return cv::countNonZero(mask);
}

Series points(std::vector<double> x, std::vector<double> y, Marker marker = Marker::Square, bool line = false) {
  return {"", std::move(x), std::move(y), marker, line};
}

std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("palpa-plot-" + std::to_string(::getpid()) + "-" + name);
}

TEST(LinePlot, RendersRequestedSizeOnWhite) {
  LinePlot plot;
  const cv::Mat image = render(plot);
  EXPECT_EQ(image.cols, 1000);
  EXPECT_EQ(image.rows, 650);
  EXPECT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.at<cv::Vec3b>(0, 0), cv::Vec3b(255, 255, 255));

  plot.width = 640;
  plot.height = 480;
  const cv::Mat small = render(plot);
  EXPECT_EQ(small.cols, 640);
  EXPECT_EQ(small.rows, 480);
}

TEST(LinePlot, MarkersLandOnTheMappedPixels) {
  LinePlot plot;
  plot.series = {points({1, 2, 3, 4}, {1, 3, 2, 5})};
  const cv::Mat image = render(plot);
  const Frame frame = frame_of(plot);
  for (std::size_t i = 0; i < 4; ++i) {
    const cv::Point2d p = *frame.to_pixel(plot.series[0].x[i], plot.series[0].y[i]);
    EXPECT_TRUE(frame.area.contains(cv::Point(cvRound(p.x), cvRound(p.y))));
    EXPECT_EQ(pixel(image, p), bgr(series_colour(0))) << "point " << i;
  }
  // Away from the points (no line joins them) there is none of that colour.
  const cv::Point2d between = (*frame.to_pixel(1, 1) + *frame.to_pixel(2, 3)) / 2.0;
  EXPECT_FALSE(colour_near(image, between, series_colour(0), 3, 40));
}

TEST(LinePlot, LinesJoinPointsAndEachSeriesHasItsColour) {
  LinePlot plot;
  plot.series = {points({0, 10}, {0, 10}, Marker::None, true), points({0, 10}, {10, 0}, Marker::Circle, true)};
  const cv::Mat image = render(plot);
  const Frame frame = frame_of(plot);
  EXPECT_NE(series_colour(0), series_colour(1));
  // A quarter of the way along each line (away from the crossing).
  EXPECT_TRUE(colour_near(image, *frame.to_pixel(2.5, 2.5), series_colour(0), 1, 10));
  EXPECT_TRUE(colour_near(image, *frame.to_pixel(2.5, 7.5), series_colour(1), 1, 10));
  EXPECT_EQ(pixel(image, *frame.to_pixel(10, 0)), bgr(series_colour(1)));
}

TEST(LinePlot, LinearRangeIsTheDataWithAMargin) {
  LinePlot plot;
  plot.series = {points({0, 10}, {-2, 2})};
  const Frame frame = frame_of(plot);
  EXPECT_DOUBLE_EQ(frame.x.min, -0.5);
  EXPECT_DOUBLE_EQ(frame.x.max, 10.5);
  EXPECT_DOUBLE_EQ(frame.y.min, -2.2);
  EXPECT_DOUBLE_EQ(frame.y.max, 2.2);
  // y grows downwards in the image: the minimum is at the bottom of the area.
  EXPECT_DOUBLE_EQ(frame.to_pixel(-0.5, -2.2)->y, frame.area.y + frame.area.height);
  EXPECT_DOUBLE_EQ(frame.to_pixel(10.5, 2.2)->x, frame.area.x + frame.area.width);

  plot.x.min = 0.0;
  plot.x.max = 100.0;
  const Frame fixed = frame_of(plot);
  EXPECT_EQ(fixed.x.min, 0.0);
  EXPECT_EQ(fixed.x.max, 100.0);
}

TEST(LinePlot, LogAxesSpanWholeDecadesEquallySpaced) {
  LinePlot plot;
  plot.x.scale = Scale::Log10;
  plot.y.scale = Scale::Log10;
  plot.series = {points({3e-6, 0.5}, {20.0, 7e3})};
  const Frame frame = frame_of(plot);
  EXPECT_DOUBLE_EQ(frame.x.min, 1e-6);
  EXPECT_DOUBLE_EQ(frame.x.max, 1.0);
  EXPECT_DOUBLE_EQ(frame.y.min, 10.0);
  EXPECT_DOUBLE_EQ(frame.y.max, 1e4);

  const double step = frame.to_pixel(1e-5, 10)->x - frame.to_pixel(1e-6, 10)->x;
  EXPECT_NEAR(step, frame.area.width / 6.0, 1e-9);
  for (int e = -6; e < 0; ++e) {
    const double gap = frame.to_pixel(std::pow(10.0, e + 1), 10)->x - frame.to_pixel(std::pow(10.0, e), 10)->x;
    EXPECT_NEAR(gap, step, 1e-9) << "decade 1e" << e;
  }
  const double y_step = frame.to_pixel(1, 100)->y - frame.to_pixel(1, 10)->y;
  EXPECT_NEAR(y_step, -frame.area.height / 3.0, 1e-9);
}

TEST(LinePlot, SkipsNonFiniteAndNonPositivePointsOnLogAxes) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  LinePlot plot;
  plot.x.scale = Scale::Log10;
  plot.y.scale = Scale::Log10;
  plot.series = {
      points({1e-3, nan, 0.0, -1.0, 1e-1, inf, 1e-2}, {1.0, 5.0, 5.0, 5.0, 100.0, 5.0, -3.0}, Marker::Circle, true)};
  const Frame frame = frame_of(plot);
  EXPECT_FALSE(frame.to_pixel(nan, 5.0));
  EXPECT_FALSE(frame.to_pixel(0.0, 5.0));
  EXPECT_FALSE(frame.to_pixel(-1.0, 5.0));
  EXPECT_FALSE(frame.to_pixel(1e-2, -3.0));
  // Only (1e-3, 1) and (1e-1, 100) count for the ranges.
  EXPECT_DOUBLE_EQ(frame.x.min, 1e-3);
  EXPECT_DOUBLE_EQ(frame.x.max, 1e-1);
  const cv::Mat image = render(plot);
  EXPECT_EQ(pixel(image, *frame.to_pixel(1e-3, 1.0)), bgr(series_colour(0)));

  // A series with nothing drawable looks exactly like an empty plot.
  LinePlot empty;
  empty.x.scale = empty.y.scale = Scale::Log10;
  LinePlot hopeless = empty;
  hopeless.series = {points({nan, -1.0, 0.0, 1.0}, {1.0, 1.0, 1.0, inf}, Marker::Circle, true)};
  EXPECT_EQ(cv::norm(render(hopeless), render(empty), cv::NORM_INF), 0.0);
}

TEST(LinePlot, EmptyPlotHasAxesAndNoSeriesColour) {
  LinePlot plot;
  plot.title = "Nothing yet";
  plot.x.label = "size";
  plot.y.label = "time (s)";
  const cv::Mat image = render(plot);
  const Frame frame = frame_of(plot);
  const cv::Vec3b corner = image.at<cv::Vec3b>(frame.area.y, frame.area.x);
  EXPECT_LT(corner[0], 100);  // the axes box is dark
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(count_colour(image, series_colour(i)), 0) << i;
  // Title above the area, y label left of the tick labels: some ink in both bands.
  cv::Mat gray;
  cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  double darkest = 255;
  cv::minMaxLoc(gray(cv::Rect(0, 0, image.cols, frame.area.y - 8)), &darkest);
  EXPECT_LT(darkest, 100);
  cv::minMaxLoc(gray(cv::Rect(0, frame.area.y, 30, frame.area.height)), &darkest);
  EXPECT_LT(darkest, 100);
}

TEST(LinePlot, LegendDoesNotHideData) {
  // Data fills the top right; the legend must go to another corner.
  LinePlot plot;
  plot.series = {{"measured", {0, 8, 9, 10}, {0, 8, 9, 10}, Marker::Square, false},
                 {"model", {1, 8, 9, 10}, {0, 9, 10, 9}, Marker::Square, false}};
  const cv::Mat image = render(plot);
  const Frame frame = frame_of(plot);
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const Series& series = plot.series[s];
    for (std::size_t i = 0; i < series.x.size(); ++i) {
      EXPECT_TRUE(colour_near(image, *frame.to_pixel(series.x[i], series.y[i]), series_colour(s), 1))
          << series.label << " " << i;
    }
  }
}

TEST(LinePlot, ExtremeDataNeverCrashes) {
  const double big = std::numeric_limits<double>::max();
  const double tiny = std::numeric_limits<double>::denorm_min();
  const std::vector<std::vector<double>> columns = {
      {-big, big}, {tiny, 2 * tiny}, {1.0, 1.0 + 1e-15}, {5.0, 5.0, 5.0}, {0.0}, {}, {1e300, -1e-300, 1e-300}};
  for (const Scale scale : {Scale::Linear, Scale::Log10}) {
    for (const auto& xs : columns) {
      for (const auto& ys : columns) {
        LinePlot plot;
        plot.width = 200;
        plot.height = 150;
        plot.x.scale = plot.y.scale = scale;
        plot.series = {{"s", xs, ys, Marker::Triangle, true}};
        const cv::Mat image = render(plot);
        EXPECT_EQ(image.size(), cv::Size(200, 150));
      }
    }
  }
  // Fixed limits far from the data: the line is clipped, nothing is drawn outside.
  LinePlot plot;
  plot.x.min = 1e6;
  plot.x.max = 2e6;
  plot.series = {points({0, 1e12}, {0, 1}, Marker::Circle, true)};
  EXPECT_NO_THROW((void)render(plot));
}

TEST(LinePlot, RejectsBadLimitsAndSizes) {
  LinePlot plot;
  plot.x.scale = Scale::Log10;
  plot.x.min = 0.0;
  EXPECT_THROW((void)render(plot), std::invalid_argument);
  plot.x.min = 10.0;
  plot.x.max = 1.0;
  EXPECT_THROW((void)frame_of(plot), std::invalid_argument);
  plot.x = {};
  plot.y.max = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)frame_of(plot), std::invalid_argument);
  plot.y = {};
  plot.width = 50;
  EXPECT_THROW((void)render(plot), std::invalid_argument);
}

TEST(LinePlot, SavePngWritesAReadableImage) {
  LinePlot plot;
  plot.width = 400;
  plot.height = 300;
  plot.series = {points({1, 2}, {3, 4})};
  const auto path = temp_path("figure.png");
  save_png(plot, path);
  const cv::Mat back = cv::imread(path.string(), cv::IMREAD_COLOR);
  std::filesystem::remove(path);
  ASSERT_FALSE(back.empty());
  EXPECT_EQ(back.cols, 400);
  EXPECT_EQ(back.rows, 300);
  EXPECT_EQ(cv::norm(back, render(plot), cv::NORM_INF), 0.0);
}

TEST(LinePlot, SavePngToAMissingFolderThrowsNamingThePath) {
  const auto path = temp_path("no-such-folder") / "figure.png";
  try {
    save_png(LinePlot{}, path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace palpa::plot
