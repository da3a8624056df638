#include "biovision_common/eval/middlebury_dataset.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "biovision_common/eval/portable_float_map.hpp"

namespace biovision_common
{
namespace fs = std::filesystem;

namespace
{
bool has(const fs::path& dir, const char* file)
{
  return fs::exists(dir / file);
}

cv::Mat readColour(const fs::path& file)
{
  cv::Mat m = cv::imread(file.string(), cv::IMREAD_COLOR);
  if (m.empty())
    throw std::runtime_error("stereo scene: cannot read " + file.string());
  return m;
}

// Integer-coded ground truth (PNG/PGM) -> disparity in px; 0 stays 0 (unknown).
cv::Mat readScaledDisparity(const fs::path& file, double scale)
{
  cv::Mat raw = cv::imread(file.string(), cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE);
  if (raw.empty())
    throw std::runtime_error("stereo scene: cannot read " + file.string());
  cv::Mat d;
  raw.convertTo(d, CV_32F, 1.0 / scale);
  return d;
}

cv::Mat readMask(const fs::path& file)
{
  cv::Mat m = cv::imread(file.string(), cv::IMREAD_GRAYSCALE);
  if (m.empty())
    throw std::runtime_error("stereo scene: cannot read " + file.string());
  return m > 128;  // Middlebury masks: 255 = in, 128 = occluded, 0 = unknown
}

// Non-occluded where the right view's ground truth at x - d agrees with d (Middlebury's own rule).
cv::Mat crossCheckedMask(const cv::Mat& left_gt, const cv::Mat& right_gt)
{
  cv::Mat mask = cv::Mat::zeros(left_gt.size(), CV_8U);
  for (int y = 0; y < left_gt.rows; ++y)
    for (int x = 0; x < left_gt.cols; ++x)
    {
      const float d = left_gt.at<float>(y, x);
      if (!(d > 0))
        continue;
      const int xr = static_cast<int>(std::lround(x - d));
      if (xr < 0 || xr >= right_gt.cols)
        continue;
      const float dr = right_gt.at<float>(y, xr);
      if (dr > 0 && std::abs(dr - d) <= 1.0f)
        mask.at<uchar>(y, x) = 255;
    }
  return mask;
}

int ceilMaxDisparity(const cv::Mat& gt)
{
  double mx = 0;
  for (int y = 0; y < gt.rows; ++y)
    for (int x = 0; x < gt.cols; ++x)
    {
      const float v = gt.at<float>(y, x);
      if (std::isfinite(v) && v > mx)
        mx = v;
    }
  return std::max(1, static_cast<int>(std::ceil(mx)));
}
}  // namespace

int MiddleburyDataset::readCalibNdisp(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("stereo scene: cannot read " + path);
  std::string line;
  while (std::getline(in, line))
  {
    line.erase(std::remove_if(line.begin(), line.end(), [](unsigned char c) { return std::isspace(c); }), line.end());
    if (line.rfind("ndisp=", 0) == 0)
    {
      try
      {
        const int n = std::stoi(line.substr(6));
        if (n > 0)
          return n;
      }
      catch (const std::exception&)
      {
      }
      throw std::runtime_error("stereo scene: bad ndisp in " + path);
    }
  }
  throw std::runtime_error("stereo scene: no ndisp in " + path);
}

StereoScene MiddleburyDataset::loadScene(const std::string& directory)
{
  const fs::path dir(directory);
  StereoScene s;
  s.name = dir.filename().string();
  if (has(dir, "im0.png") && has(dir, "im1.png") && has(dir, "calib.txt"))
  {
    s.layout = "v3";
    s.left = readColour(dir / "im0.png");
    s.right = readColour(dir / "im1.png");
    s.max_disparity = readCalibNdisp((dir / "calib.txt").string());
    if (has(dir, "disp0GT.pfm"))
    {
      s.ground_truth = PortableFloatMap::read((dir / "disp0GT.pfm").string());
      if (s.ground_truth.channels() != 1)
        throw std::runtime_error("stereo scene: disp0GT.pfm in " + directory + " is not single-channel");
    }
    if (has(dir, "mask0nocc.png"))
      s.nonoccluded = readMask(dir / "mask0nocc.png");
  }
  else if (has(dir, "imL.png") && has(dir, "groundtruth.png") && has(dir, "info.txt"))
  {
    s.layout = "v2-masks";
    std::ifstream info(dir / "info.txt");
    double scale = 0;
    int md = 0;
    if (!(info >> scale >> md) || scale <= 0 || md <= 0)
      throw std::runtime_error("stereo scene: bad info.txt in " + directory);
    s.left = readColour(dir / "imL.png");
    s.right = readColour(dir / "imR.png");
    s.ground_truth = readScaledDisparity(dir / "groundtruth.png", scale);
    s.max_disparity = md;
    if (has(dir, "nonocc.png"))
      s.nonoccluded = readMask(dir / "nonocc.png");
  }
  else if (has(dir, "view1.png") && has(dir, "view5.png") && has(dir, "disp1.png"))
  {
    s.layout = "2005-2006";
    s.left = readColour(dir / "view1.png");
    s.right = readColour(dir / "view5.png");
    s.ground_truth = readScaledDisparity(dir / "disp1.png", 3.0);
    if (has(dir, "disp5.png"))
      s.nonoccluded = crossCheckedMask(s.ground_truth, readScaledDisparity(dir / "disp5.png", 3.0));
  }
  else if (has(dir, "imL.png") && has(dir, "truedisp.pgm"))
  {
    s.layout = "tsukuba";
    s.left = readColour(dir / "imL.png");
    s.right = readColour(dir / "imR.png");
    s.ground_truth = readScaledDisparity(dir / "truedisp.pgm", 16.0);
    if (has(dir, "nonocc.png"))
      s.nonoccluded = readMask(dir / "nonocc.png");
  }
  else if (has(dir, "imL.png") && has(dir, "disp2.png"))
  {
    s.layout = "2003";
    s.left = readColour(dir / "imL.png");
    s.right = readColour(dir / "imR.png");
    s.ground_truth = readScaledDisparity(dir / "disp2.png", 4.0);
    if (has(dir, "disp6.png"))
      s.nonoccluded = crossCheckedMask(s.ground_truth, readScaledDisparity(dir / "disp6.png", 4.0));
  }
  else if ((has(dir, "im2.ppm") || has(dir, "im2.jpg")) && has(dir, "im6.ppm") && has(dir, "disp2.pgm"))
  {
    s.layout = "2001";
    s.left = readColour(dir / (has(dir, "im2.ppm") ? "im2.ppm" : "im2.jpg"));  // 'bull' ships only a JPEG
    s.right = readColour(dir / "im6.ppm");
    s.ground_truth = readScaledDisparity(dir / "disp2.pgm", 8.0);
    if (has(dir, "disp6.pgm"))
      s.nonoccluded = crossCheckedMask(s.ground_truth, readScaledDisparity(dir / "disp6.pgm", 8.0));
  }
  else
    throw std::runtime_error("stereo scene: no known Middlebury layout in " + directory);
  if (s.left.size() != s.right.size())
    throw std::runtime_error("stereo scene: left and right differ in size in " + directory);
  if (!s.ground_truth.empty() && s.ground_truth.size() != s.left.size())
    throw std::runtime_error("stereo scene: ground truth and image differ in size in " + directory);
  if (s.max_disparity == 0)
    s.max_disparity = s.ground_truth.empty() ? s.left.cols / 4 : ceilMaxDisparity(s.ground_truth);
  s.max_disparity = std::min(s.max_disparity, s.left.cols - 1);
  return s;
}

std::vector<StereoScene> MiddleburyDataset::load(const std::string& directory)
{
  if (!fs::is_directory(directory))
    throw std::runtime_error("stereo dataset: " + directory + " is not a folder");
  try
  {
    return {loadScene(directory)};
  }
  catch (const std::runtime_error& e)
  {
    if (std::string(e.what()).find("no known Middlebury layout") == std::string::npos)
      throw;
  }
  std::vector<fs::path> dirs;
  for (const auto& entry : fs::directory_iterator(directory))
    if (entry.is_directory())
      dirs.push_back(entry.path());
  std::sort(dirs.begin(), dirs.end());
  std::vector<StereoScene> scenes;
  for (const auto& d : dirs)
  {
    try
    {
      scenes.push_back(loadScene(d.string()));
    }
    catch (const std::runtime_error& e)
    {
      // Folders that are not scenes (notes, extra data) are passed over; broken scenes are errors.
      if (std::string(e.what()).find("no known Middlebury layout") == std::string::npos)
        throw;
    }
  }
  if (scenes.empty())
    throw std::runtime_error("stereo dataset: no scene in " + directory);
  return scenes;
}
}  // namespace biovision_common
