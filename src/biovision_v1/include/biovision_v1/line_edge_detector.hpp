#pragma once

#include "biovision_v1/end_stopped_cells.hpp"
#include "biovision_v1/line_edge_map.hpp"
#include "biovision_v1/scale_responses.hpp"

namespace biovision_v1
{
/// Line and edge events from simple and complex cells (after Rodrigues & du Buf 2009), as a local
/// energy model: an event sits where the complex response of the dominant orientation peaks across
/// the bar; the quadrature phase atan2(R^O, R^E) there says which of the four events it is (0: line+,
/// pi/2: edge+, pi: line-, -pi/2: edge-), which is the same as "R^E extremum with an R^O zero
/// crossing" (lines) or the converse (edges), but also holds on a decimated grid where lambda is two
/// samples and neighbouring samples cannot show a zero crossing.
/// - cross-orientation inhibition: only the orientation with the largest complex response at a point
///   may carry an event there;
/// - lateral inhibition: the complex response is reduced by the single end-stopped response of the
///   same orientation, which suppresses responses that leak past line and edge ends;
/// - complex cells give the confidence.
class LineEdgeDetector
{
public:
  struct Parameters
  {
    double relative_threshold = 0.1;  ///< inhibited response >= this * scale contrast. [0, 1]
    double min_contrast = 0.01;       ///< no events at all below this scale contrast (intensity units)
    double lateral_inhibition = 1.0;  ///< gain of the end-stopped inhibition. [0, 4]
  };

  LineEdgeDetector() = default;
  explicit LineEdgeDetector(const Parameters& parameters) : parameters_(parameters) {}

  LineEdgeMap detect(const ScaleResponses& responses, const EndStoppedCells& cells) const;

private:
  Parameters parameters_;
};
}  // namespace biovision_v1
