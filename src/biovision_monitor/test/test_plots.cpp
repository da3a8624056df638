// The plots of known states have their features where they belong (ROS-free, no master).
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_common/path_plot.hpp"
#include "biovision_monitor/attractor_plot.hpp"
#include "biovision_monitor/disparity_plot.hpp"
#include "biovision_monitor/drawing.hpp"
#include "biovision_monitor/ego_map_plot.hpp"
#include "biovision_monitor/monitor_panel.hpp"
#include "biovision_monitor/monitor_parameters.hpp"
#include "biovision_monitor/object_plot.hpp"
#include "biovision_monitor/occupancy_grid_plot.hpp"
#include "biovision_monitor/run_report.hpp"
#include "biovision_monitor/saliency_plot.hpp"
#include "biovision_monitor/time_series_plot.hpp"

using namespace biovision_monitor;

namespace
{
constexpr double kDeg = M_PI / 180.0;
const cv::Size kSize(320, 240);

bool near(const cv::Vec3b& a, const cv::Scalar& b, int tolerance = 40)
{
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) <= tolerance;
}

// Whether a pixel of `colour` lies within `radius` px of `p`.
bool colourNear(const cv::Mat& image, cv::Point p, const cv::Scalar& colour, int radius)
{
  for (int y = p.y - radius; y <= p.y + radius; ++y)
    for (int x = p.x - radius; x <= p.x + radius; ++x)
      if (x >= 0 && y >= 0 && x < image.cols && y < image.rows && near(image.at<cv::Vec3b>(y, x), colour))
        return true;
  return false;
}

AttractorView nineSections()
{
  AttractorView s;
  s.controller = "head_pan";
  for (int i = 0; i < 9; ++i)
    s.section_angles.push_back((-80 + 20 * i) * kDeg);
  s.attraction.assign(9, 0.0);
  s.repulsion.assign(9, 0.0);
  s.forcelet.assign(9, 0.0);
  return s;
}

MonitorParameters defaults;
}  // namespace

TEST(AttractorPlot, AnAttractorCrossesZeroFallingAtItsAngleAndColumn)
{
  AttractorView s = nineSections();
  s.attraction[6] = 1.0;  // +40 deg
  s.angle = 0.0;
  const AttractorPlot plot(defaults.model("head_pan"));
  const auto crossings = plot.zeroCrossings(s);
  ASSERT_EQ(crossings.size(), 1u);
  EXPECT_NEAR(crossings[0].angle, 40 * kDeg, 0.5 * kDeg);
  EXPECT_TRUE(crossings[0].stable);
  EXPECT_GT(plot.sum(s, 0.0), 0.0) << "left of the attractor the rate turns the head left (towards it)";

  AttractorPlot::Axes axes;
  const cv::Mat image = plot.render(s, kSize, &axes);
  ASSERT_EQ(image.size(), kSize);
  const int column = axes.column(40 * kDeg), zero = axes.row(0.0);
  // The sum curve passes the zero line at the attractor's column, and the stable-point disc sits there.
  EXPECT_TRUE(colourNear(image, {column, zero}, colours::kAttraction, 1));
  EXPECT_FALSE(colourNear(image, {axes.column(-40 * kDeg), zero}, colours::kAttraction, 2));
  // The curve is above zero left of the attractor (rate > 0) and below it to the right.
  EXPECT_TRUE(colourNear(image, {axes.column(20 * kDeg), axes.row(plot.sum(s, 20 * kDeg))}, colours::kSum, 2));
  EXPECT_LT(axes.row(plot.sum(s, 20 * kDeg)), zero);
  EXPECT_GT(axes.row(plot.sum(s, 60 * kDeg)), zero);
}

TEST(AttractorPlot, ARepellerCrossesZeroRisingAtItsAngle)
{
  AttractorView s = nineSections();
  s.repulsion[2] = 1.0;  // -40 deg
  const AttractorPlot plot(defaults.model("head_pan"));
  const auto crossings = plot.zeroCrossings(s);
  ASSERT_EQ(crossings.size(), 1u);
  EXPECT_NEAR(crossings[0].angle, -40 * kDeg, 0.5 * kDeg);
  EXPECT_FALSE(crossings[0].stable);
  AttractorPlot::Axes axes;
  const cv::Mat image = plot.render(s, kSize, &axes);
  EXPECT_TRUE(colourNear(image, {axes.column(-40 * kDeg) + 4, axes.row(0.0)}, colours::kRepulsion, 1));
}

