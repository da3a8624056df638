#include "biovision_v1/line_edge_detector.hpp"

#include <cmath>

namespace biovision_v1
{
namespace
{
// Nearest 8-neighbour step along a unit direction: the non-maximum suppression compares with these.
cv::Point neighbourStep(const cv::Point2f& direction)
{
  return cv::Point(static_cast<int>(std::lround(direction.x)), static_cast<int>(std::lround(direction.y)));
}
}  // namespace

LineEdgeMap LineEdgeDetector::detect(const ScaleResponses& responses, const EndStoppedCells& cells) const
{
  const cv::Size size = responses.gridSize();
  const int n = responses.orientations();
  LineEdgeMap map;
  map.wavelength = responses.wavelength;
  map.decimation = responses.decimation;
  map.events = cv::Mat::zeros(size, CV_8U);
  map.orientation = cv::Mat::zeros(size, CV_8U);
  map.confidence = cv::Mat::zeros(size, CV_32F);
  const double contrast = cells.maxComplex();
  if (contrast < parameters_.min_contrast)
    return map;

  // Cross-orientation inhibition: the dominant orientation and its laterally inhibited response.
  cv::Mat best = cv::Mat::zeros(size, CV_32F), best_index = cv::Mat::zeros(size, CV_8U);
  for (int i = 0; i < n; ++i)
  {
    const cv::Mat inhibited = cells.complexCells()[i] - parameters_.lateral_inhibition * cells.singleStopped()[i];
    for (int y = 0; y < size.height; ++y)
    {
      const float* c = inhibited.ptr<float>(y);
      float* b = best.ptr<float>(y);
      uchar* bi = best_index.ptr<uchar>(y);
      for (int x = 0; x < size.width; ++x)
        if (c[x] > b[x])
        {
          b[x] = c[x];
          bi[x] = static_cast<uchar>(i);
        }
    }
  }

  std::vector<cv::Point> steps(n);
  for (int i = 0; i < n; ++i)
    steps[i] = neighbourStep(cells.normal(i));
  const float floor = static_cast<float>(parameters_.relative_threshold * contrast);
  for (int y = 1; y + 1 < size.height; ++y)
    for (int x = 1; x + 1 < size.width; ++x)
    {
      const float b = best.at<float>(y, x);
      if (b < floor)
        continue;
      const int i = best_index.at<uchar>(y, x);
      const cv::Mat& c = cells.complexCells()[i];
      const float here = c.at<float>(y, x);
      // Local energy peak across the bar (non-maximum suppression along the normal).
      const cv::Point s = steps[i];
      if (here < c.at<float>(y + s.y, x + s.x) || here < c.at<float>(y - s.y, x - s.x))
        continue;
      const double phase = std::atan2(responses.odd[i].at<float>(y, x), responses.even[i].at<float>(y, x));
      // Nearest of the four event phases: 0 line+, pi/2 edge+, +-pi line-, -pi/2 edge-.
      const int quadrant = static_cast<int>(std::lround(phase / (M_PI / 2))) & 3;
      static constexpr LineEdgeMap::Event kByQuadrant[4] = {LineEdgeMap::kLinePositive, LineEdgeMap::kEdgePositive,
                                                            LineEdgeMap::kLineNegative, LineEdgeMap::kEdgeNegative};
      map.events.at<uchar>(y, x) = kByQuadrant[quadrant];
      map.orientation.at<uchar>(y, x) = static_cast<uchar>(i);
      map.confidence.at<float>(y, x) = static_cast<float>(std::min(1.0, b / contrast));
    }
  return map;
}
}  // namespace biovision_v1
