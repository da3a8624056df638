#include "biovision_monitor/object_plot.hpp"

#include <algorithm>
#include <string>

#include <opencv2/imgproc.hpp>

#include "biovision_monitor/drawing.hpp"

namespace biovision_monitor
{
cv::Mat ObjectPlot::render(const cv::Mat& image, const std::vector<ObjectView>& objects, cv::Size size) const
{
  double scale = 1.0;
  cv::Point2d offset;
  cv::Mat tile = fitInto(image, size, &scale, &offset);
  const cv::Scalar green(0, 230, 0);
  int free_row = 34;
  for (const ObjectView& o : objects)
  {
    const std::string label = o.label + " " + formatNumber(o.score, 2);
    if (o.box.area() > 0)
    {
      const cv::Rect box(cv::Point(int(offset.x + o.box.x * scale), int(offset.y + o.box.y * scale)),
                         cv::Point(int(offset.x + (o.box.x + o.box.width) * scale),
                                   int(offset.y + (o.box.y + o.box.height) * scale)));
      cv::rectangle(tile, box, green, 2, cv::LINE_AA);
      putLabel(tile, label, 0.4, {box.x, box.y - 3}, green, kTitleHeight + 2);
    }
    else  // no box: listed at the left
    {
      cv::putText(tile, label, {4, free_row}, cv::FONT_HERSHEY_SIMPLEX, 0.4, green, 1, cv::LINE_AA);
      free_row += 14;
    }
  }
  return tile;
}
}  // namespace biovision_monitor