TEST(AttractorPlot, TheCurrentAngleIsADotAtTheControllersRate)
{
  AttractorView s = nineSections();
  s.attraction[4] = 1.0;
  s.angle = -30 * kDeg;
  s.rate = 0.2;
  AttractorPlot::Axes axes;
  const cv::Mat image = AttractorPlot(defaults.model("head_pan")).render(s, kSize, &axes);
  EXPECT_TRUE(near(image.at<cv::Vec3b>(axes.row(0.2), axes.column(-30 * kDeg)), colours::kCurrent));
  EXPECT_FALSE(near(image.at<cv::Vec3b>(axes.row(0.2), axes.column(30 * kDeg)), colours::kCurrent));
}

TEST(AttractorPlot, TheBasesGoalIsASineAttractorAtTheTarget)
{
  AttractorView s = nineSections();
  s.controller = "base";
  s.target = -20 * kDeg;
  const auto crossings = AttractorPlot(defaults.model("base")).zeroCrossings(s);
  ASSERT_EQ(crossings.size(), 1u);
  EXPECT_NEAR(crossings[0].angle, -20 * kDeg, 0.5 * kDeg);
  EXPECT_TRUE(crossings[0].stable);
  // An obstacle at +20 deg pushes the stable heading to the right (below -20 deg), as Fig. 5.6.
  s.repulsion[5] = 0.2;
  const auto pushed = AttractorPlot(defaults.model("base")).zeroCrossings(s);
  ASSERT_FALSE(pushed.empty());
  EXPECT_LT(pushed.front().angle, -20 * kDeg);
}

TEST(AttractorPlot, ATitleTooLongForThePlotGoesOnTwoLines)
{
  AttractorView s = nineSections();
  s.angle = 58 * kDeg;
  s.rate = 0.11;
  auto dark = [](const cv::Mat& image, const cv::Rect& r) {
    int n = 0;
    for (int y = r.y; y < r.br().y; ++y)
      for (int x = r.x; x < r.br().x; ++x)
        n += near(image.at<cv::Vec3b>(y, x), colours::kAxis, 150);
    return n;
  };
  AttractorPlot::Axes axes;
  s.behaviour = "look_ahead";  // "head_pan (look_ahead)  phi 58 deg, dphi/dt 0.11 rad/s": wider than 320 px
  const cv::Mat two = AttractorPlot(defaults.model("head_pan")).render(s, kSize, &axes);
  const cv::Rect second_line(axes.area.x + 3, axes.area.y + 14, 60, 9);
  EXPECT_GT(dark(two, second_line), 10) << "the state on a second line";
  s.behaviour = "";
  const cv::Mat one = AttractorPlot(defaults.model("head_pan")).render(s, cv::Size(640, 240), &axes);
  EXPECT_EQ(dark(one, cv::Rect(axes.area.x + 3, axes.area.y + 14, 60, 9)), 0) << "one line where it fits";
}

TEST(AttractorPlot, CurvesLeaveTheTitlesLinesABandOfTheirOwn)
{
  AttractorView s = nineSections();
  s.attraction[4] = 1.0;  // the sum's peak, where the axis would put it at 1/1.1 of the area's half height
  s.angle = 0.0;
  for (const cv::Size size : {kSize, cv::Size(640, 240)})  // two lines of title, then one
  {
    s.behaviour = size == kSize ? "look_ahead" : "";  // too long for 320 px on one line (as above)
    AttractorPlot::Axes axes;
    const cv::Mat image = AttractorPlot(defaults.model("head_pan")).render(s, size, &axes);
    const int lines = size.width == kSize.width ? 2 : 1;
    int crossing = 0;
    for (int y = axes.area.y + 1; y < axes.area.y + 11 * lines; ++y)  // the text's rows (the band: 3 more)
      for (int x = axes.area.x + 1; x < axes.area.br().x - 1; ++x)
        crossing += near(image.at<cv::Vec3b>(y, x), colours::kSum, 60) ||
                    near(image.at<cv::Vec3b>(y, x), colours::kAttraction, 60);
    EXPECT_EQ(crossing, 0) << size << ": curves through the title's band";
    int drawn = 0;
    for (int y = axes.area.y; y < axes.area.br().y; ++y)
      drawn += near(image.at<cv::Vec3b>(y, axes.column(-10 * kDeg)), colours::kSum, 60);
    EXPECT_GT(drawn, 0) << "the sum is still drawn";
  }
}

TEST(AttractorPlot, NonFiniteAndMissingValuesDrawNothingWrong)
{
  AttractorView s = nineSections();
  s.attraction = {NAN, INFINITY};
  s.repulsion.clear();
  s.rate = NAN;
  s.angle = NAN;
  const cv::Mat image = AttractorPlot(defaults.model("head_pan")).render(s, cv::Size(10, 10));
  EXPECT_EQ(image.size(), cv::Size(64, 48));
}

