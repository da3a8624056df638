#include "biovision_hri/greet_behaviour.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace biovision_hri
{
namespace
{
void check(bool ok, const std::string& message)
{
  if (!ok)
    throw std::invalid_argument("GreetBehaviour::Parameters: " + message);
}
bool positive(double v)
{
  return std::isfinite(v) && v > 0;
}
}  // namespace

void GreetBehaviour::Parameters::validate() const
{
  check(std::isfinite(pan_min) && std::isfinite(pan_max) && pan_min < pan_max, "pan_min must be below pan_max");
  check(std::isfinite(tilt_min) && std::isfinite(tilt_max) && tilt_min < tilt_max, "tilt_min must be below tilt_max");
  check(std::isfinite(look_up_tilt) && look_up_tilt >= tilt_min && look_up_tilt <= tilt_max,
        "look_up_tilt must be within [tilt_min, tilt_max], got " + std::to_string(look_up_tilt));
  check(positive(search_timeout), "search_timeout must be > 0 s");
  check(positive(lost_timeout), "lost_timeout must be > 0 s");
  check(positive(gesture_timeout), "gesture_timeout must be > 0 s");
  check(positive(centre_gain) && centre_gain <= 1.0,
        "centre_gain must be in (0, 1], got " + std::to_string(centre_gain));
  check(positive(centred_tolerance), "centred_tolerance must be > 0 rad");
  check(positive(horizontal_fov) && horizontal_fov < M_PI, "horizontal_fov must be in (0, pi) rad");
}

GreetBehaviour::GreetBehaviour(const Parameters& parameters)
{
  setParameters(parameters);
}

void GreetBehaviour::setParameters(const Parameters& parameters)
{
  parameters.validate();
  parameters_ = parameters;
}

const char* GreetBehaviour::name(State s)
{
  switch (s)
  {
    case State::Idle:
      return "idle";
    case State::LookUp:
      return "look_up";
    case State::Centre:
      return "centre";
    case State::ReadGesture:
      return "read_gesture";
  }
  return "?";
}

void GreetBehaviour::start(double t, double pan, double /*tilt*/)
{
  state_ = State::LookUp;
  started_ = last_face_ = last_t_ = t;
  pan_cmd_ = std::clamp(std::isfinite(pan) ? pan : 0.0, parameters_.pan_min, parameters_.pan_max);
  tilt_cmd_ = parameters_.look_up_tilt;
}

void GreetBehaviour::stop()
{
  state_ = State::Idle;
}

GreetBehaviour::Output GreetBehaviour::finish(const std::string& reason)
{
  state_ = State::Idle;
  Output out;
  out.finished = true;
  out.reason = reason;
  return out;
}

GreetBehaviour::Output GreetBehaviour::update(double t, const cv::Size& image_size,
                                              const std::vector<cv::Rect2f>& faces,
                                              const std::vector<std::string>& gestures, double pan, double tilt)
{
  if (state_ == State::Idle)
    return Output();
  if (t < last_t_)
    return finish("time jumped back");
  last_t_ = t;
  const Parameters& p = parameters_;

  if (!faces.empty() && image_size.width > 0 && image_size.height > 0 && std::isfinite(pan) && std::isfinite(tilt))
  {
    last_face_ = t;
    // Pinhole: focal length from the HFOV; the angle of the face centre from the optical axis.
    const double f = 0.5 * image_size.width / std::tan(0.5 * p.horizontal_fov);
    const cv::Point2f c(faces.front().x + faces.front().width / 2, faces.front().y + faces.front().height / 2);
    const double pan_error = std::atan((image_size.width / 2.0 - c.x) / f);    // + = face left of centre
    const double tilt_error = std::atan((c.y - image_size.height / 2.0) / f);  // + = face below centre
    pan_cmd_ = std::clamp(pan + p.centre_gain * pan_error, p.pan_min, p.pan_max);
    tilt_cmd_ = std::clamp(tilt + p.centre_gain * tilt_error, p.tilt_min, p.tilt_max);
    const bool centred = std::hypot(pan_error, tilt_error) < p.centred_tolerance;
    if (state_ == State::LookUp)
      state_ = State::Centre;
    if (state_ == State::Centre && centred)
    {
      state_ = State::ReadGesture;
      centred_since_ = t;
    }
  }
  else if (state_ == State::LookUp && t - started_ > p.search_timeout)
    return finish("no face");
  else if (state_ != State::LookUp && t - last_face_ > p.lost_timeout)
    return finish("face lost");

  if (state_ == State::ReadGesture)
  {
    for (const std::string& g : gestures)
    {
      const auto it = p.actions.find(g);
      if (it == p.actions.end())
        continue;
      Output out = finish("action");
      out.action = it->second;
      out.gesture = g;
      return out;
    }
    if (t - centred_since_ > p.gesture_timeout)
      return finish("no gesture");
  }
  Output out;
  out.head_active = true;
  out.pan = pan_cmd_;
  out.tilt = tilt_cmd_;
  return out;
}
}  // namespace biovision_hri
