#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_hri/complex_cell_features.hpp"
#include "biovision_hri/feature_layout.hpp"
#include "biovision_hri/gesture_recognizer.hpp"

namespace biovision_hri
{
/// Hand posture (static gesture) recognition from the appearance of the whole hand region: the region's
/// complex-cell HOG window (the face/hand detectors' features, thesis §2.3) classified one-vs-rest by
/// linear SVMs trained with LIBLINEAR. Ours, beyond the thesis: its keypoint templates (§2.4, see
/// GestureRecognizer) need many repeatable keypoints on a hand of 50-150 px and matched 2 of 25 frames of
/// another LinTO session; the shape of the whole region carries over between sessions better
/// (docs/benchmarks.md, hri_gestures_*).
///
/// Training examples are augmented: each hand region also enters rotated by +-`rotation` degrees and, with
/// `mirror`, left-right mirrored (left and right hands show the same posture). Examples labelled
/// `rejection_label` (gesture-free regions) train a class of their own; a region is given a gesture when
/// a gesture class wins with an SVM score >= `min_score`.
///
/// Not thread-safe (the feature extractor caches Gabor spectra): one instance per thread.
class HandPostureClassifier
{
public:
  struct Parameters
  {
    /// Soft-margin cost of every one-vs-rest SVM ([1e-6, 1e6]). Chosen on the validation parts of LinTO and Triesch
    /// (their template parts split again, as `gesture_eval --validation true`): 0.01 lost 5 of 41 Triesch
    /// postures, 0.03-1 within one region of each other. > 0
    double C = 0.1;
    /// In-plane rotation of the augmented copies [deg]; 0 = none. Validation: +-15 deg gained 1 of 15
    /// LinTO regions over none and lost no Triesch posture. [0, 45]
    double rotation = 15.0;
    bool mirror = true;  ///< also train on the left-right mirror image
    /// Context around the hand box: the square crop's side is max(width, height) * (1 + 2 margin).
    /// Validation (scratch program, without rejection class): 0 beat 0.1 on LinTO (11 vs 8 of 15). [0, 1]
    double margin = 0.0;
    /// The winning gesture class's SVM score needed to report it (below: no gesture). [-10, 10]
    /// Validation, with the rejection class: 0 kept 1 of 15 LinTO regions, -0.5 and -10 (no threshold) 9;
    /// gesture-free regions 0 of 200 false in all three. So the rejection class does the rejecting.
    double min_score = -10.0;
    std::string rejection_label = "none";  ///< 1-256 characters

    /// Throws std::invalid_argument naming the field and its range.
    void validate() const;
  };

  /// Throws std::invalid_argument for invalid parameters or layout.
  HandPostureClassifier(const FeatureLayout& layout, const Parameters& parameters);

  /// Adds the region `box` of a gray image (CV_32FC1 in [0, 1]) as a training example of `label`, with its
  /// augmented copies (3 rotations x 2 mirrors by default). The region is cut as a square around the box's
  /// centre (image border replicated). Throws std::invalid_argument for a label of 0 or > 256 characters,
  /// an empty or non-float image, non-finite pixels in the region, or a box that is empty, under 8 px,
  /// does not overlap the image or is more than 8 times its larger side (nothing is added then).
  void addExample(const cv::Mat& gray, const cv::Rect& box, const std::string& label);
  /// Trains one SVM per label on the examples (LIBLINEAR; needs 2-256 labels, at least one of them not the
  /// rejection label). Throws std::logic_error otherwise. The examples are kept (a later call retrains).
  void train();
  bool trained() const { return !labels_.empty(); }

  /// One result per hand box, in order; label "" when no gesture (rejection class won or score <
  /// min_score); `score` is the winning class's SVM score, `matches` 0. Throws std::logic_error when not
  /// trained, std::invalid_argument for an empty or non-float image. A box addExample() would refuse, a
  /// textureless region (all features ~0: the biases alone would pick a class) and non-finite pixels give
  /// "" with best_label "".
  std::vector<GestureResult> classify(const cv::Mat& gray, const std::vector<cv::Rect>& hand_boxes);

  /// StoredFile "BVHRIPOS" (version, byte-order mark, CRC-32, written atomically): layout, labels, weights,
  /// `provenance`. The examples are not stored. Throws std::logic_error when not trained,
  /// std::invalid_argument for what load() would refuse (labels > 256 characters, provenance > 64 KiB).
  void save(const std::string& path, const std::string& provenance) const;
  /// Replaces the layout and the trained classes with a file's. Throws biovision_common::StoredFileError
  /// for a missing, foreign, corrupt, truncated or inconsistent file (a class twice, non-finite weights)
  /// or a path that is no regular file (nothing is changed then).
  void load(const std::string& path);

  const std::vector<std::string>& labels() const { return labels_; }
  size_t exampleCount() const { return example_labels_.size(); }
  const FeatureLayout& layout() const { return features_.layout(); }
  void setParameters(const Parameters& parameters);
  const Parameters& parameters() const { return parameters_; }

  /// The square crop the classifier sees for `box` (side of the layout's window), rotated by `degrees`.
  cv::Mat regionPatch(const cv::Mat& gray, const cv::Rect& box, double degrees) const;

  /// Features with a smaller L2 norm are a textureless region (a flat patch gives exactly 0).
  static constexpr double kMinFeatureNorm = 1e-3;

private:
  ComplexCellFeatures features_;
  Parameters parameters_;
  std::vector<cv::Mat> examples_;  ///< 1 x featureCount CV_32F rows
  std::vector<std::string> example_labels_;
  std::vector<std::string> labels_;  ///< trained classes, sorted
  cv::Mat weights_;                  ///< labels x featureCount CV_32F
  std::vector<float> biases_;
};
}  // namespace biovision_hri