TEST(EgoMapPlot, AnObstacleIsABlackSliceAtItsAngleBeyondItsDistance)
{
  EgoMapView stm;
  stm.section_width = 20 * kDeg;
  for (int i = 0; i < 9; ++i)
    stm.section_angles.push_back((-80 + 20 * i) * kDeg);
  stm.obstacle_distance.assign(9, INFINITY);
  stm.confidence.assign(9, 1.0);
  stm.max_range = 2.0;
  stm.obstacle_distance[6] = 1.0;  // +40 deg: left of the robot
  EgoMapPlot::Axes axes;
  const cv::Mat image = EgoMapPlot().render(stm, kSize, &axes);
  if (getenv("MONITOR_TEST_DUMP"))
    cv::imwrite("/tmp/stm_test.png", image);
  const cv::Point obstacle = axes.point(40 * kDeg, 1.3), mirrored = axes.point(-40 * kDeg, 1.3),
                  before = axes.point(40 * kDeg, 0.7);
  EXPECT_LT(obstacle.x, axes.robot.x) << "+ = left is drawn to the left";
  EXPECT_TRUE(near(image.at<cv::Vec3b>(obstacle), cv::Scalar(0, 0, 0), 10));
  EXPECT_FALSE(near(image.at<cv::Vec3b>(mirrored), cv::Scalar(0, 0, 0), 60));
  EXPECT_TRUE(near(image.at<cv::Vec3b>(before), cv::Scalar(170, 230, 170), 10));
  // The neighbouring sector (+20 deg) is free at the same distance.
  EXPECT_TRUE(near(image.at<cv::Vec3b>(axes.point(20 * kDeg, 1.3)), cv::Scalar(170, 230, 170), 10));
}

TEST(DisparityPlot, InvalidPixelsAreBlackAndTheBarSpansTheRange)
{
  cv::Mat d(120, 160, CV_32FC1);
  for (int c = 0; c < d.cols; ++c)
    d.col(c).setTo(c * 64.0 / (d.cols - 1));
  d(cv::Rect(0, 0, 20, 20)).setTo(-1.0f);
  const cv::Mat image = DisparityPlot().render(d, 0.0, 64.0, kSize);
  ASSERT_EQ(image.size(), kSize);
  // The map is fitted into the 280 x 240 left part: 160 x 120 scaled by 1.75, centred vertically.
  const double s = 280.0 / 160.0;
  const int y0 = int((240 - 120 * s) / 2);
  EXPECT_EQ(image.at<cv::Vec3b>(y0 + 5, 5), cv::Vec3b(0, 0, 0)) << "invalid -> black";
  const cv::Vec3b far = image.at<cv::Vec3b>(y0 + 100, int(30 * s)),
                  nearer = image.at<cv::Vec3b>(y0 + 100, int(150 * s));
  EXPECT_GT(far[0], far[2]) << "small disparity (far) is blue";
  EXPECT_GT(nearer[2], nearer[0]) << "large disparity (near) is red";
  // The bar: max colour at its top, min colour at its bottom.
  const int x = kSize.width - DisparityPlot::kBarWidth + 8;
  EXPECT_EQ(image.at<cv::Vec3b>(22, x), DisparityPlot::colourOf(64.0, 0.0, 64.0));
  EXPECT_EQ(image.at<cv::Vec3b>(kSize.height - 14, x), DisparityPlot::colourOf(0.0, 0.0, 64.0));
  EXPECT_THROW(DisparityPlot().render(d, 5.0, 5.0, kSize), std::invalid_argument);
  EXPECT_THROW(DisparityPlot().render(cv::Mat(4, 4, CV_8UC1), 0.0, 1.0, kSize), std::invalid_argument);
}

TEST(SaliencyPlot, ThresholdsAtTheFractionOfTheMaximumAndBoxesTheAttendedRegion)
{
  cv::Mat map(120, 160, CV_32FC1, cv::Scalar(0.05f));
  map(cv::Rect(100, 40, 20, 20)).setTo(1.0f);
  const SaliencyPlot plot(0.15);
  const cv::Mat m = plot.mask(map);
  EXPECT_EQ(cv::countNonZero(m), 400);
  // The region in full-resolution px of a 320 x 240 image: twice the map's coordinates.
  RegionView r;
  r.rank = 0;
  r.box = cv::Rect(200, 80, 40, 40);
  RegionView inhibited;
  inhibited.rank = 1;
  inhibited.box = cv::Rect(20, 20, 40, 40);
  inhibited.inhibition = 0.8;
  const cv::Mat image = plot.renderThresholded(map, {r, inhibited}, 320, 240, kSize);
  // 160 x 120 -> 320 x 240: scale 2; the box's left edge at x = 200.
  EXPECT_TRUE(near(image.at<cv::Vec3b>(100, 200), cv::Scalar(0, 0, 255)));
  EXPECT_TRUE(near(image.at<cv::Vec3b>(100, 220), cv::Scalar(255, 255, 255))) << "salient inside";
  EXPECT_TRUE(near(image.at<cv::Vec3b>(40, 40), cv::Scalar(255, 0, 255))) << "IoR cross through the centre";
  EXPECT_THROW(SaliencyPlot(1.5), std::invalid_argument);
}

