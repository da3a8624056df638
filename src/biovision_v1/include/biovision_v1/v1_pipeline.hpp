#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_v1/gabor_parameters.hpp"
#include "biovision_v1/keypoint.hpp"
#include "biovision_v1/keypoint_detector.hpp"
#include "biovision_v1/line_edge_detector.hpp"
#include "biovision_v1/line_edge_map.hpp"
#include "biovision_v1/scale_responses.hpp"
#include "biovision_v1/simple_cell_bank.hpp"

namespace biovision_v1
{
/// Everything the V1 model computes for one image.
struct V1Result
{
  std::vector<ScaleResponses> responses;  ///< simple cells per scale
  std::vector<Keypoint> keypoints;        ///< all scales, strongest first
  std::vector<LineEdgeMap> line_edges;    ///< per scale, when asked for
  int nonfinite_pixels = 0;               ///< NaN/Inf input pixels that were replaced by 0
};

/// The V1 model in one call: input conversion, simple cells, end-stopped cells, keypoints and
/// (optionally) line/edge maps. Not thread-safe: one pipeline per thread.
class V1Pipeline
{
public:
  struct Parameters
  {
    GaborParameters gabor;
    KeypointDetector::Parameters keypoints;
    LineEdgeDetector::Parameters line_edges;
    double end_stop_offset = 0.6;  ///< d in wavelengths. [0.2, 2]
  };

  explicit V1Pipeline(const Parameters& parameters);

  /// image: any depth/channels InputImage accepts. Throws std::invalid_argument on bad input.
  V1Result process(const cv::Mat& image, bool with_line_edges = false);

  const Parameters& parameters() const { return parameters_; }

private:
  Parameters parameters_;
  SimpleCellBank bank_;
  KeypointDetector keypoint_detector_;
  LineEdgeDetector line_edge_detector_;
};
}  // namespace biovision_v1
