#include "biovision_common/path_plot.hpp"
#include "biovision_common/plot_title.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace biovision_common
{
const cv::Scalar PathPlot::kPathColour(200, 80, 0), PathPlot::kStartColour(0, 150, 0), PathPlot::kEndColour(0, 0, 210);

namespace
{
const cv::Scalar kBackground(255, 255, 255), kAxis(0, 0, 0);
constexpr int kStartRing = 9;  // [px] radius: outside a mark's 6 px disc at the same place

// A point to draw: finite and within 1e6 m (beyond, the metres-to-pixels scale underflows).
bool usable(cv::Point2d p)
{
  return std::abs(p.x) <= 1e6 && std::abs(p.y) <= 1e6;
}
}  // namespace

cv::Mat PathPlot::render(const GridView& grid, cv::Point2d origin, const std::vector<cv::Point2d>& path,
                         const std::vector<Mark>& marks, const std::string& title, cv::Size size) const
{
  if (size.width < 64 || size.height < 64)
    throw std::invalid_argument("PathPlot: a plot needs at least 64 x 64 px");
  const bool have_grid = grid.width > 0 || grid.height > 0;
  if (have_grid && !(grid.resolution > 0))
    throw std::invalid_argument("PathPlot: a grid needs a positive resolution");
  cv::Mat map_image;
  if (have_grid)
    map_image = grid.toImage();  // throws for a size mismatch

  // The extent in metres of everything drawn, plus a margin.
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  auto extend = [&](cv::Point2d p) {
    if (!usable(p))
      return;
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  };
  const bool grid_placeable = usable(origin) &&
                              usable(origin + cv::Point2d(grid.width * grid.resolution, grid.height * grid.resolution));
  if (have_grid && grid_placeable)
  {
    extend(origin);
    extend(origin + cv::Point2d(grid.width * grid.resolution, grid.height * grid.resolution));
  }
  for (const auto& p : path)
    extend(p);
  for (const auto& m : marks)
    extend(m.position);
  cv::Mat image(size, CV_8UC3, kBackground);
  const int top = 24;  // title strip
  if (!(x1 >= x0))
  {
    drawTitle(image, title);
    return image;
  }
  constexpr double kMargin = 0.5;
  x0 -= kMargin, y0 -= kMargin, x1 += kMargin, y1 += kMargin;
  const double scale = std::min(size.width / (x1 - x0), (size.height - top) / (y1 - y0));  // px per m
  const cv::Point2d offset((size.width - scale * (x1 - x0)) / 2, top + (size.height - top - scale * (y1 - y0)) / 2);
  auto px = [&](cv::Point2d p) {
    return cv::Point(int(std::lround(offset.x + (p.x - x0) * scale)), int(std::lround(offset.y + (y1 - p.y) * scale)));
  };

  if (have_grid && grid_placeable)
  {
    // Grid row 0 (y = origin.y) is the image's last row; place it by its corners.
    const cv::Point a = px(origin + cv::Point2d(0, grid.height * grid.resolution));
    const cv::Point b = px(origin + cv::Point2d(grid.width * grid.resolution, 0));
    const cv::Rect where(a, b);
    const cv::Rect inside = where & cv::Rect(0, 0, size.width, size.height);
    if (inside.area() > 0)
    {
      cv::Mat scaled, colour;
      cv::resize(map_image, scaled, where.size(), 0, 0, cv::INTER_NEAREST);
      cv::cvtColor(scaled, colour, cv::COLOR_GRAY2BGR);
      colour(cv::Rect(inside.tl() - where.tl(), inside.size())).copyTo(image(inside));
    }
  }
  std::vector<cv::Point> line;
  for (const auto& p : path)
    if (usable(p))
      line.push_back(px(p));
  cv::Mat path_mask(size, CV_8UC1, cv::Scalar(0));  // what labels should not cover
  std::vector<cv::Rect> taken;
  auto disc = [&](cv::Point p, int radius) {
    taken.emplace_back(p.x - radius - 1, p.y - radius - 1, 2 * radius + 3, 2 * radius + 3);
  };
  if (line.size() >= 2)
  {
    cv::polylines(image, line, false, kPathColour, 2, cv::LINE_8);
    cv::polylines(path_mask, line, false, cv::Scalar(255), 2, cv::LINE_8);
  }
  if (!line.empty())
  {
    cv::circle(image, line.back(), 5, kEndColour, cv::FILLED, cv::LINE_8);
    disc(line.back(), 5);
  }
  // Every mark first, then the labels around them.
  std::vector<std::pair<cv::Point, const Mark*>> shown;
  for (const auto& m : marks)
    if (usable(m.position))
    {
      const cv::Point p = px(m.position);
      cv::circle(image, p, 6, m.colour, m.filled ? cv::FILLED : 2, cv::LINE_8);
      disc(p, 6);
      shown.emplace_back(p, &m);
    }
  // The start as a ring around whatever mark is there: a mission starts at home, whose disc hid a start disc.
  if (!line.empty())
  {
    cv::circle(image, line.front(), kStartRing, kStartColour, 2, cv::LINE_8);
    disc(line.front(), kStartRing);
  }
  // 1 m scale bar, bottom left.
  const cv::Point bar0(10, size.height - 12), bar1(10 + int(std::lround(scale)), size.height - 12);
  cv::line(image, bar0, bar1, kAxis, 2);
  cv::putText(image, "1 m", bar1 + cv::Point(6, 4), cv::FONT_HERSHEY_SIMPLEX, 0.4, kAxis, 1, cv::LINE_AA);
  taken.emplace_back(cv::Point(bar0.x, bar0.y - 10), cv::Point(bar1.x + 36, size.height));
  // Legend, bottom right on the scale bar's row, right to left: what the discs and the path are; left out
  // where it would reach the scale bar's label (a small plot).
  struct Entry
  {
    const char* name;
    cv::Scalar colour;
    enum
    {
      kDisc,
      kRing,
      kStroke
    } glyph;
    int width;  // of the name [px]
  };
  Entry entries[] = {{"end", kEndColour, Entry::kDisc, 0},
                     {"start", kStartColour, Entry::kRing, 0},
                     {"path", kPathColour, Entry::kStroke, 0}};
  int legend_width = 0;
  for (Entry& e : entries)
  {
    int baseline = 0;
    e.width = cv::getTextSize(e.name, cv::FONT_HERSHEY_SIMPLEX, 0.4, 1, &baseline).width;
    legend_width += e.width + 24;
  }
  if (size.width - 8 - legend_width > bar1.x + 40)
  {
    int right = size.width - 8;
    for (const Entry& e : entries)
    {
      const int x = right - e.width, y = size.height - 12;
      cv::putText(image, e.name, {x, size.height - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kAxis, 1, cv::LINE_AA);
      if (e.glyph == Entry::kStroke)
        cv::line(image, {x - 22, y}, {x - 4, y}, e.colour, 2);
      else
        cv::circle(image, {x - 9, y}, 5, e.colour, e.glyph == Entry::kDisc ? cv::FILLED : 2, cv::LINE_8);
      right -= e.width + 24;
    }
    taken.emplace_back(cv::Point(right, size.height - 20), cv::Point(size.width, size.height));  // no label over it
  }
  // Each label is placed against every one before it: the first kMaxLabels only (a helper's 10,000 labelled
  // marks took 5 s; a mission report has tens).
  constexpr size_t kMaxLabels = 500;
  size_t labelled = 0;
  for (const auto& [p, m] : shown)
  {
    if (m->label.empty() || ++labelled > kMaxLabels)
      continue;
    int baseline = 0;
    const cv::Size text = cv::getTextSize(m->label, cv::FONT_HERSHEY_SIMPLEX, 0.4, 1, &baseline);
    const cv::Point o = labelOrigin(p, text, size, top, taken, path_mask);
    cv::putText(image, m->label, o, cv::FONT_HERSHEY_SIMPLEX, 0.4, m->colour, 1, cv::LINE_AA);
    taken.emplace_back(o.x, o.y - text.height, text.width, text.height + baseline);
  }
  drawTitle(image, title);
  return image;
}

cv::Point PathPlot::labelOrigin(cv::Point mark, cv::Size text, cv::Size image, int top,
                                const std::vector<cv::Rect>& taken, const cv::Mat& avoid)
{
  constexpr int kGap = 8;  // clear of the 6 px mark
  const int right = mark.x + kGap, left = mark.x - kGap - text.width;
  const int above = mark.y - 6, below = mark.y + kGap + text.height;
  const bool right_fits = right + text.width <= image.width - 2, above_fits = above - text.height >= top + 2;
  // The first choice as it always was; then the other side, the other height, both.
  const int x0 = right_fits ? right : left, x1 = right_fits ? left : right;
  const int y0 = above_fits ? above : below, y1 = above_fits ? below : above;
  const cv::Rect inside(2, top + 2, image.width - 4, image.height - top - 4);
  cv::Point best;
  double best_cost = INFINITY;
  // Beside the mark, then one line further out (clear of a path running along the mark).
  const int further = text.height + 6, out0 = y0 < mark.y ? -further : further, out1 = -out0;
  for (const cv::Point o :
       {cv::Point(x0, y0), cv::Point(x1, y0), cv::Point(x0, y1), cv::Point(x1, y1), cv::Point(x0, y0 + out0),
        cv::Point(x1, y0 + out0), cv::Point(x0, y1 + out1), cv::Point(x1, y1 + out1)})
  {
    const cv::Point c(std::max(o.x, 2), o.y);
    const cv::Rect box(c.x, c.y - text.height, text.width, text.height + 3);  // + the baseline's descenders
    double cost = (box & inside) == box ? 0.0 : 1e9;  // a place leaving the image only when all do
    for (const cv::Rect& t : taken)
      cost += 100.0 * (box & t).area();
    if (!avoid.empty() && avoid.size() == image && avoid.type() == CV_8UC1)
    {
      const cv::Rect in = box & cv::Rect(0, 0, image.width, image.height);
      if (in.area() > 0)
        cost += cv::countNonZero(avoid(in));
    }
    if (cost < best_cost)
      best_cost = cost, best = c;
    if (cost == 0.0)
      break;
  }
  return best;
}
}  // namespace biovision_common