TEST(SaliencyPlot, LabelsOfBoxesAtTheEdgesStayInsideAndBelowTheTileTitle)
{
  const cv::Mat map(120, 160, CV_32FC1, cv::Scalar(0.05f));
  RegionView top;  // at the image's top edge: "#0" under the title strip, not in it
  top.rank = 0;
  top.box = cv::Rect(100, 0, 60, 60);
  RegionView corner;  // cut by the left and bottom edges: its "IoR" label whole inside the image
  corner.rank = 1;
  corner.box = cv::Rect(-30, 200, 80, 80);
  corner.inhibition = 0.8;
  const cv::Mat image = SaliencyPlot(0.15).renderThresholded(map, {top, corner}, 320, 240, kSize);
  const cv::Scalar red(0, 0, 255), magenta(255, 0, 255);
  auto count = [&](const cv::Rect& r, const cv::Scalar& colour) {
    int n = 0;
    for (int y = r.y; y < r.br().y; ++y)
      for (int x = r.x; x < r.br().x; ++x)
        n += near(image.at<cv::Vec3b>(y, x), colour, 60);
    return n;
  };
  EXPECT_GT(count(cv::Rect(103, kTitleHeight, 20, 12), red), 5) << "the rank below the title";
  EXPECT_EQ(count(cv::Rect(103, 2, 20, kTitleHeight - 3), red), 0) << "nothing of it under the title";
  int baseline = 0;
  const int width = cv::getTextSize("IoR 0.8", cv::FONT_HERSHEY_SIMPLEX, 0.35, 1, &baseline).width;
  const cv::Point ior = textOriginInside(image, "IoR 0.8", 0.35, {-30 + (80 - width) / 2, 277}, kTitleHeight);
  EXPECT_EQ(ior.x, 0);
  EXPECT_LT(ior.y, 240);
  // Right of the cross's lines (they leave the image below row 240 there): the label's letters alone.
  EXPECT_GT(count(cv::Rect(10, ior.y - 8, 30, 9), magenta), 5) << "the label inside the image";
}

TEST(SaliencyPlot, LabelsStayReadableOnTheWhiteBlobAndOverTheCross)
{
  // A salient blob everywhere (white) and an inhibited box whose cross runs through both labels' places.
  const cv::Mat map(120, 160, CV_32FC1, cv::Scalar(1.0f));
  RegionView inhibited;
  inhibited.rank = 1;
  inhibited.box = cv::Rect(100, 100, 60, 60);
  inhibited.inhibition = 0.5;
  const cv::Mat image = SaliencyPlot(0.15).renderThresholded(map, {inhibited}, 320, 240, kSize);
  int baseline = 0;
  for (const auto& label : {std::make_pair(std::string("#1"), 0.4), std::make_pair(std::string("IoR 0.5"), 0.35)})
  {
    const cv::Size size = cv::getTextSize(label.first, cv::FONT_HERSHEY_SIMPLEX, label.second, 1, &baseline);
    // Where the plot puts it (as renderThresholded: the box is at scale 1 here, kSize = 320 x 240).
    const cv::Point wanted = label.first == "#1" ? cv::Point(102, 112) : cv::Point(100 + (60 - size.width) / 2, 157);
    const cv::Point at = textOriginInside(image, label.first, label.second, wanted, kTitleHeight);
    const cv::Rect text(at.x, at.y - size.height, size.width, size.height + baseline);
    int dark = 0, white = 0;
    for (int y = text.y; y < text.br().y; ++y)
      for (int x = text.x; x < text.br().x; ++x)
      {
        const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
        dark += p[0] < 60 && p[1] < 60 && p[2] < 60;
        white += p[0] > 200 && p[1] > 200 && p[2] > 200;
      }
    EXPECT_GT(dark, text.area() / 3) << label.first << ": on a dark plate";
    EXPECT_EQ(white, 0) << label.first << ": no white blob showing through the letters";
  }
}

