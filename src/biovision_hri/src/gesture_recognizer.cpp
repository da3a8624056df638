#include "biovision_hri/gesture_recognizer.hpp"

#include <cmath>
#include <stdexcept>

namespace biovision_hri
{
namespace
{
void check(bool ok, const std::string& message)
{
  if (!ok)
    throw std::invalid_argument("GestureRecognizer::Parameters: " + message);
}

std::shared_ptr<const biovision_recognition::V1Descriptor> checked(
    std::shared_ptr<const biovision_recognition::V1Descriptor> descriptor)
{
  if (!descriptor)
    throw std::invalid_argument("GestureRecognizer: no descriptor");
  return descriptor;
}
}  // namespace

void GestureRecognizer::Parameters::validate() const
{
  check(max_distance >= 0 && max_distance <= 64,
        "max_distance must be in [0, 64] bits, got " + std::to_string(max_distance));
  check(min_matches >= 2 && min_matches <= 50, "min_matches must be in [2, 50], got " + std::to_string(min_matches));
  check(std::isfinite(inlier_distance) && inlier_distance > 0 && inlier_distance <= 50,
        "inlier_distance must be in (0, 50] px, got " + std::to_string(inlier_distance));
  check(std::isfinite(max_rotation) && max_rotation > 0 && max_rotation <= 180,
        "max_rotation must be in (0, 180] deg, got " + std::to_string(max_rotation));
  check(max_keypoints >= 10 && max_keypoints <= 5000,
        "max_keypoints must be in [10, 5000], got " + std::to_string(max_keypoints));
  check(region_margin >= 0 && region_margin <= 100,
        "region_margin must be in [0, 100] px, got " + std::to_string(region_margin));
}

biovision_recognition::ObjectRecognizer::Parameters GestureRecognizer::recognizerParameters(const Parameters& p)
{
  p.validate();
  biovision_recognition::ObjectRecognizer::Parameters r;
  r.max_distance = p.max_distance;
  r.max_keypoints = p.max_keypoints;
  r.region_margin = p.region_margin;
  r.verifier.min_inliers = p.min_matches;
  r.verifier.inlier_distance = p.inlier_distance;
  r.verifier.max_rotation_degrees = p.max_rotation;
  return r;
}

GestureRecognizer::GestureRecognizer(std::shared_ptr<const biovision_recognition::V1Descriptor> descriptor,
                                     const Parameters& parameters)
  : descriptor_(checked(std::move(descriptor))),
    parameters_(parameters),
    recognizer_(descriptor_, recognizerParameters(parameters)),
    templates_(descriptor_->model().bits(), descriptor_->model().id())
{
}

void GestureRecognizer::setParameters(const Parameters& parameters)
{
  recognizer_.setParameters(recognizerParameters(parameters));
  parameters_ = parameters;
}

size_t GestureRecognizer::addTemplate(const cv::Mat& gray, const cv::Rect& box, const std::string& label)
{
  if (label.empty())
    throw std::invalid_argument("GestureRecognizer::addTemplate: empty label");
  biovision_recognition::ObjectView view = recognizer_.describe(gray, box, label);
  const size_t n = view.keypoints.size();
  templates_.addView(std::move(view));
  return n;
}

void GestureRecognizer::loadTemplates(const std::string& path)
{
  templates_ = biovision_recognition::ObjectMemory::load(path, descriptor_->model().id());
}

std::vector<GestureResult> GestureRecognizer::recognize(const cv::Mat& gray, const std::vector<cv::Rect>& hand_boxes)
{
  // As HandPostureClassifier::classify: an empty image had read as "no gesture", an 8-bit one threw deep inside.
  if (gray.empty() || gray.type() != CV_32FC1)
    throw std::invalid_argument("GestureRecognizer::recognize: expected a non-empty CV_32FC1 image");
  std::vector<GestureResult> results;
  results.reserve(hand_boxes.size());
  for (const cv::Rect& box : hand_boxes)
  {
    GestureResult g;
    g.box = box;
    const auto found = recognizer_.recognize(gray, {{box, 0}}, templates_);
    if (!found.empty())
    {
      g.best_label = found.front().label;
      g.matches = found.front().matches;
      g.score = found.front().score;
      if (g.best_label != parameters_.rejection_label)
        g.label = g.best_label;
    }
    results.push_back(g);
  }
  return results;
}
}  // namespace biovision_hri
