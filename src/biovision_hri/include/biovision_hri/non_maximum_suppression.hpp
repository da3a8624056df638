#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_hri/detection.hpp"

namespace biovision_hri
{
/// Intersection over union of two boxes, in [0, 1] (0 for empty boxes).
double intersectionOverUnion(const cv::Rect2f& a, const cv::Rect2f& b);

/// Greedy non-maximum suppression (thesis L392): strongest first, a detection is dropped when it
/// overlaps an already kept one by IoU >= `overlap` (the thesis' "50%" without a measure; IoU is the
/// measure the evaluation uses). Returns the kept detections, strongest first; ties keep input order.
/// Throws std::invalid_argument for overlap outside (0, 1].
std::vector<Detection> nonMaximumSuppression(std::vector<Detection> detections, double overlap);
}  // namespace biovision_hri
