#include "biovision_monitor/time_series_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "biovision_monitor/drawing.hpp"

namespace biovision_monitor
{
int TimeSeriesPlot::Axes::column(double t) const
{
  return area.x + int(std::lround((t - t0) / (t1 - t0) * (area.width - 1)));
}

int TimeSeriesPlot::Axes::row(double y) const
{
  return area.br().y - 1 - int(std::lround((y - y0) / (y1 - y0) * (area.height - 1)));
}

std::vector<int> TimeSeriesPlot::labelRows(const std::vector<cv::Range>& spans, int rows, int gap)
{
  std::vector<int> ends(std::max(rows, 0), std::numeric_limits<int>::min() / 2), out;
  for (const cv::Range& s : spans)
  {
    const auto free = std::find_if(ends.begin(), ends.end(),
                                   [&](int end) { return static_cast<long long>(end) + gap <= s.start; });
    if (free == ends.end())
    {
      out.push_back(-1);
      continue;
    }
    *free = s.end;
    out.push_back(static_cast<int>(free - ends.begin()));
  }
  return out;
}

cv::Mat TimeSeriesPlot::render(const std::vector<cv::Point2d>& points, const std::vector<Mark>& marks,
                               const std::string& title, cv::Size size, Axes* axes_out) const
{
  return render(std::vector<Series>{{"", colours::kSum, points}}, marks, title, size, axes_out);
}

cv::Mat TimeSeriesPlot::render(const std::vector<Series>& series, const std::vector<Mark>& marks,
                               const std::string& title, cv::Size size, Axes* axes_out) const
{
  size.width = std::max(size.width, 160);
  size.height = std::max(size.height, 120);
  cv::Mat image(size, CV_8UC3, colours::kBackground);
  constexpr int kLabelRows = 4, kLabelRowHeight = 10;
  constexpr double kLabelFont = 0.3;
  Axes axes;
  // Marks' labels get a band of their own between the title and the plot: inside it they hid the curves.
  const int band = marks.empty() ? 0 : kLabelRows * kLabelRowHeight;
  axes.area = cv::Rect(48, 24 + band, size.width - 48 - 10, std::max(20, size.height - 24 - band - 34));
  axes.label_band = cv::Rect(axes.area.x, axes.area.y - band, axes.area.width, band);
  bool any = false;
  double t0 = INFINITY, t1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const Series& s : series)
    for (const auto& p : s.points)
      if (std::isfinite(p.x) && std::isfinite(p.y))
      {
        any = true;
        t0 = std::min(t0, p.x), t1 = std::max(t1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
      }
  if (any)
  {
    const double pad = std::max(1e-6, 0.05 * (y1 - y0));
    axes.t0 = t0, axes.t1 = t1 > t0 ? t1 : t0 + 1, axes.y0 = y0 - pad, axes.y1 = y1 + pad;
  }
  cv::rectangle(image, axes.area, colours::kAxis, 1);
  if (axes.y0 < 0 && axes.y1 > 0)
    cv::line(image, {axes.area.x, axes.row(0)}, {axes.area.br().x - 1, axes.row(0)}, colours::kGrid, 1);
  auto label = [&](const std::string& text, cv::Point at) {
    cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.38, colours::kAxis, 1, cv::LINE_AA);
  };
  label(formatNumber(axes.y1, 1), {2, axes.area.y + 10});
  label(formatNumber(axes.y0, 1), {2, axes.area.br().y - 2});
  label(formatNumber(axes.t0, 1) + " s", {axes.area.x, axes.area.br().y + 14});
  label(formatNumber(axes.t1, 1) + " s", {axes.area.br().x - 50, axes.area.br().y + 14});
  cv::putText(image, title, {axes.area.x, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45, colours::kAxis, 1, cv::LINE_AA);
  std::vector<cv::Range> spans;
  std::vector<const Mark*> shown;
  for (const Mark& m : marks)
  {
    if (!std::isfinite(m.t) || m.t < axes.t0 || m.t > axes.t1)
      continue;
    const int x = axes.column(m.t);
    for (int y = axes.label_band.y; y < axes.area.br().y; y += 6)
      cv::line(image, {x, y}, {x, std::min(y + 3, axes.area.br().y - 1)}, colours::kAttraction, 1);
    int baseline = 0;
    const int width = cv::getTextSize(m.label, cv::FONT_HERSHEY_SIMPLEX, kLabelFont, 1, &baseline).width;
    const int start = x + 2 + width <= axes.area.br().x - 2 ? x + 2 : x - 2 - width;  // right of the line if it fits
    spans.emplace_back(start, start + width);
    shown.push_back(&m);
  }
  const std::vector<int> rows = labelRows(spans, kLabelRows);
  for (size_t i = 0; i < shown.size(); ++i)
    if (rows[i] >= 0)
    {
      // On the background's colour: a neighbouring mark's dashed line would otherwise run through the letters.
      const cv::Point at(spans[i].start, axes.label_band.y + kLabelRowHeight - 1 + kLabelRowHeight * rows[i]);
      cv::rectangle(image, {at.x - 1, at.y - 8}, {spans[i].end, at.y + 1}, colours::kBackground, cv::FILLED);
      cv::putText(image, shown[i]->label, at, cv::FONT_HERSHEY_SIMPLEX, kLabelFont, colours::kAttraction, 1,
                  cv::LINE_AA);
    }
  int legend_right = size.width - 10;  // the legend fills the title's row from the right, clear of the marks' labels
  for (const Series& s : series)
  {
    std::vector<cv::Point> line;
    for (const auto& p : s.points)
      if (std::isfinite(p.x) && std::isfinite(p.y))
        line.emplace_back(axes.column(p.x), axes.row(p.y));
    if (line.size() > 1)
      cv::polylines(image, line, false, s.colour, 1, cv::LINE_AA);
    if (s.label.empty())
      continue;
    // Legend: a short stroke in the series' colour and its name.
    int baseline = 0;
    const int text = cv::getTextSize(s.label, cv::FONT_HERSHEY_SIMPLEX, 0.4, 1, &baseline).width;
    const int x = legend_right - text - 20;
    cv::line(image, {x, 12}, {x + 16, 12}, s.colour, 2);
    cv::putText(image, s.label, {x + 20, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.4, s.colour, 1, cv::LINE_AA);
    legend_right = x - 12;
  }
  if (!any)
    putTextCentred(image, "no samples", size.height / 2, colours::kAxis, 0.5);
  if (axes_out)
    *axes_out = axes;
  return image;
}
}  // namespace biovision_monitor
