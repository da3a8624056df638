#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace biovision_hri
{
/// The look-up-and-greet behaviour of thesis §2.1 (L318, L349, L415, L432), kept minimal and ROS-free.
/// The thesis gives the sequence but no states, angles, timeouts or gesture table ([gap]); ours:
///
///   IDLE --start()--> LOOK_UP: tilt to `look_up_tilt`, pan held; wait for a face (`search_timeout`)
///   LOOK_UP --face--> CENTRE: move pan/tilt towards the strongest face by `centre_gain` of its angular
///                     offset per update, until within `centred_tolerance`
///   CENTRE --centred--> READ_GESTURE: keep centring; the first recognised gesture with an entry in the
///                     action table is the result (the robot "seems to look the person in the eyes", L415)
///   any state --no face for `lost_timeout` / search or gesture timeout--> IDLE (release the head)
///
/// Angles follow REP-103 and the URDF: pan + = left, tilt + = down [rad]. Commands are always clamped to
/// the joint limits. Image offsets become angles through the horizontal field of view (pinhole).
class GreetBehaviour
{
public:
  enum class State
  {
    Idle,
    LookUp,
    Centre,
    ReadGesture
  };

  struct Parameters
  {
    double look_up_tilt = -0.35;      ///< tilt while searching for a face [rad, + = down] (thesis: "looks up")
    double search_timeout = 8.0;      ///< give up when no face is seen this long after start [s]. > 0
    double lost_timeout = 2.0;        ///< give up when the face is lost this long [s]. > 0
    double gesture_timeout = 15.0;    ///< give up waiting for a known gesture [s]. > 0
    double centre_gain = 0.5;         ///< fraction of the face's angular offset corrected per update. (0, 1]
    double centred_tolerance = 0.05;  ///< |offset| below which the face is centred [rad]. > 0
    double horizontal_fov = 0.7505;   ///< camera HFOV [rad] (Bumblebee-2 43 deg, thesis L948). (0, pi)
    double pan_min = -1.5708, pan_max = 1.5708;    ///< joint limits [rad]
    double tilt_min = -0.7854, tilt_max = 0.7854;  ///< joint limits [rad]
    std::map<std::string, std::string> actions;    ///< gesture label -> action name (e.g. palm -> stop)

    /// Throws std::invalid_argument naming the field and its range.
    void validate() const;
  };

  /// What to do after an update.
  struct Output
  {
    bool head_active = false;      ///< the behaviour owns the head (hold the head controller)
    double pan = 0.0, tilt = 0.0;  ///< head command [rad] when head_active, inside the limits
    bool finished = false;         ///< the behaviour just returned to IDLE (release the head)
    std::string action;            ///< the action of the recognised gesture, once, when one was read
    std::string gesture;           ///< that gesture
    std::string reason;            ///< why it finished ("action", "no face", "face lost", "no gesture")
  };

  explicit GreetBehaviour(const Parameters& parameters);

  /// Starts the search from the current head pose at time t [s].
  void start(double t, double pan, double tilt);
  /// Stops and returns to IDLE.
  void stop();
  /// One step at time t [s] (monotonic within a run; a backward jump resets to IDLE). faces: face boxes
  /// [px] of an image of `image_size`, strongest first; gestures: recognised gesture labels in the hand
  /// regions of the same image; pan/tilt: the head's measured joint angles [rad].
  Output update(double t, const cv::Size& image_size, const std::vector<cv::Rect2f>& faces,
                const std::vector<std::string>& gestures, double pan, double tilt);

  State state() const { return state_; }
  static const char* name(State s);
  void setParameters(const Parameters& parameters);
  const Parameters& parameters() const { return parameters_; }

private:
  Output finish(const std::string& reason);

  Parameters parameters_;
  State state_ = State::Idle;
  double started_ = 0.0, last_face_ = 0.0, centred_since_ = 0.0, last_t_ = 0.0;
  double pan_cmd_ = 0.0, tilt_cmd_ = 0.0;
};
}  // namespace biovision_hri
