#include "biovision_hri/linear_detector_model.hpp"

#include <cmath>
#include <stdexcept>

#include "biovision_common/payload_writer.hpp"
#include "biovision_common/stored_file.hpp"

namespace biovision_hri
{
namespace
{
const char* const kMagic = "BVHRIDET";
constexpr uint32_t kVersion = 3;  // 2: FeatureLayout::grid_step and clip; 3: aspect_ratio
}  // namespace

void LinearDetectorModel::validate() const
{
  if (kind.empty())
    throw std::invalid_argument("LinearDetectorModel: empty kind");
  layout.validate();
  if (static_cast<int>(weights.size()) != layout.featureCount())
    throw std::invalid_argument("LinearDetectorModel: " + std::to_string(weights.size()) + " weights for " +
                                std::to_string(layout.featureCount()) + " features");
  for (float w : weights)
    if (!std::isfinite(w))
      throw std::invalid_argument("LinearDetectorModel: a weight is not finite");
  if (!std::isfinite(bias))
    throw std::invalid_argument("LinearDetectorModel: the bias is not finite");
}

float LinearDetectorModel::score(const float* features) const
{
  float s = bias;
  for (size_t i = 0; i < weights.size(); ++i)
    s += weights[i] * features[i];
  return s;
}

void LinearDetectorModel::save(const std::string& path) const
{
  validate();
  biovision_common::PayloadWriter w;
  w.putString(kind);
  layout.write(w);
  w.putArray(weights.data(), weights.size());
  w.put<float>(bias);
  w.putString(provenance);
  biovision_common::StoredFile::write(path, kMagic, kVersion, w.bytes());
}

LinearDetectorModel LinearDetectorModel::load(const std::string& path)
{
  return biovision_common::StoredFile::load<LinearDetectorModel>(path, kMagic, kVersion, "detector model",
                                                                 [](biovision_common::PayloadReader& r) {
                                                                   LinearDetectorModel m;
                                                                   m.kind = r.getString(64);
                                                                   m.layout = FeatureLayout::read(r);
                                                                   m.weights = r.getArray<float>(1u << 20);
                                                                   m.bias = r.get<float>();
                                                                   m.provenance = r.getString(1u << 16);
                                                                   m.validate();
                                                                   return m;
                                                                 });
}
}  // namespace biovision_hri
