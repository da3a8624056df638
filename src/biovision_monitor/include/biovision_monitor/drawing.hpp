#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "biovision_common/plot_title.hpp"

/// Drawing helpers shared by the plots and the panel (OpenCV only). Images are CV_8UC3 BGR.
namespace biovision_monitor
{
/// Colours of every plot (BGR).
namespace colours
{
const cv::Scalar kBackground(255, 255, 255);
const cv::Scalar kAxis(0, 0, 0);
const cv::Scalar kGrid(200, 200, 200);
const cv::Scalar kAttraction(0, 150, 0);
const cv::Scalar kRepulsion(0, 0, 210);
const cv::Scalar kSum(200, 80, 0);
const cv::Scalar kCurrent(0, 140, 255);
const cv::Scalar kNoData(60, 60, 60);
const cv::Scalar kText(255, 255, 255);
const cv::Scalar kLabelPlate(20, 20, 20);  // behind box labels (putLabel)
}  // namespace colours

/// `image` (CV_8UC1 or CV_8UC3) scaled to fit inside `size` keeping its aspect ratio, centred on black.
/// `scale` and `offset` receive the mapping image px -> tile px (tile = image * scale + offset). Throws
/// std::invalid_argument for a `size` below 1 x 1.
cv::Mat fitInto(const cv::Mat& image, cv::Size size, double* scale = nullptr, cv::Point2d* offset = nullptr);

/// A tile of `size` saying "no data on <topic>" (dark grey, centred white text), for a panel whose
/// input never arrived.
cv::Mat noDataTile(const std::string& topic, cv::Size size);

/// The panel's tile titles: the report plots' strip (biovision_common), kTitleHeight px high.
using biovision_common::drawTitle;
using biovision_common::kTitleHeight;
/// The baseline origin nearest `wanted` at which `text` (FONT_HERSHEY_SIMPLEX, `scale`, thickness 1) lies
/// wholly inside `image` below row `top` (a label of a box cut by the image's edge stays readable); the
/// left or top edge wins where the text is larger than the room. Throws std::invalid_argument for a scale
/// outside (0, 100].
cv::Point textOriginInside(const cv::Mat& image, const std::string& text, double scale, cv::Point wanted, int top = 0);

/// Draws `text` (FONT_HERSHEY_SIMPLEX, `scale`, thickness 1, `colour`) at textOriginInside(image, text, scale,
/// wanted, top) on a dark plate (colours::kLabelPlate) 2 px wider on every side, so that it stays readable on
/// white salient blobs and over lines drawn before it. Returns the plate's rectangle (clipped to the image).
/// Throws std::invalid_argument as textOriginInside.
cv::Rect putLabel(cv::Mat& image, const std::string& text, double scale, cv::Point wanted, const cv::Scalar& colour,
                  int top = 0);

/// Draws `text` centred horizontally at baseline row `y`, scaled down until it fits the width.
void putTextCentred(cv::Mat& image, const std::string& text, int y, const cv::Scalar& colour, double scale = 0.5);

/// "%.*f" of `value` with `digits` decimals.
std::string formatNumber(double value, int digits);
}  // namespace biovision_monitor
