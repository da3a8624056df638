#pragma once

#include <biovision_hri/HriConfig.h>

#include "biovision_hri/gesture_recognizer.hpp"
#include "biovision_hri/greet_behaviour.hpp"
#include "biovision_hri/sliding_window_detector.hpp"

namespace biovision_hri
{
/// The one mapping of the nodelet's reconfigurable parameters (cfg/Hri.cfg) onto the core's parameter
/// structs. Does not validate: the cores' setParameters() do. Fields that are not reconfigurable (joint
/// limits, field of view, action table) keep the values of `base`.
/// Detector defaults of the node: the thresholds are read off the validation part's DET curves
/// (`detector_eval --split validation`): faces 0.5 ~ 1e-4 false positives per window (0.50 for the
/// committed model), hands 0.5 ~ 1e-3 (read for the previous hand model; not re-read)
/// (at 1e-4 the hand detector would miss ~90% on validation crops).
inline SlidingWindowDetector::Parameters nodeDetectorDefaults(double threshold, int max_detections)
{
  SlidingWindowDetector::Parameters p;
  p.threshold = threshold;
  p.max_detections = max_detections;
  return p;
}

struct HriParameters
{
  SlidingWindowDetector::Parameters face = nodeDetectorDefaults(0.5, 5), hand = nodeDetectorDefaults(0.5, 2);
  GestureRecognizer::Parameters gestures;
  GreetBehaviour::Parameters greet;
  int detection_width = 320;
  bool detect_hands = true;
  bool hands_in_salient_regions = false;
  int region_margin = 15;
  double gesture_box_scale = 1.5;
};

inline HriParameters toHriParameters(const HriConfig& c, const GreetBehaviour::Parameters& greet_base)
{
  HriParameters p;
  for (auto* d : {&p.face, &p.hand})
  {
    d->stride = c.stride;
    d->max_cell_size = c.max_cell_size;
    d->nms_overlap = c.nms_overlap;
  }
  p.face.threshold = c.face_threshold;
  p.face.min_size = c.face_min_size;
  p.face.max_size = c.face_max_size;
  p.face.max_detections = c.max_faces;
  p.hand.threshold = c.hand_threshold;
  p.hand.min_size = c.hand_min_size;
  p.hand.max_size = c.hand_max_size;
  p.hand.max_detections = c.max_hands;
  p.detection_width = c.detection_width;
  p.detect_hands = c.detect_hands;
  if (c.hand_regions != "full" && c.hand_regions != "salient")
    throw std::invalid_argument("hand_regions must be 'full' or 'salient', got '" + c.hand_regions + "'");
  p.hands_in_salient_regions = c.hand_regions == "salient";
  p.region_margin = c.region_margin;
  p.gestures.max_distance = c.gesture_max_distance;
  p.gestures.min_matches = c.gesture_min_matches;
  p.gestures.region_margin = c.region_margin;
  p.gesture_box_scale = c.gesture_box_scale;
  p.greet = greet_base;
  p.greet.look_up_tilt = c.look_up_tilt;
  p.greet.search_timeout = c.search_timeout;
  p.greet.lost_timeout = c.lost_timeout;
  p.greet.gesture_timeout = c.gesture_timeout;
  p.greet.centre_gain = c.centre_gain;
  p.greet.centred_tolerance = c.centred_tolerance;
  return p;
}
}  // namespace biovision_hri
