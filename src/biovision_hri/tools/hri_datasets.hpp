#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_hri/feature_layout.hpp"

namespace biovision_hri
{
/// Readers and splits of ../shared/data/hri for the training and evaluation tools (never the nodelet).
///
/// Splits are by source, never by random sample, and fixed:
/// - Caltech WebFaces crops, Oxford hand crops (no identity labels; consecutive files come from the
///   same web photos): contiguous ranges in name order, train [0, 55%), validation [55%, 70%) (parameter
///   choices), test [70%, 100%) (reported).
/// - Negative scenes (SUN via CS143): the same contiguous ranges in name order.
/// - LinTO gesture frames: per gesture in capture order (the time field of their UUID-1 names): the
///   first half gives templates, the second half is tested.
/// - Triesch postures: by person: people sorted by name, first half templates, second half tested.
enum class Split
{
  Train,
  Validation,
  Test
};

const char* toString(Split split);
Split splitFromString(const std::string& name);  ///< "train", "validation", "test"; throws otherwise

/// Files of a folder with one of the extensions (lower-case, with dot), sorted by name. Throws
/// std::runtime_error naming the folder when it does not exist or holds none.
std::vector<std::string> listImages(const std::string& folder, const std::vector<std::string>& extensions);

/// The part of a name-sorted list that belongs to `split` (contiguous ranges, see above).
std::vector<std::string> splitPart(const std::vector<std::string>& files, Split split);

/// Reads an image as CV_32FC1 in [0, 1] (biovision_v1::InputImage); throws std::runtime_error naming it.
cv::Mat readGray(const std::string& path);

/// The data root: $BIOVISION_SHARED/data/hri, else `fallback` + /data/hri.
std::string hriDataRoot(const std::string& fallback);

/// An annotated object box (VOC XML or CSV).
struct LabelledBox
{
  std::string label;
  cv::Rect box;
};
/// Objects of a Pascal VOC XML file (labelImg). Throws std::runtime_error when unreadable.
std::vector<LabelledBox> readVocBoxes(const std::string& xml_path);

/// Average precision (VOC, all-points interpolation) of scored detections against ground-truth boxes per
/// image, a detection being correct when its IoU with a not yet matched box is >= iou.
struct ScoredBox
{
  int image = 0;
  cv::Rect2f box;
  float score = 0.f;
};
struct AveragePrecision
{
  double ap = 0.0;
  double recall_at_best_f1 = 0.0, precision_at_best_f1 = 0.0;
  double max_recall = 0.0;
  int ground_truth = 0, detections = 0;
};
AveragePrecision averagePrecision(const std::vector<ScoredBox>& detections,
                                  const std::vector<std::vector<cv::Rect2f>>& ground_truth, double iou);

/// Miss rate at a false-positive-per-window rate: the threshold is the score the given fraction of negative
/// window scores exceed; miss rate = fraction of positive scores <= that threshold.
double missRateAtFppw(std::vector<float> positive_scores, std::vector<float> negative_scores, double fppw,
                      double* threshold = nullptr);

/// Positive crops of a detector kind: "face" = Caltech WebFaces 36x36 crops, "hand" = Oxford hand crops
/// 60x60 (pos/). Throws std::invalid_argument for another kind.
std::vector<std::string> positiveCrops(const std::string& root, const std::string& kind);
/// Negative crops (none for faces; Oxford neg/ for hands: they contain faces, hand negatives only).
std::vector<std::string> negativeCrops(const std::string& root, const std::string& kind);
/// Face-free scene photos (negatives/scenes).
std::vector<std::string> sceneFiles(const std::string& root);

/// `count` random square patches of the scenes (side uniform in [min_side, min(scene side, max_side)]
/// px, position uniform), as gray CV_32FC1 crops. Deterministic for a given rng state.
std::vector<cv::Mat> randomScenePatches(const std::vector<cv::Mat>& scenes, int count, cv::RNG& rng, int min_side,
                                        int max_side);

/// Window features of patches (ComplexCellFeatures::patchFeatures), one row each, computed on both
/// cores; with `mirror` every patch is followed by its left-right mirror image.
cv::Mat patchFeatureRows(const FeatureLayout& layout, const std::vector<cv::Mat>& patches, bool mirror);

/// A hand region showing a gesture, and whether it makes templates or is tested.
struct GestureSample
{
  std::string file;
  std::string label;
  cv::Rect box;       ///< the hand [px of the file's image]
  std::string group;  ///< session (LinTO) or person (Triesch)
  bool template_part = false;
};
/// LinTO frames (one box per frame; label = the file's prefix). Split by recording session: the time field
/// of the UUID-1 file names has two sessions (2021, high word 11eb and 11ec); the earlier gives templates,
/// the later is tested.
std::vector<GestureSample> lintoSamples(const std::string& root);
/// Triesch postures (train/<posture>/<person><posture>1.bmp; box = the whole crop). Split by person:
/// people sorted by name, the first half gives templates, the second half is tested.
std::vector<GestureSample> trieschSamples(const std::string& root);
}  // namespace biovision_hri
