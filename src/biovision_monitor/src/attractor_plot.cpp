#include "biovision_monitor/attractor_plot.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <biovision_attractor/forcelets.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_monitor/drawing.hpp"

namespace biovision_monitor
{
namespace
{
constexpr double kDeg = M_PI / 180.0;

double at(const std::vector<double>& v, size_t i)
{
  return i < v.size() && std::isfinite(v[i]) ? v[i] : 0.0;
}
}  // namespace

int AttractorPlot::Axes::column(double angle) const
{
  return area.x + int(std::lround((angle - angle_lo) / (angle_hi - angle_lo) * (area.width - 1)));
}

int AttractorPlot::Axes::row(double rate) const
{
  const double mid = area.y + (area.height - 1) / 2.0;
  return int(std::lround(mid - rate / rate_max * (area.height - 1) / 2.0));
}

double AttractorPlot::attractor(const AttractorView& s, size_t i, double phi) const
{
  if (model_.sine_goal || i >= s.section_angles.size())
    return 0.0;
  return model_.gain * biovision_attractor::attraction(phi, s.section_angles[i], model_.alpha_attraction,
                                                       at(s.attraction, i), model_.epsilon_attraction);
}

double AttractorPlot::repeller(const AttractorView& s, size_t i, double phi) const
{
  if (i >= s.section_angles.size())
    return 0.0;
  return model_.gain * biovision_attractor::repulsion(phi, s.section_angles[i], model_.alpha_repulsion,
                                                      std::max(0.0, at(s.repulsion, i)), model_.epsilon_repulsion);
}

double AttractorPlot::sum(const AttractorView& s, double phi) const
{
  double f = 0.0;
  if (model_.sine_goal && std::isfinite(s.target))
    f += model_.gain * biovision_attractor::sineAttraction(phi, s.target, model_.alpha_attraction);
  for (size_t i = 0; i < s.section_angles.size(); ++i)
    f += attractor(s, i, phi) + repeller(s, i, phi);
  return f;
}

std::vector<AttractorPlot::Crossing> AttractorPlot::zeroCrossings(const AttractorView& s) const
{
  std::vector<Crossing> out;
  const double step = 0.25 * kDeg;
  double a = -M_PI / 2, fa = sum(s, a);
  for (double b = a + step; b <= M_PI / 2 + 1e-12; b += step)
  {
    const double fb = sum(s, b);
    if ((fa > 0 && fb <= 0) || (fa < 0 && fb >= 0))
    {
      double lo = a, hi = b, flo = fa;
      for (int k = 0; k < 30; ++k)
      {
        const double m = 0.5 * (lo + hi), fm = sum(s, m);
        if ((flo > 0) == (fm > 0))
          lo = m, flo = fm;
        else
          hi = m;
      }
      out.push_back({0.5 * (lo + hi), fa > 0});
    }
    a = b;
    fa = fb;
  }
  return out;
}

cv::Mat AttractorPlot::render(const AttractorView& s, cv::Size size, Axes* axes_out) const
{
  size.width = std::max(size.width, 64);
  size.height = std::max(size.height, 48);
  cv::Mat image(size, CV_8UC3, colours::kBackground);
  Axes axes;
  axes.area = cv::Rect(34, 22, size.width - 34 - 6, size.height - 22 - 16);

  // Curves sampled once per column.
  const int n = axes.area.width;
  std::vector<double> phis(n), total(n);
  double peak = std::isfinite(s.rate) ? std::abs(s.rate) : 0.0;
  for (int c = 0; c < n; ++c)
  {
    phis[c] = axes.angle_lo + (axes.angle_hi - axes.angle_lo) * c / std::max(1, n - 1);
    total[c] = sum(s, phis[c]);
    if (std::isfinite(total[c]))
      peak = std::max(peak, std::abs(total[c]));
  }
  std::vector<std::vector<double>> att(s.section_angles.size()), rep(s.section_angles.size());
  for (size_t i = 0; i < s.section_angles.size(); ++i)
  {
    att[i].resize(n);
    rep[i].resize(n);
    for (int c = 0; c < n; ++c)
    {
      att[i][c] = attractor(s, i, phis[c]);
      rep[i][c] = repeller(s, i, phis[c]);
      peak = std::max({peak, std::abs(att[i][c]), std::abs(rep[i][c])});
    }
  }
  // The title's lines sit inside the plot area's top (a panel's tile title covers the image's top rows), on
  // two lines where one would run out of the plot (a panel tile's plot cut "rad/s" off). The rate axis
  // leaves them a band of their own: curves drawn through them made both unreadable.
  const std::string name = (s.controller.empty() ? std::string("attractor") : s.controller) +
                           (s.behaviour.empty() ? "" : " (" + s.behaviour + ")"),
                    state = "phi " + formatNumber(s.angle / kDeg, 0) + " deg, dphi/dt " + formatNumber(s.rate, 2) +
                            " rad/s";
  constexpr double kFont = 0.33;
  constexpr int kLineStep = 11;
  int baseline = 0;
  const std::string line = name + "  " + state;
  const bool fits = cv::getTextSize(line, cv::FONT_HERSHEY_SIMPLEX, kFont, 1, &baseline).width <= axes.area.width - 6;
  const std::vector<std::string> lines = fits ? std::vector<std::string>{line} : std::vector<std::string>{name, state};
  const double half = (axes.area.height - 1) / 2.0, band = kLineStep * double(lines.size()) + 3;
  axes.rate_max = peak > 1e-9 ? 1.1 * peak : 1.0;
  if (peak > 1e-9 && half > 2 * band)  // a tiny plot keeps its whole height for the curves
    axes.rate_max = std::max(axes.rate_max, peak * half / (half - band));

  // Grid: section boundaries, 0 deg, zero line.
  const size_t sections = s.section_angles.size();
  if (sections > 1)
  {
    const double width = (s.section_angles.back() - s.section_angles.front()) / double(sections - 1);
    for (size_t i = 0; i <= sections; ++i)
    {
      const int x = axes.column(s.section_angles.front() + (double(i) - 0.5) * width);
      if (x >= axes.area.x && x < axes.area.br().x)
        cv::line(image, {x, axes.area.y}, {x, axes.area.br().y - 1}, colours::kGrid, 1);
    }
  }
  cv::rectangle(image, axes.area, colours::kAxis, 1);
  const int zero_row = axes.row(0.0);
  cv::line(image, {axes.area.x, zero_row}, {axes.area.br().x - 1, zero_row}, colours::kAxis, 1);
  for (int deg : {-90, -45, 0, 45, 90})
  {
    const std::string label = std::to_string(deg);
    const int x = axes.column(deg * kDeg);
    cv::line(image, {x, axes.area.br().y}, {x, axes.area.br().y + 3}, colours::kAxis, 1);
    cv::putText(image, label, {x - 4 * int(label.size()), size.height - 3}, cv::FONT_HERSHEY_SIMPLEX, 0.33,
                colours::kAxis, 1, cv::LINE_AA);
  }
  cv::putText(image, formatNumber(axes.rate_max, 2), {1, axes.area.y + 8}, cv::FONT_HERSHEY_SIMPLEX, 0.3,
              colours::kAxis, 1, cv::LINE_AA);
  cv::putText(image, formatNumber(-axes.rate_max, 2), {1, axes.area.br().y - 2}, cv::FONT_HERSHEY_SIMPLEX, 0.3,
              colours::kAxis, 1, cv::LINE_AA);

  auto polyline = [&](const std::vector<double>& values, const cv::Scalar& colour, int thickness) {
    std::vector<cv::Point> points;
    points.reserve(n);
    for (int c = 0; c < n; ++c)
      if (std::isfinite(values[c]))
        points.emplace_back(axes.area.x + c, std::clamp(axes.row(values[c]), axes.area.y, axes.area.br().y - 1));
    if (points.size() > 1)
      cv::polylines(image, points, false, colour, thickness, cv::LINE_AA);
  };
  for (size_t i = 0; i < sections; ++i)
  {
    if (std::abs(at(s.attraction, i)) > 0 && !model_.sine_goal)
      polyline(att[i], colours::kAttraction, 1);
    if (at(s.repulsion, i) > 0)
      polyline(rep[i], colours::kRepulsion, 1);
  }
  polyline(total, colours::kSum, 2);

  for (const Crossing& z : zeroCrossings(s))
  {
    const cv::Point p(axes.column(z.angle), zero_row);
    if (z.stable)
      cv::circle(image, p, 4, colours::kAttraction, cv::FILLED, cv::LINE_AA);
    else
      cv::circle(image, p, 4, colours::kRepulsion, 1, cv::LINE_AA);
  }
  if (std::isfinite(s.target) && std::abs(s.target) <= M_PI / 2)
  {
    const int x = axes.column(s.target);
    for (int y = axes.area.y; y < axes.area.br().y; y += 6)
      cv::line(image, {x, y}, {x, std::min(y + 3, axes.area.br().y - 1)}, colours::kAttraction, 1);
  }
  if (std::isfinite(s.angle))
  {
    const double rate = std::isfinite(s.rate) ? s.rate : 0.0;
    const cv::Point p(axes.column(std::clamp(s.angle, axes.angle_lo, axes.angle_hi)),
                      std::clamp(axes.row(rate), axes.area.y, axes.area.br().y - 1));
    cv::circle(image, p, 5, colours::kCurrent, cv::FILLED, cv::LINE_AA);
    cv::circle(image, p, 5, colours::kAxis, 1, cv::LINE_AA);
  }
  for (size_t i = 0; i < lines.size(); ++i)
    cv::putText(image, lines[i], {axes.area.x + 3, axes.area.y + kLineStep * (1 + static_cast<int>(i))},
                cv::FONT_HERSHEY_SIMPLEX, kFont, colours::kAxis, 1, cv::LINE_AA);
  if (axes_out)
    *axes_out = axes;
  return image;
}
}  // namespace biovision_monitor
