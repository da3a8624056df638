#include "biovision_v1/scale_responses.hpp"

namespace biovision_v1
{
cv::Mat ScaleResponses::complexCell(int orientation) const
{
  cv::Mat c;
  cv::magnitude(even[orientation], odd[orientation], c);
  return c;
}

std::vector<cv::Mat> ScaleResponses::complexCells() const
{
  std::vector<cv::Mat> cells(even.size());
  for (size_t i = 0; i < even.size(); ++i)
    cells[i] = complexCell(static_cast<int>(i));
  return cells;
}
}  // namespace biovision_v1
