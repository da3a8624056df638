#include "biovision_recognition/object_memory.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

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

void ObjectMemory::addView(ObjectView view)
{
  if (view.label.empty())
    throw std::invalid_argument("ObjectMemory: empty label");
  if (view.codes.bits() != bits_)
    throw std::invalid_argument("ObjectMemory: view codes have " + std::to_string(view.codes.bits()) +
                                " bits, the memory " + std::to_string(bits_));
  if (view.codes.size() != view.keypoints.size())
    throw std::invalid_argument("ObjectMemory: keypoints and codes differ in count");
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
    const int words = BinaryCodeSet::wordsFor(bits);
    ObjectMemory memory(bits, r.getString());
    if (memory.descriptor_id_ != expected_descriptor_id)
      throw StoredFileError(path + ": built with descriptor model '" + memory.descriptor_id_ + "', this one is '" +
                            expected_descriptor_id + "'");
    const auto views = r.get<uint64_t>();
    if (views > (1u << 24))
      throw std::runtime_error("implausible view count");
    for (uint64_t i = 0; i < views; ++i)
    {
      ObjectView v;
      v.label = r.getString();
      v.size.width = r.get<int32_t>();
      v.size.height = r.get<int32_t>();
      v.keypoints = r.getArray<biovision_v1::Keypoint>(1u << 22);
      const auto words_read = r.getArray<uint64_t>(uint64_t(words) << 22);
      if (words_read.size() != v.keypoints.size() * words)
        throw std::runtime_error("view '" + v.label + "' has " + std::to_string(v.keypoints.size()) +
                                 " keypoints but " + std::to_string(words_read.size() / words) + " codes");
      v.codes = BinaryCodeSet(bits, v.keypoints.size());
      std::copy(words_read.begin(), words_read.end(), v.codes.data());
      if (v.label.empty() || v.size.width <= 0 || v.size.height <= 0)
        throw std::runtime_error("view with an empty label or size");
      memory.views_.push_back(std::move(v));
    }
    memory.rebuild();
    return memory;
  });
}
}  // namespace biovision_recognition
