#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_recognition/binary_code_set.hpp"
#include "biovision_recognition/multi_index_hash.hpp"
#include "biovision_v1/keypoint.hpp"

namespace biovision_recognition
{
/// One learned view of an object: its keypoints (in the view's own pixel frame) and their codes.
struct ObjectView
{
  std::string label;
  cv::Size size;  ///< the learned region [px]; keypoints lie in [0, size)
  std::vector<biovision_v1::Keypoint> keypoints;
  BinaryCodeSet codes;
};

/// The robot's object/landmark library (thesis 4.6, 5.x): several views per label, stored as a
/// versioned, checksummed file written atomically (StoredFile "BVOBJMEM" v1). The file names the
/// descriptor model it was built with; loading it with another model is refused, since its codes would
/// be meaningless. All codes are also kept flat, with a multi-index hash, for matching.
class ObjectMemory
{
public:
  /// bits: the descriptor length; descriptor_id: identifies the descriptor model (see modelId()).
  ObjectMemory(int bits, std::string descriptor_id);

  /// Adds a view (a label may have any number). Throws std::invalid_argument for an empty label, a code
  /// length that differs from the memory's, or keypoints and codes that disagree in count.
  void addView(ObjectView view);
  /// Removes every view of `label`; returns how many were removed.
  size_t remove(const std::string& label);
  void clear();

  std::vector<std::string> labels() const;  ///< sorted, unique
  size_t viewCount(const std::string& label) const;
  size_t keypointCount(const std::string& label) const;
  const std::vector<ObjectView>& views() const { return views_; }
  size_t codeCount() const { return library_.size(); }
  int bits() const { return bits_; }
  const std::string& descriptorId() const { return descriptor_id_; }

  /// All codes back to back, and for code i its view and keypoint.
  const BinaryCodeSet& library() const { return library_; }
  uint32_t viewOf(size_t code) const { return view_of_[code]; }
  uint32_t keypointOf(size_t code) const { return keypoint_of_[code]; }
  /// Built on first use after a change: adding views one by one stays linear.
  const MultiIndexHash& index() const;

  void save(const std::string& path) const;
  /// Throws StoredFileError when the file is missing, foreign, corrupt, truncated, of another version or
  /// built with another descriptor model; *this is never modified.
  static ObjectMemory load(const std::string& path, const std::string& expected_descriptor_id);

private:
  void rebuild();

  int bits_;
  std::string descriptor_id_;
  std::vector<ObjectView> views_;
  BinaryCodeSet library_;
  std::vector<uint32_t> view_of_, keypoint_of_;
  mutable MultiIndexHash index_;
  mutable bool index_stale_ = true;
};
}  // namespace biovision_recognition