TEST(Drawing, TextOriginInsideKeepsTheWholeTextInTheImageBelowTheTop)
{
  const cv::Mat image(100, 200, CV_8UC3);
  int baseline = 0;
  const cv::Size text = cv::getTextSize("label", cv::FONT_HERSHEY_SIMPLEX, 0.4, 1, &baseline);
  EXPECT_EQ(textOriginInside(image, "label", 0.4, {50, 50}, 18), cv::Point(50, 50)) << "room: where wanted";
  const cv::Point clamped = textOriginInside(image, "label", 0.4, {190, 2}, 18);
  EXPECT_LE(clamped.x + text.width, 200);
  EXPECT_GE(clamped.y - text.height, 18);
  const cv::Point low = textOriginInside(image, "label", 0.4, {-40, 140}, 18);
  EXPECT_EQ(low.x, 0);
  EXPECT_LE(low.y + baseline, 100);
  EXPECT_THROW(textOriginInside(image, "label", NAN, {50, 50}), std::invalid_argument);
  const cv::Point extreme = textOriginInside(image, "label", 0.4, {INT_MAX, INT_MIN}, INT_MAX);
  EXPECT_GE(extreme.x, 0);
  EXPECT_LE(extreme.x, 200);
  EXPECT_GT(extreme.y, 0);
  EXPECT_THROW(fitInto(image, cv::Size(0, 0)), std::invalid_argument);
}

TEST(ObjectPlot, BoxesTheObjectWhereItIs)
{
  const cv::Mat camera(240, 320, CV_8UC3, cv::Scalar(90, 90, 90));
  const cv::Mat image = ObjectPlot().render(camera, {{"mug_red", 0.9, cv::Rect(100, 100, 50, 40)}}, kSize);
  EXPECT_TRUE(near(image.at<cv::Vec3b>(120, 100), cv::Scalar(0, 230, 0)));
  EXPECT_TRUE(near(image.at<cv::Vec3b>(120, 125), cv::Scalar(90, 90, 90), 5));
}

TEST(OccupancyGridPlot, RowZeroIsAtTheBottomAndValuesAreGreyLevels)
{
  GridView g;
  g.width = 4;
  g.height = 3;
  g.resolution = 0.1;
  g.data.assign(12, 0);
  g.data[0] = 100;  // row 0, col 0: the map's bottom-left
  g.data[11] = -1;
  const cv::Mat image = OccupancyGridPlot::toImage(g);
  EXPECT_EQ(image.at<uchar>(2, 0), 0);
  EXPECT_EQ(image.at<uchar>(0, 3), 160);
  EXPECT_EQ(image.at<uchar>(1, 1), 255);
  g.data.pop_back();
  EXPECT_THROW(OccupancyGridPlot::toImage(g), std::invalid_argument);
}

TEST(MonitorPanel, EightTilesInTheThesisOrderAndNoDataTilesNameTheirTopic)
{
  const MonitorPanel panel(4, kSize);
  std::vector<MonitorPanel::Tile> tiles(8);
  for (int i = 0; i < 8; ++i)
  {
    tiles[i].title = "tile " + std::to_string(i);
    tiles[i].topic = "topic/" + std::to_string(i);
    if (i % 2 == 0)
      tiles[i].image = cv::Mat(kSize, CV_8UC3, cv::Scalar(0, 200, 0));
  }
  const cv::Mat image = panel.compose(tiles);
  EXPECT_EQ(image.size(), cv::Size(4 * 320 + 3 * MonitorPanel::kGap, 2 * 240 + MonitorPanel::kGap));
  for (int i = 0; i < 8; ++i)
  {
    const cv::Mat tile = image(panel.tileRect(i));
    const cv::Vec3b centre = tile.at<cv::Vec3b>(60, 10);
    if (i % 2 == 0)
      EXPECT_TRUE(near(centre, cv::Scalar(0, 200, 0), 5)) << i;
    else
      EXPECT_TRUE(near(centre, colours::kNoData, 5)) << i;
    cv::Mat grey;
    cv::cvtColor(tile, grey, cv::COLOR_BGR2GRAY);
    double lo, hi;
    cv::minMaxLoc(grey, &lo, &hi);
    EXPECT_GT(hi - lo, 50) << "tile " << i << " is not uniform (it has a title)";
  }
  // Tile 4 starts the second row.
  EXPECT_EQ(panel.tileRect(4).tl(), cv::Point(0, 240 + MonitorPanel::kGap));
  EXPECT_THROW(MonitorPanel(0, kSize), std::invalid_argument);
}

TEST(TimeSeriesPlot, MarksSitAtTheirTimes)
{
  TimeSeriesPlot::Axes axes;
  const cv::Mat image = TimeSeriesPlot().render({{0, -10}, {10, 30}}, {{5.0, "mug"}}, "pan", cv::Size(400, 200), &axes);
  int dashes = 0;  // the dashed line's pixels in the plot's top 12 rows (two dash periods)
  for (int y = axes.area.y + 1; y < axes.area.y + 13; ++y)
    dashes += near(image.at<cv::Vec3b>(y, axes.column(5.0)), colours::kAttraction);
  EXPECT_GE(dashes, 6);
  EXPECT_EQ(axes.column(0.0), axes.area.x);
}

