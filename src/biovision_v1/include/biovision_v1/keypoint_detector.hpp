#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_v1/end_stopped_cells.hpp"
#include "biovision_v1/keypoint.hpp"
#include "biovision_v1/scale_responses.hpp"

namespace biovision_v1
{
/// Multi-scale keypoints from end-stopped cells (Rodrigues & du Buf 2006; Terzic et al. 2013).
///
/// Keypoint map of a scale, summing end-stopped cells over orientations and subtracting inhibition:
///   K(p) = [ sum_i S_i(p) + sum_i D_i(p) - g (I_t(p) + I_r(p)) ]^+
///   tangential  I_t(p) = sum_i sum_{+,-} [C_i(p +- d n_i) - C_i(p)]^+
///       (a cell beside a line or edge sees a stronger response across it: not a vertex)
///   radial      I_r(p) = sum_i sum_{+,-} [C_i(p) - r X_i(p +- d/2 n_i)]^+,  X_i = max_{|j-i| >= 45 deg} C_j
///       (along a straight line every clearly different orientation is silent; at a junction one is
///       not. Rodrigues & du Buf use only the orthogonal orientation C_{i+N/2}; that also silences
///       junctions whose lines meet at 60 deg, measured on synthetic X-junctions)
/// plus junction cells  w * sum_i [min(C_i, X_i) - b max(C_i, X_i)]^+, a balanced AND of clearly different orientations (our
/// addition: on synthetic X-junctions the end-stopped cells alone put a ring of four maxima ~0.4
/// lambda around the crossing instead of one on it).
/// Keypoints are local maxima of K over 3x3 grid samples above threshold * scale contrast, refined to
/// sub-sample position by a parabola through the neighbours, and mapped to image coordinates.
class KeypointDetector
{
public:
  struct Parameters
  {
    double threshold = 0.2;          ///< K >= threshold * scale contrast. [0, 4]
    double min_contrast = 0.01;      ///< scales whose largest complex response is below this give none
    double inhibition_gain = 1.0;    ///< g. [0, 4]
    double radial_factor = 2.0;      ///< r. [0, 8]
    double junction_weight = 0.5;    ///< w of the junction cells. [0, 4]
    double junction_balance = 0.35;  ///< b: junction cells see [min(C_i, X_i) - b max(C_i, X_i)]^+. [0, 1)
    int max_keypoints = 2000;        ///< per image, strongest first. >= 1
  };

  KeypointDetector() = default;
  explicit KeypointDetector(const Parameters& parameters) : parameters_(parameters) {}

  /// The keypoint map K_s on the grid, CV_32F, in units of the scale's contrast.
  cv::Mat keypointMap(const EndStoppedCells& cells) const;

  /// Keypoints of one scale, in image coordinates.
  std::vector<Keypoint> detect(const ScaleResponses& responses, const EndStoppedCells& cells) const;

  const Parameters& parameters() const { return parameters_; }

private:
  Parameters parameters_;
};
}  // namespace biovision_v1
