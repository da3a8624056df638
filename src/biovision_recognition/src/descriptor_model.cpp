#include "biovision_recognition/descriptor_model.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "biovision_common/payload_reader.hpp"
#include "biovision_common/payload_writer.hpp"
#include "biovision_common/stored_file.hpp"

using biovision_common::PayloadReader;
using biovision_common::PayloadWriter;
using biovision_common::StoredFile;

namespace biovision_recognition
{
namespace
{
constexpr char kMagic[] = "BVLDAH";
constexpr uint32_t kVersion = 3;  // 2: layout.phases; 3: layout.shape
}  // namespace

void DescriptorModel::validate() const
{
  layout.validate();
  if (bits() != 64 && bits() != 128 && bits() != 256)
    throw std::invalid_argument("DescriptorModel: bits must be 64, 128 or 256, got " + std::to_string(bits()));
  if (projection.cols() != layout.featureCount())
    throw std::invalid_argument("DescriptorModel: projection has " + std::to_string(projection.cols()) +
                                " columns, the layout gives " + std::to_string(layout.featureCount()) + " features");
  if (thresholds.size() != projection.rows())
    throw std::invalid_argument("DescriptorModel: one threshold per bit needed");
  if (!projection.allFinite() || !thresholds.allFinite())
    throw std::invalid_argument("DescriptorModel: non-finite values");
}

std::string DescriptorModel::id() const
{
  uint32_t crc = StoredFile::crc32(reinterpret_cast<const uint8_t*>(projection.data()),
                                   projection.size() * sizeof(float));
  crc = StoredFile::crc32(reinterpret_cast<const uint8_t*>(thresholds.data()), thresholds.size() * sizeof(float), crc);
  char hex[9];
  std::snprintf(hex, sizeof(hex), "%08x", crc);
  return "ldahash-" + std::to_string(bits()) + "-" + hex;
}

void DescriptorModel::save(const std::string& path) const
{
  validate();
  PayloadWriter w;
  w.putArray(layout.scales.data(), layout.scales.size());
  w.put<int32_t>(layout.orientations);
  w.put<double>(layout.patch_wavelengths);
  w.put<int32_t>(layout.pooling_diameter);
  w.put<int32_t>(layout.pooling_step);
  w.put<int32_t>(layout.phases);
  w.put<int32_t>(layout.shape.iterations);
  w.put<double>(layout.shape.window_wavelengths);
  w.put<int32_t>(layout.shape.level_offset);
  w.put<double>(layout.shape.max_anisotropy);
  w.put<int32_t>(static_cast<int32_t>(projection.rows()));
  w.put<int32_t>(static_cast<int32_t>(projection.cols()));
  std::vector<uint16_t> half(projection.size());
  for (Eigen::Index i = 0; i < projection.size(); ++i)
    half[i] = Eigen::numext::bit_cast<uint16_t>(Eigen::half(projection.data()[i]));
  w.putArray(half.data(), half.size());
  w.putArray(thresholds.data(), thresholds.size());
  w.putString(provenance);
  StoredFile::write(path, kMagic, kVersion, w.bytes());
}

DescriptorModel DescriptorModel::load(const std::string& path)
{
  return StoredFile::load<DescriptorModel>(path, kMagic, kVersion, "descriptor model", [&](PayloadReader& r) {
    DescriptorModel m;
    m.layout.scales = r.getArray<int>(16);
    m.layout.orientations = r.get<int32_t>();
    m.layout.patch_wavelengths = r.get<double>();
    m.layout.pooling_diameter = r.get<int32_t>();
    m.layout.pooling_step = r.get<int32_t>();
    m.layout.phases = r.get<int32_t>();
    m.layout.shape.iterations = r.get<int32_t>();
    m.layout.shape.window_wavelengths = r.get<double>();
    m.layout.shape.level_offset = r.get<int32_t>();
    m.layout.shape.max_anisotropy = r.get<double>();
    const int rows = r.get<int32_t>(), cols = r.get<int32_t>();
    if (rows <= 0 || rows > 512 || cols <= 0 || cols > (1 << 20))
      throw std::runtime_error("projection size " + std::to_string(rows) + " x " + std::to_string(cols));
    const auto half = r.getArray<uint16_t>(uint64_t(rows) * cols);
    if (half.size() != size_t(rows) * cols)
      throw std::runtime_error("projection has the wrong number of entries");
    m.projection.resize(rows, cols);
    for (size_t i = 0; i < half.size(); ++i)
      m.projection.data()[i] = static_cast<float>(Eigen::numext::bit_cast<Eigen::half>(half[i]));
    const auto t = r.getArray<float>(512);
    m.thresholds = Eigen::Map<const Eigen::VectorXf>(t.data(), static_cast<Eigen::Index>(t.size()));
    m.provenance = r.getString(1 << 16);
    m.validate();
    return m;
  });
}
}  // namespace biovision_recognition
