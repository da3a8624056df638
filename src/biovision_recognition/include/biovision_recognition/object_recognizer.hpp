#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_recognition/geometric_verifier.hpp"
#include "biovision_recognition/object_memory.hpp"
#include "biovision_recognition/v1_descriptor.hpp"
#include "biovision_recognition/v1_feature_pyramid.hpp"

namespace biovision_recognition
{
/// A region to look for objects in (a salient region, or the whole image).
struct SearchRegion
{
  cv::Rect box;
  uint32_t rank = 0;
};

/// An object found in a region.
struct RecognizedObject
{
  std::string label;
  double score = 0.0;  ///< verified matches / query keypoints in the region, in [0, 1]
  int matches = 0;     ///< geometrically verified matches
  cv::Rect box;        ///< the learned view's outline mapped into the image, clipped
  uint32_t region_rank = 0;
  std::vector<cv::Point2f> match_points;  ///< the verified matches' keypoints in the image [px]: on the object
};

/// Object recognition as the robot does it (thesis 4.6): V1 keypoints at lambda ~ {6, 12, 24} inside each
/// salient region in Focus-of-Attention order, coded with the learned descriptor, matched against the
/// object memory (Hamming distance <= max_distance, the source's "< 25 of 128 bits"), then per learned
/// view: at least min_matches matches (the source's rule) that also agree on one similarity transform
/// (our addition, the source's proposed fix for look-alikes). The best view's label wins the region.
class ObjectRecognizer
{
public:
  struct Parameters
  {
    std::vector<int> keypoint_levels{1, 3, 5};  ///< pyramid levels of query keypoints (lambda 5.7, 11.3, 22.6)
    std::vector<int> template_levels{0, 1, 2, 3, 4, 5, 6};  ///< levels of learned keypoints: +-1 level of slack
    int max_distance = 24;                                  ///< Hamming radius [bits of 128]
    int max_keypoints = 400;                                ///< per region, strongest first
    int region_margin = 15;       ///< context added around a region for the filters [px] (the source's 15)
    int min_region_side = 16;     ///< smaller regions are skipped [px]
    double time_budget_ms = 0.0;  ///< stop starting new regions after this long; 0 = no limit
    /// Use the multi-index hash when the library has at least this many codes and the hash would
    /// verify under 1% of them (MultiIndexHash::candidateFraction); otherwise SIMD brute force, which
    /// matcher_bench measured faster at the default radius 24 even with 2 million codes.
    int index_min_library = 100000;
    /// The feature pyramid on coarse DFT sizes (V1FeaturePyramid::Parameters::coarse_dft_sizes): region
    /// crops of ever-new sizes then rarely rebuild the V1 kernel spectra. false only to measure that.
    bool coarse_dft_sizes = true;
    /// A view to learn needs this many keypoints. A small view's keypoints lie mostly on its outline,
    /// which a look-alike shares: in the simulated table-top, can_yellow learned from 9-10 keypoints was
    /// named on the striped mug by exactly min_matches (5) verified matches (3 of the 3 runs that learned
    /// such a view, 20 times in one CI run); views of 11-45 keypoints were never confused (7 runs). Every
    /// refused view costs recall: on COIL-100 (recognition_eval) 20 refused 18 of 216 templates and took
    /// the recognition rate from 96.3% to 90.7%; 12 is the smallest count above the confused ones.
    int min_view_keypoints = 12;
    GeometricVerifier::Parameters verifier;
  };

  struct Statistics
  {
    int regions_processed = 0;
    int regions_skipped = 0;  ///< too small, empty, or over the time budget
    int keypoints = 0;
    long kernel_spectra_built = 0;  ///< V1 kernel spectra sets built for new region sizes (cache misses)
    double milliseconds = 0.0;
  };

  ObjectRecognizer(std::shared_ptr<const V1Descriptor> descriptor, const Parameters& parameters);

  /// gray: CV_32FC1 [0, 1]. Regions are clipped to the image; none = the whole image (rank 0).
  /// At most one object per region: the best verified view.
  std::vector<RecognizedObject> recognize(const cv::Mat& gray, const std::vector<SearchRegion>& regions,
                                          const ObjectMemory& memory, Statistics* statistics = nullptr);

  /// Describes `box` of the image as a view to learn (keypoints relative to the box). Empty box = the
  /// whole image. Throws std::invalid_argument when the box does not overlap the image.
  ObjectView describe(const cv::Mat& gray, cv::Rect box, const std::string& label);
  /// Why `view` (from describe()) should not be learned, or "" when it may: fewer than
  /// max(min_view_keypoints, verifier.min_inliers) keypoints.
  std::string learnProblem(const ObjectView& view) const;

  const Parameters& parameters() const { return parameters_; }
  /// A change of coarse_dft_sizes rebuilds the pyramid (its cached kernel spectra are dropped).
  void setParameters(const Parameters& parameters);
  const V1Descriptor& descriptor() const { return *descriptor_; }

private:
  struct RegionFeatures
  {
    std::vector<biovision_v1::Keypoint> keypoints;  // image coordinates
    BinaryCodeSet codes;
  };
  RegionFeatures regionFeatures(const cv::Mat& gray, const cv::Rect& box, const std::vector<int>& levels);

  std::shared_ptr<const V1Descriptor> descriptor_;
  Parameters parameters_;
  V1FeaturePyramid pyramid_;
};
}  // namespace biovision_recognition
