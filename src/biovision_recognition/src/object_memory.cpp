#include "biovision_recognition/object_memory.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "biovision_common/object_label.hpp"
#include "biovision_common/payload_reader.hpp"
#include "biovision_common/payload_writer.hpp"
#include "biovision_common/stored_file.hpp"

using biovision_common::PayloadReader;
using biovision_common::PayloadWriter;
using biovision_common::StoredFile;
using biovision_common::StoredFileError;

namespace biovision_recognition
{
namespace
{
constexpr char kMagic[] = "BVOBJMEM";
constexpr uint32_t kVersion = 1;
}  // namespace

ObjectMemory::ObjectMemory(int bits, std::string descriptor_id)
  : bits_(bits), descriptor_id_(std::move(descriptor_id)), library_(bits)
{
}

void ObjectMemory::validateLabel(const std::string& label)
{
  const std::string problem = biovision_common::ObjectLabel::problem(label);
  if (!problem.empty())
    throw std::invalid_argument(problem);
}

void ObjectMemory::validateView(const ObjectView& view, int bits)
{
  validateLabel(view.label);
  const std::string name = "view of '" + view.label + "': ";
  if (view.size.width < 1 || view.size.width > kMaxViewSide || view.size.height < 1 || view.size.height > kMaxViewSide)
    throw std::invalid_argument(name + "size " + std::to_string(view.size.width) + " x " +
                                std::to_string(view.size.height) + " px is outside [1, " +
                                std::to_string(kMaxViewSide) + "]");
  if (view.codes.bits() != bits)
    throw std::invalid_argument(name + "codes have " + std::to_string(view.codes.bits()) + " bits, the memory " +
                                std::to_string(bits));
  if (view.codes.size() != view.keypoints.size())
    throw std::invalid_argument(name + std::to_string(view.keypoints.size()) + " keypoints but " +
                                std::to_string(view.codes.size()) + " codes");
  if (view.keypoints.size() > kMaxKeypointsPerView)
    throw std::invalid_argument(name + std::to_string(view.keypoints.size()) + " keypoints, the limit is " +
                                std::to_string(kMaxKeypointsPerView));
  const auto check = [&](size_t i, const char* field, float value, double low, double high) {
    if (!std::isfinite(value) || value < low || value > high)
      throw std::invalid_argument(name + "keypoint " + std::to_string(i) + " " + field + " = " + std::to_string(value) +
                                  " is " + (std::isfinite(value) ? "outside [" : "not finite [") + std::to_string(low) +
                                  ", " + std::to_string(high) + "]");
  };
  for (size_t i = 0; i < view.keypoints.size(); ++i)
  {
    const auto& k = view.keypoints[i];
    check(i, "x", k.x, 0.0, view.size.width);
    check(i, "y", k.y, 0.0, view.size.height);
    check(i, "wavelength", k.wavelength, 1e-3, 1e6);
    check(i, "strength", k.strength, -1e30, 1e30);
    check(i, "orientation", k.orientation, -2 * M_PI, 2 * M_PI);
  }
}

void ObjectMemory::checkRoomFor(const ObjectView& view) const
{
  validateView(view, bits_);
  if (views_.size() >= kMaxViews)
    throw std::invalid_argument("the memory holds " + std::to_string(views_.size()) + " views, the limit");
  if (viewCount(view.label) >= kMaxViewsPerObject)
    throw std::invalid_argument("'" + view.label + "' has " + std::to_string(kMaxViewsPerObject) +
                                " views, the limit per object: forget it first to learn it anew");
}

void ObjectMemory::addView(ObjectView view)
{
  checkRoomFor(view);
  views_.push_back(std::move(view));
  rebuild();
}

size_t ObjectMemory::remove(const std::string& label)
{
  const size_t before = views_.size();
  views_.erase(std::remove_if(views_.begin(), views_.end(), [&](const ObjectView& v) { return v.label == label; }),
               views_.end());
  if (views_.size() != before)
    rebuild();
  return before - views_.size();
}

void ObjectMemory::clear()
{
  views_.clear();
  rebuild();
}

void ObjectMemory::rebuild()
{
  library_ = BinaryCodeSet(bits_);
  view_of_.clear();
  keypoint_of_.clear();
  for (size_t v = 0; v < views_.size(); ++v)
  {
    library_.append(views_[v].codes);
    for (size_t k = 0; k < views_[v].keypoints.size(); ++k)
    {
      view_of_.push_back(static_cast<uint32_t>(v));
      keypoint_of_.push_back(static_cast<uint32_t>(k));
    }
  }
  index_stale_ = true;
}

const MultiIndexHash& ObjectMemory::index() const
{
  if (index_stale_)
  {
    index_.build(library_);
    index_stale_ = false;
  }
  return index_;
}

std::vector<std::string> ObjectMemory::labels() const
{
  std::set<std::string> s;
  for (const auto& v : views_)
    s.insert(v.label);
  return {s.begin(), s.end()};
}

size_t ObjectMemory::viewCount(const std::string& label) const
{
  return std::count_if(views_.begin(), views_.end(), [&](const ObjectView& v) { return v.label == label; });
}

size_t ObjectMemory::keypointCount(const std::string& label) const
{
  size_t n = 0;
  for (const auto& v : views_)
    if (v.label == label)
      n += v.keypoints.size();
  return n;
}

void ObjectMemory::save(const std::string& path) const
{
  PayloadWriter w;
  w.put<int32_t>(bits_);
  w.putString(descriptor_id_);
  w.put<uint64_t>(views_.size());
  for (const auto& v : views_)
  {
    w.putString(v.label);
    w.put<int32_t>(v.size.width);
    w.put<int32_t>(v.size.height);
    w.putArray(v.keypoints.data(), v.keypoints.size());
    w.putArray(v.codes.data(), v.codes.size() * v.codes.words());
  }
  StoredFile::write(path, kMagic, kVersion, w.bytes());
}

ObjectMemory ObjectMemory::load(const std::string& path, const std::string& expected_descriptor_id)
{
  return StoredFile::load<ObjectMemory>(path, kMagic, kVersion, "object memory", [&](PayloadReader& r) {
    const int bits = r.get<int32_t>();
    if (bits != 64 && bits != 128 && bits != 256)
      throw std::runtime_error("code length " + std::to_string(bits) + " bits (64, 128 or 256)");
    const int words = BinaryCodeSet::wordsFor(bits);
    ObjectMemory memory(bits, r.getString());
    if (memory.descriptor_id_ != expected_descriptor_id)
      throw StoredFileError(path + ": built with descriptor model '" + memory.descriptor_id_ + "', this one is '" +
                            expected_descriptor_id + "'");
    const auto views = r.get<uint64_t>();
    if (views > kMaxViews)
      throw std::runtime_error(std::to_string(views) + " views, the limit is " + std::to_string(kMaxViews));
    for (uint64_t i = 0; i < views; ++i)
    {
      ObjectView v;
      // Read generously, then validate with the same rules as addView: the message names the field.
      v.label = r.getString(uint64_t(1) << 20);
      v.size.width = r.get<int32_t>();
      v.size.height = r.get<int32_t>();
      v.keypoints = r.getArray<biovision_v1::Keypoint>(kMaxKeypointsPerView);
      const auto words_read = r.getArray<uint64_t>(uint64_t(words) * kMaxKeypointsPerView);
      if (words_read.size() != v.keypoints.size() * words)
        throw std::runtime_error("view " + std::to_string(i) + " has " + std::to_string(v.keypoints.size()) +
                                 " keypoints but " + std::to_string(words_read.size() / words) + " codes");
      v.codes = BinaryCodeSet(bits, v.keypoints.size());
      std::copy(words_read.begin(), words_read.end(), v.codes.data());
      try
      {
        memory.checkRoomFor(v);
      }
      catch (const std::invalid_argument& e)
      {
        throw std::runtime_error("view " + std::to_string(i) + ": " + e.what());
      }
      memory.views_.push_back(std::move(v));
    }
    memory.rebuild();
    return memory;
  });
}
}  // namespace biovision_recognition
