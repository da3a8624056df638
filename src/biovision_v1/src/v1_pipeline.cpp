#include "biovision_v1/v1_pipeline.hpp"

#include <algorithm>
#include <stdexcept>

#include "biovision_v1/end_stopped_cells.hpp"
#include "biovision_v1/input_image.hpp"

namespace biovision_v1
{
V1Pipeline::V1Pipeline(const Parameters& parameters)
  : parameters_(parameters),
    bank_(parameters.gabor),
    keypoint_detector_(parameters.keypoints),
    line_edge_detector_(parameters.line_edges)
{
  if (!(parameters.end_stop_offset >= 0.2 && parameters.end_stop_offset <= 2.0))
    throw std::invalid_argument("V1Pipeline: end_stop_offset outside [0.2, 2]");
  if (parameters.keypoints.max_keypoints < 1)
    throw std::invalid_argument("V1Pipeline: max_keypoints must be >= 1");
}

V1Result V1Pipeline::process(const cv::Mat& image, bool with_line_edges)
{
  const InputImage input(image);
  V1Result result;
  result.nonfinite_pixels = input.nonfinitePixels();
  result.responses = bank_.compute(input.gray());
  const int min_side = std::min(image.cols, image.rows);
  for (const ScaleResponses& scale : result.responses)
  {
    const EndStoppedCells cells(scale, parameters_.end_stop_offset);
    // A scale whose wavelength exceeds half the image sees mostly padding: no keypoints from it.
    if (2 * scale.wavelength <= min_side)
    {
      auto kps = keypoint_detector_.detect(scale, cells);
      result.keypoints.insert(result.keypoints.end(), kps.begin(), kps.end());
    }
    if (with_line_edges)
      result.line_edges.push_back(line_edge_detector_.detect(scale, cells));
  }
  std::sort(result.keypoints.begin(), result.keypoints.end(),
            [](const Keypoint& a, const Keypoint& b) { return a.strength > b.strength; });
  if (static_cast<int>(result.keypoints.size()) > parameters_.keypoints.max_keypoints)
    result.keypoints.resize(parameters_.keypoints.max_keypoints);
  return result;
}
}  // namespace biovision_v1