TEST(TimeSeriesPlot, MarkLabelsTakeTheFirstFreeRowAndAreLeftOutWhenTheRowsAreFull)
{
  // Three overlapping labels take rows 0, 1, 2; one that starts after the first ends (+ gap) reuses row 0;
  // with two rows the third overlapping one has no room.
  const std::vector<cv::Range> spans{{10, 60}, {20, 70}, {30, 80}, {63, 90}, {64, 100}};
  EXPECT_EQ(TimeSeriesPlot::labelRows(spans, 4), (std::vector<int>{0, 1, 2, 0, 3}));
  EXPECT_EQ(TimeSeriesPlot::labelRows(spans, 2), (std::vector<int>{0, 1, -1, 0, -1}));
  EXPECT_EQ(TimeSeriesPlot::labelRows(spans, 4, 5), (std::vector<int>{0, 1, 2, 3, -1}));
  EXPECT_TRUE(TimeSeriesPlot::labelRows({}, 4).empty());
  EXPECT_EQ(TimeSeriesPlot::labelRows(spans, 0), (std::vector<int>(5, -1)));

  // A mark at the right edge has its label left of its line, inside the picture, in the band above the plot.
  TimeSeriesPlot::Axes axes;
  const cv::Mat image = TimeSeriesPlot().render({{0, -10}, {10, 30}}, {{10.0, "target_box"}}, "pan", cv::Size(400, 200),
                                                &axes);
  const int x = axes.column(10.0);
  ASSERT_EQ(axes.label_band.br().y, axes.area.y);
  ASSERT_GE(axes.label_band.height, 10);
  cv::Mat left = image(cv::Rect(x - 60, axes.label_band.y, 56, 10)),
          right = image(cv::Rect(x + 2, 0, 400 - x - 2, 200));
  // Not over the curves: nothing of the label inside the plot area (it sat there, over the pan curve).
  cv::Mat in_plot = image(cv::Rect(x - 60, axes.area.y + 1, 56, axes.area.height - 2));
  auto green = [](const cv::Mat& m) {
    int n = 0;
    for (int r = 0; r < m.rows; ++r)
      for (int c = 0; c < m.cols; ++c)
        n += near(m.at<cv::Vec3b>(r, c), colours::kAttraction, 60);
    return n;
  };
  EXPECT_GT(green(left), 10) << "the label is drawn left of the line";
  EXPECT_EQ(green(right), 0) << "nothing right of the line";
  EXPECT_EQ(green(in_plot), 0) << "the label is not drawn over the plot";
  // Without marks the plot keeps the band's height.
  TimeSeriesPlot::Axes bare;
  TimeSeriesPlot().render({{0, -10}, {10, 30}}, {}, "pan", cv::Size(400, 200), &bare);
  EXPECT_TRUE(bare.label_band.empty());
  EXPECT_EQ(bare.area.y, 24);
  EXPECT_GT(bare.area.height, axes.area.height);
}

