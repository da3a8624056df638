#include "biovision_common/eval/portable_float_map.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "biovision_common/atomic_file.hpp"

namespace biovision_common
{
namespace
{
bool hostIsLittleEndian()
{
  const std::uint16_t one = 1;
  std::uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

void swapBytes(float& v)
{
  std::uint8_t b[4];
  std::memcpy(b, &v, 4);
  std::swap(b[0], b[3]);
  std::swap(b[1], b[2]);
  std::memcpy(&v, b, 4);
}
}  // namespace

cv::Mat PortableFloatMap::read(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error("PFM " + path + ": cannot open");
  std::string magic;
  int width = 0, height = 0;
  double scale = 0;
  in >> magic >> width >> height >> scale;
  if (!in || (magic != "Pf" && magic != "PF"))
    throw std::runtime_error("PFM " + path + ": not a PFM header (magic '" + magic + "')");
  if (width <= 0 || height <= 0 || width > 100000 || height > 100000 || scale == 0)
    throw std::runtime_error("PFM " + path + ": bad size or scale in header");
  in.get();  // the single whitespace character that ends the header
  const int channels = magic == "PF" ? 3 : 1;
  cv::Mat image(height, width, channels == 3 ? CV_32FC3 : CV_32FC1);
  const bool file_little = scale < 0;
  const size_t row_bytes = size_t(width) * channels * sizeof(float);
  for (int r = 0; r < height; ++r)
  {
    // Stored bottom to top.
    char* dst = image.ptr<char>(height - 1 - r);
    in.read(dst, static_cast<std::streamsize>(row_bytes));
    if (!in)
      throw std::runtime_error("PFM " + path + ": truncated at row " + std::to_string(r));
  }
  if (file_little != hostIsLittleEndian())
    for (int r = 0; r < height; ++r)
    {
      float* p = image.ptr<float>(r);
      for (int i = 0; i < width * channels; ++i)
        swapBytes(p[i]);
    }
  return image;
}

void PortableFloatMap::write(const std::string& path, const cv::Mat& image, float scale)
{
  if (image.depth() != CV_32F || (image.channels() != 1 && image.channels() != 3) || image.empty())
    throw std::runtime_error("PFM " + path + ": can only write non-empty CV_32FC1 or CV_32FC3");
  if (scale == 0)
    throw std::runtime_error("PFM " + path + ": scale must not be 0");
  std::ostringstream out;
  out << (image.channels() == 3 ? "PF" : "Pf") << "\n" << image.cols << " " << image.rows << "\n" << scale << "\n";
  const bool file_little = scale < 0;
  std::vector<float> row(size_t(image.cols) * image.channels());
  for (int r = image.rows - 1; r >= 0; --r)
  {
    std::memcpy(row.data(), image.ptr<float>(r), row.size() * sizeof(float));
    if (file_little != hostIsLittleEndian())
      for (float& v : row)
        swapBytes(v);
    out.write(reinterpret_cast<const char*>(row.data()), static_cast<std::streamsize>(row.size() * sizeof(float)));
  }
  writeFileAtomically(path, out.str());  // throws FileError (a std::runtime_error) naming the file
}
}  // namespace biovision_common
