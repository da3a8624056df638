#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_common/object_label.hpp"
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

  /// The one schema of a stored memory, enforced the same way when learning (addView) and when loading
  /// (load): whatever addView accepts, save writes and load reads back.
  static constexpr size_t kMaxLabelBytes = biovision_common::ObjectLabel::kMaxBytes;  ///< label length [bytes]
  static constexpr size_t kMaxViewsPerObject = 256;                                   ///< learned views of one label
  static constexpr size_t kMaxViews = 1 << 16;                                        ///< views in the whole memory
  static constexpr size_t kMaxKeypointsPerView = 1 << 16;
  static constexpr int kMaxViewSide = 1 << 14;  ///< width and height of a learned region [px]

  /// Throws std::invalid_argument naming the problem for a label that is empty, longer than kMaxLabelBytes
  /// or holds control characters (biovision_common::ObjectLabel, shared with biovision_memory).
  static void validateLabel(const std::string& label);
  /// Throws std::invalid_argument naming the field for a view that breaks the schema: its label (above), a
  /// size outside [1, kMaxViewSide] px, more than kMaxKeypointsPerView keypoints, keypoints and codes that
  /// disagree in count, a code length other than `bits`, or a keypoint value that is not finite or out of
  /// range (x in [0, width], y in [0, height], wavelength > 0, |orientation| <= 2 pi).
  static void validateView(const ObjectView& view, int bits);

  /// Adds a view (a label may have up to kMaxViewsPerObject). Throws std::invalid_argument (see
  /// validateView(), and when a limit on views is reached); *this is then unchanged.
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
  /// Throws StoredFileError when the file is missing, foreign, corrupt, truncated, of another version,
  /// built with another descriptor model, or holds a view that validateView() or the limits refuse (the
  /// message names the view and the field); *this is never modified.
  static ObjectMemory load(const std::string& path, const std::string& expected_descriptor_id);

private:
  void rebuild();
  void checkRoomFor(const ObjectView& view) const;

  int bits_;
  std::string descriptor_id_;
  std::vector<ObjectView> views_;
  BinaryCodeSet library_;
  std::vector<uint32_t> view_of_, keypoint_of_;
  mutable MultiIndexHash index_;
  mutable bool index_stale_ = true;
};
}  // namespace biovision_recognition