TEST(RunReport, WritesPicturesAndASelfContainedPage)
{
  EXPECT_EQ(RunReport::base64({'f', 'o', 'o'}), "Zm9v");
  EXPECT_EQ(RunReport::base64({'f', 'o'}), "Zm8=");
  char folder[] = "/tmp/run_report_testXXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  const std::string dir = folder;
  std::ofstream(dir + "/pan.csv") << "t,pan,tilt\n0.0,0.0,0.0\n1.0,0.5,0.2\n2.0,-0.3,0.2\n";
  std::ofstream(dir + "/fixations.json") << R"({"fixations": [{"t": 1.0, "object": "mug", "pan_deg": 28.6}]})";
  std::ofstream(dir + "/report.json")
      << R"({"title": "t", "ok": true, "listened_s": 3, "topics": {"a": {"messages": 3, "rate_hz": 1.0}, "b": {"messages": 0, "rate_hz": 0}}})";
  const auto written = RunReport(dir).write();
  EXPECT_EQ(written.size(), 3u);
  std::ifstream page(dir + "/report.html");
  std::stringstream text;
  text << page.rdbuf();
  EXPECT_NE(text.str().find("data:image/png;base64,iVBOR"), std::string::npos);
  EXPECT_NE(text.str().find("mug"), std::string::npos);
  EXPECT_NE(text.str().find("recognition.json"), std::string::npos) << "missing inputs are named";
  // pan.png shows pan (kSum: blue) and tilt (kRepulsion: red) curves, anti-aliased, so counted as pixels where
  // that channel leads the other two; an older run's "t,pan" file gives pan alone.
  const cv::Mat head = cv::imread(dir + "/pan.png");
  ASSERT_FALSE(head.empty());
  auto count = [](const cv::Mat& image, int channel) {
    int n = 0;
    for (int y = 0; y < image.rows; ++y)
      for (int x = 0; x < image.cols; ++x)
      {
        const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
        n += p[channel] - std::max(p[(channel + 1) % 3], p[(channel + 2) % 3]) > 60;
      }
    return n;
  };
  const int blue = 0, red = 2;
  EXPECT_GT(count(head, blue), 400) << "the pan curve across the 900 px plot";
  EXPECT_GT(count(head, red), 400) << "the tilt curve across the 900 px plot";
  std::ofstream(dir + "/pan.csv") << "t,pan\n0.0,0.0\n1.0,0.5\n2.0,-0.3\n";
  RunReport(dir).write();
  const cv::Mat pan_only = cv::imread(dir + "/pan.png");
  EXPECT_GT(count(pan_only, blue), 400);
  EXPECT_LT(count(pan_only, red), 20) << "no tilt curve, no tilt legend";
  // Columns are found by name: CR line ends, a byte order mark, blanks and another order read the same.
  std::ofstream(dir + "/pan.csv") << "\xEF\xBB\xBFt, tilt ,pan\r\n0.0,0.0,0.0\r\n1.0,0.2,0.5\r\n2.0,0.2,-0.3\r\n";
  RunReport(dir).write();
  const cv::Mat reordered = cv::imread(dir + "/pan.png");
  EXPECT_GT(count(reordered, red), 400);
  EXPECT_EQ(cv::norm(reordered, head, cv::NORM_INF), 0) << "the same picture as from t,pan,tilt";
  // Refused, naming the file: a short row, an extra column, trailing junk, no header, a header without pan.
  for (const char* text : {"t,pan,tilt\n0.0,0.0\n", "t,pan,tilt\n0,0,0,0\n", "t,pan,tilt\n0,0.2xyz,0\n",
                           "0,0.1,0.2\n1,0.1,0.2\n", "t,tilt\n0,0\n"})
  {
    std::ofstream(dir + "/pan.csv") << text;
    try
    {
      RunReport(dir).write();
      ADD_FAILURE() << "accepted: " << text;
    }
    catch (const std::runtime_error& e)
    {
      EXPECT_NE(std::string(e.what()).find("pan.csv"), std::string::npos) << e.what();
    }
  }
  std::ofstream(dir + "/pan.csv") << "t,pan\nbroken\n";
  EXPECT_THROW(RunReport(dir).write(), std::runtime_error);
  // With latencies the rates chart gets a second column: the p50 bar (attraction green) right of the rates.
  std::remove((dir + "/pan.csv").c_str());
  std::ofstream(dir + "/report.json") << R"({"title": "t", "ok": true, "listened_s": 3, "topics": )"
                                      << R"({"a": {"messages": 3, "rate_hz": 1.0, "latency_ms": )"
                                      << R"({"p50": 80.0, "p95": 120.0, "samples": 3}}}})";
  RunReport(dir).write();
  const cv::Mat rates = cv::imread(dir + "/rates.png");
  ASSERT_FALSE(rates.empty());
  int green_right = 0;
  for (int y = 0; y < rates.rows; ++y)
    for (int x = rates.cols / 2; x < rates.cols; ++x)
      green_right += near(rates.at<cv::Vec3b>(y, x), colours::kAttraction);
  EXPECT_GT(green_right, 100);
  std::ifstream page2(dir + "/report.html");
  std::stringstream text2;
  text2 << page2.rdbuf();
  EXPECT_NE(text2.str().find("80.0 / 120.0"), std::string::npos);
  // A latency_ms that is not two numbers (null, text, missing p95, strings) or is huge is shown as "-" or drawn
  // within the chart; it once threw a JSON type error and no report was written at all.
  std::ofstream(dir + "/report.json")
      << R"({"title": "t", "ok": true, "listened_s": 3, "topics": {)"
      << R"("a": {"messages": 3, "rate_hz": 1.0, "latency_ms": null}, "b": {"messages": 3, "latency_ms": "slow"},)"
      << R"("c": {"messages": 3, "latency_ms": {"p50": 3.0}}, "d": {"messages": 3, "latency_ms": {"p50": "1", "p95": 2}},)"
      << R"("e": {"messages": 3, "rate_hz": 1e308, "latency_ms": {"p50": 1e308, "p95": 1.7e308}},)"
      << R"("f": {"messages": 3, "rate_hz": 2.0, "latency_ms": {"p50": -5.0, "p95": 40.0}}}})";
  EXPECT_NO_THROW(RunReport(dir).write());
  std::ifstream page3(dir + "/report.html");
  std::stringstream text3;
  text3 << page3.rdbuf();
  EXPECT_NE(text3.str().find("-5.0 / 40.0"), std::string::npos);
  EXPECT_FALSE(cv::imread(dir + "/rates.png").empty());
  // topic_report's window that never opened: the page names why the run FAILED; a malformed window is ignored.
  std::ofstream(dir + "/report.json") << R"({"title": "t", "ok": false, "listened_s": 30, "window": {"opened": false, )"
                                      << R"("problem": "the listening window never opened: goal <sent> nothing"}, )"
                                      << R"("topics": {"goal": {"messages": 0, "rate_hz": 0}}})";
  RunReport(dir).write();
  std::ifstream page4(dir + "/report.html");
  std::stringstream text4;
  text4 << page4.rdbuf();
  EXPECT_NE(
      text4.str().find("FAILED</b> (listened 30.0 s): the listening window never opened: goal &lt;sent&gt; nothing"),
      std::string::npos)
      << text4.str().substr(0, 1200);
  std::ofstream(dir + "/report.json") << R"({"title": "t", "ok": false, "window": {"problem": 3}, "topics": {}})";
  EXPECT_NO_THROW(RunReport(dir).write());
  std::ofstream(dir + "/report.json") << R"({"title": "t", "ok": false, "window": {"interrupted": 3}, "topics": {}})";
  EXPECT_NO_THROW(RunReport(dir).write());
  // The tf pairs: each with its translation or why it failed; a window shut down early says so.
  std::ofstream(dir + "/report.json")
      << R"({"title": "t", "ok": false, "listened_s": 4, "window": {"opened": true, "interrupted": true}, )"
      << R"("topics": {}, "frames": [{"parent": "map", "child": "base_link", "ok": true, "translation": [1.5, -2, 0]}, )"
      << R"({"parent": "odom", "child": "cam", "ok": false, "error": "\"cam\" does not exist"}, 7]})";
  RunReport(dir).write();
  std::ifstream page5(dir + "/report.html");
  std::stringstream text5;
  text5 << page5.rdbuf();
  EXPECT_NE(text5.str().find("(listened 4.0 s): shut down before its window ended"), std::string::npos);
  EXPECT_NE(text5.str().find("<td><code>map</code></td><td><code>base_link</code></td><td>yes</td><td>1.500, "
                             "-2.000, 0.000</td>"),
            std::string::npos)
      << text5.str();
  EXPECT_NE(text5.str().find("<tr class=\"bad\"><td><code>odom</code></td><td><code>cam</code></td><td>NO</td><td>"
                             "\"cam\" does not exist</td>"),
            std::string::npos)
      << text5.str();
  for (const char* f : {"pan.csv", "fixations.json", "report.json", "report.html", "pan.png", "rates.png"})
    std::remove((dir + "/" + f).c_str());
  rmdir(folder);
}

