// PathPlot and GridView (biovision_common's plots): the map, the path, its start and end and the marks
// are drawn where their metric positions put them, in one frame.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_common/path_plot.hpp"
#include "biovision_common/plot_title.hpp"

using biovision_common::GridView;
using biovision_common::PathPlot;

namespace
{
cv::Scalar asScalar(const cv::Vec3b& v)
{
  return cv::Scalar(v[0], v[1], v[2]);
}
}  // namespace

TEST(GridView, RowZeroIsTheImagesBottomAndValuesAreShades)
{
  GridView g;
  g.width = 4;
  g.height = 3;
  g.resolution = 0.1;
  g.data.assign(12, 0);
  g.data[0] = 100;  // row 0, col 0: the map's bottom-left
  g.data[11] = -1;
  const cv::Mat image = g.toImage();
  EXPECT_EQ(image.at<uchar>(2, 0), 0);
  EXPECT_EQ(image.at<uchar>(0, 3), 160);
  EXPECT_EQ(image.at<uchar>(1, 1), 255);
  g.data.pop_back();
  EXPECT_THROW(g.toImage(), std::invalid_argument);
}

TEST(PathPlot, PathStartEndMarksAndMapShareOneMetricFrame)
{
  // A 4 x 2 m map with one occupied cell at map (3.05, 1.05); the path from (0.5, 0.5) to (3.5, 0.5); a
  // goal mark at (3.5, 1.5) and home at the start.
  GridView g;
  g.width = 40;
  g.height = 20;
  g.resolution = 0.1;
  g.data.assign(800, 0);
  g.data[10 * 40 + 30] = 100;
  const cv::Point2d origin(0.0, 0.0);
  const PathPlot::Mark goal{{3.5, 1.5}, "goal", cv::Scalar(0, 200, 255)};
  const std::vector<cv::Point2d> path = {{0.5, 0.5}, {2.0, 0.5}, {3.5, 0.5}};
  const cv::Mat image = PathPlot().render(g, origin, path, {goal}, "path", cv::Size(520, 324));
  ASSERT_EQ(image.size(), cv::Size(520, 324));
  // 5 x 3 m with the margin into 520 x 300 px below the title: 100 px per metre, x0 = -0.5, y1 = 2.5.
  auto px = [](double x, double y) {
    return cv::Point(int(std::lround(10 + (x + 0.5) * 100)), int(std::lround(24 + (2.5 - y) * 100)));
  };
  EXPECT_EQ(image.at<cv::Vec3b>(px(3.05, 1.05)), cv::Vec3b(0, 0, 0));             // the occupied cell
  EXPECT_EQ(image.at<cv::Vec3b>(px(1.05, 1.55)), cv::Vec3b(255, 255, 255));       // free cells
  EXPECT_EQ(asScalar(image.at<cv::Vec3b>(px(2.0, 0.5))), PathPlot::kPathColour);  // on the path
  EXPECT_EQ(asScalar(image.at<cv::Vec3b>(px(0.5, 0.5) + cv::Point(0, -9))),
            PathPlot::kStartColour);                                             // its start's ring
  EXPECT_EQ(asScalar(image.at<cv::Vec3b>(px(3.5, 0.5))), PathPlot::kEndColour);  // its end
  EXPECT_EQ(image.at<cv::Vec3b>(px(3.5, 1.5)), cv::Vec3b(0, 200, 255));          // the goal mark
  // Off the path, the map and the marks: the white background; 1 m above the path's middle: free map.
  EXPECT_EQ(image.at<cv::Vec3b>(px(-0.3, 2.3)), cv::Vec3b(255, 255, 255));
  EXPECT_NE(asScalar(image.at<cv::Vec3b>(px(2.0, 1.0))), PathPlot::kPathColour);
  // A ring (filled = false) leaves its centre as it was; marks are drawn over the path (home at the start).
  const PathPlot::Mark ring{{2.0, 1.5}, "ring", cv::Scalar(255, 0, 255), false};
  const PathPlot::Mark home{{0.5, 0.5}, "home", cv::Scalar(255, 0, 255)};
  const cv::Mat marked = PathPlot().render(g, origin, path, {ring, home}, "path", cv::Size(520, 324));
  EXPECT_EQ(marked.at<cv::Vec3b>(px(2.0, 1.5)), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(marked.at<cv::Vec3b>(px(2.0, 1.5) + cv::Point(6, 0)), cv::Vec3b(255, 0, 255));
  EXPECT_EQ(marked.at<cv::Vec3b>(px(0.5, 0.5)), cv::Vec3b(255, 0, 255));
  // ... and the start's ring around home stays visible (home's disc had hidden the start).
  EXPECT_EQ(asScalar(marked.at<cv::Vec3b>(px(0.5, 0.5) + cv::Point(0, -9))), PathPlot::kStartColour);
  EXPECT_EQ(asScalar(marked.at<cv::Vec3b>(px(0.5, 0.5) + cv::Point(-9, 0))), PathPlot::kStartColour);
  // Nothing at all still gives a titled tile; bad grids and sizes throw.
  EXPECT_EQ(PathPlot().render(GridView(), {}, {}, {}, "empty", cv::Size(100, 100)).size(), cv::Size(100, 100));
  EXPECT_THROW(PathPlot().render(GridView(), {}, path, {}, "small", cv::Size(63, 100)), std::invalid_argument);
  g.data.pop_back();
  EXPECT_THROW(PathPlot().render(g, origin, {}, {}, "bad", cv::Size(100, 100)), std::invalid_argument);
  g.data.push_back(0);
  g.resolution = 0;
  EXPECT_THROW(PathPlot().render(g, origin, {}, {}, "bad", cv::Size(100, 100)), std::invalid_argument);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

TEST(PathPlot, ALegendNamesThePathAndItsDiscsAtTheBottomRight)
{
  const std::vector<cv::Point2d> path = {{0.5, 2.0}, {1.0, 2.0}};  // away from the legend's corner
  const cv::Mat image = PathPlot().render(GridView(), {}, path, {}, "path", cv::Size(520, 324));
  auto count = [&](const cv::Scalar& colour) {
    int n = 0;
    for (int y = image.rows - 20; y < image.rows; ++y)
      for (int x = image.cols / 2; x < image.cols; ++x)
        n += asScalar(image.at<cv::Vec3b>(y, x)) == colour;
    return n;
  };
  EXPECT_GT(count(PathPlot::kPathColour), 20) << "the path's stroke";
  EXPECT_GT(count(PathPlot::kStartColour), 20) << "the start's ring";
  EXPECT_GT(count(PathPlot::kEndColour), 20) << "the end's disc";
  // A labelled mark in that corner puts its label elsewhere than over the legend.
  const cv::Size text(40, 10);
  const cv::Rect legend(cv::Point(300, 324 - 20), cv::Point(520, 324));
  const cv::Point o = PathPlot::labelOrigin({500, 300}, text, image.size(), 24, {legend});
  EXPECT_EQ((cv::Rect(o.x, o.y - text.height, text.width, text.height + 3) & legend).area(), 0);
}

TEST(PathPlot, ASmallPlotLeavesTheLegendOutAndFarPointsAreIgnored)
{
  const std::vector<cv::Point2d> path = {{0.0, 5.0}, {1.0, 5.0}};  // drawn mid-height: the bottom rows free
  auto bottom = [](const cv::Mat& image, const cv::Scalar& colour) {
    int n = 0;
    for (int y = image.rows - 20; y < image.rows; ++y)
      for (int x = 0; x < image.cols; ++x)
        n += asScalar(image.at<cv::Vec3b>(y, x)) == colour;
    return n;
  };
  EXPECT_EQ(bottom(PathPlot().render(GridView(), {}, path, {}, "p", cv::Size(140, 100)), PathPlot::kStartColour), 0)
      << "no legend where it would reach the scale bar";
  EXPECT_GT(bottom(PathPlot().render(GridView(), {}, path, {}, "p", cv::Size(520, 324)), PathPlot::kStartColour), 0);
  // A point 1e17 m out (the scale would underflow to 0 and draw everything at one pixel) is left out.
  std::vector<cv::Point2d> far = path;
  far.emplace_back(1e17, 0.0);
  const cv::Mat image = PathPlot().render(GridView(), {}, far, {}, "p", cv::Size(520, 324));
  int drawn = 0;
  for (int y = 0; y < image.rows - 20; ++y)
    for (int x = 0; x < image.cols; ++x)
      drawn += asScalar(image.at<cv::Vec3b>(y, x)) == PathPlot::kPathColour;
  EXPECT_GT(drawn, 200) << "the 1 m path still spans the plot";
  cv::Mat empty;
  EXPECT_NO_THROW(biovision_common::drawTitle(empty, "title"));
}

TEST(PathPlot, LabelsStayInsideTheImageAndOffTheTitle)
{
  const cv::Size image(720, 560), text(60, 10);
  // Room on the right and above: right of and above the mark.
  EXPECT_EQ(PathPlot::labelOrigin({100, 300}, text, image, 24), cv::Point(108, 294));
  // At the right edge: to the mark's left, the whole text inside.
  const cv::Point right = PathPlot::labelOrigin({700, 300}, text, image, 24);
  EXPECT_EQ(right.x, 700 - 8 - 60);
  EXPECT_LE(right.x + text.width, image.width);
  // Just below the title strip: below the mark.
  const cv::Point high = PathPlot::labelOrigin({100, 30}, text, image, 24);
  EXPECT_GE(high.y - text.height, 24);
  EXPECT_GT(high.y, 30);
  // A label wider than the room on either side starts at the left edge.
  EXPECT_EQ(PathPlot::labelOrigin({20, 300}, cv::Size(710, 10), image, 24).x, 2);
}

TEST(PathPlot, ALabelMovesOffTakenPlacesAndOffThePath)
{
  const cv::Size image(720, 560), text(60, 10);
  const cv::Point mark(300, 300);
  const cv::Point first = PathPlot::labelOrigin(mark, text, image, 24);
  const cv::Rect first_box(first.x, first.y - text.height, text.width, text.height + 3);
  // Its first place taken (another label there): the other side of the mark.
  const cv::Point moved = PathPlot::labelOrigin(mark, text, image, 24, {first_box});
  EXPECT_EQ(moved, cv::Point(300 - 8 - 60, first.y));
  // Both sides above taken: below the mark.
  const cv::Rect left_box(moved.x, moved.y - text.height, text.width, text.height + 3);
  const cv::Point below = PathPlot::labelOrigin(mark, text, image, 24, {first_box, left_box});
  EXPECT_GT(below.y, mark.y);
  // A path through the first place: moved off it.
  cv::Mat path(image, CV_8UC1, cv::Scalar(0));
  cv::line(path, {first_box.x, first_box.y + 5}, {first_box.br().x, first_box.y + 5}, cv::Scalar(255), 2);
  EXPECT_NE(PathPlot::labelOrigin(mark, text, image, 24, {}, path), first);
  // Every place taken: the one overlapping least (here the first, on a tie).
  const cv::Rect everywhere(0, 0, 720, 560);
  EXPECT_EQ(PathPlot::labelOrigin(mark, text, image, 24, {everywhere}), first);
}
