#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace biovision_common
{
/// [px] height of drawTitle's strip: what a plot's own labels keep clear of.
constexpr int kTitleHeight = 18;

/// Draws `text` (white, FONT_HERSHEY_SIMPLEX 0.45) on a dark strip kTitleHeight px high across the top of
/// `image` (CV_8UC3 BGR; the strip is the image's own pixels darkened, so what lies under it still shows):
/// the title of every report plot and of biovision_monitor's panel tiles, so that they look the same. An
/// empty image is left as it is.
void drawTitle(cv::Mat& image, const std::string& text);
}  // namespace biovision_common