TEST(RunReport, PathPictureShowsTheStartAroundHomeAndNamesTheRememberedTarget)
{
  char folder[] = "/tmp/run_report_pathXXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  const std::string dir = folder;
  // A mission that starts at home (0, 0), drives to (4, 0) and back; the target at (5, 1), remembered at (5, 1.5).
  std::ofstream(dir + "/path.csv") << "t,x,y\n0,0,0\n1,2,0\n2,4,0\n3,2,0.2\n4,0.05,0\n";
  std::ofstream(dir + "/mission.json")
      << R"({"mission": "find_and_return", "target": "box", "home": [0, 0], "target_truth": [5, 1],)"
      << R"( "target_remembered": [5, 1.5], "found": true, "returned": true})";
  RunReport(dir).write();
  const cv::Mat path = cv::imread(dir + "/path.png");
  ASSERT_FALSE(path.empty());
  // The start's ring (kStartColour) shows around home's disc: the two are at the same place.
  int start = 0;
  for (int y = 0; y < path.rows - 24; ++y)  // above the legend's row
    for (int x = 0; x < path.cols; ++x)
      start += cv::Scalar(path.at<cv::Vec3b>(y, x)) == biovision_common::PathPlot::kStartColour;
  EXPECT_GT(start, 30) << "the start hidden under home";
  std::ifstream page(dir + "/report.html");
  std::stringstream text;
  text << page.rdbuf();
  EXPECT_NE(text.str().find("where the memory put it (ring)"), std::string::npos) << "path.png's marks explained";
  for (const char* f : {"path.csv", "mission.json", "report.html", "path.png"})
    std::remove((dir + "/" + f).c_str());
  rmdir(folder);
}

TEST(MonitorParameters, RejectsValuesOutsideTheirRangeByName)
{
  MonitorParameters p;
  EXPECT_NO_THROW(p.validate());
  p.tile_width = 10;
  try
  {
    p.validate();
    FAIL() << "tile_width 10 accepted";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("tile_width"), std::string::npos);
  }
  p = MonitorParameters();
  p.head_epsilon_attraction = 0;
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = MonitorParameters();
  p.rate = NAN;
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
