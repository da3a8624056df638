#include "bumblebee2_driver/dc1394_camera.hpp"

#include <dc1394/dc1394.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace bumblebee2_driver
{
namespace
{
constexpr uint64_t kEndiannessRegister = 0x1048;
constexpr uint64_t kBayerRegister = 0x1040;
constexpr uint32_t kBigEndian = 0x80000001;

void check(dc1394error_t error, const char* what)
{
  if (error != DC1394_SUCCESS)
    throw CameraError(std::string(what) + " failed: " + dc1394_error_get_string(error));
}

std::string hexGuid(uint64_t guid)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(guid));
  return text;
}

void setFeature(dc1394camera_t* camera, dc1394feature_t feature, int value, const char* name)
{
  if (value < 0)
  {
    dc1394_feature_set_mode(camera, feature, DC1394_FEATURE_MODE_AUTO);  // not every camera has auto
    return;
  }
  check(dc1394_feature_set_mode(camera, feature, DC1394_FEATURE_MODE_MANUAL), name);
  uint32_t lo = 0, hi = 0;
  check(dc1394_feature_get_boundaries(camera, feature, &lo, &hi), name);
  check(dc1394_feature_set_value(camera, feature, std::clamp<uint32_t>(static_cast<uint32_t>(value), lo, hi)), name);
}
}  // namespace

Dc1394Camera::~Dc1394Camera()
{
  close();
}

void Dc1394Camera::close()
{
  if (camera_ != nullptr)
  {
    if (capturing_)
    {
      dc1394_video_set_transmission(camera_, DC1394_OFF);
      dc1394_capture_stop(camera_);
    }
    dc1394_camera_free(camera_);
  }
  camera_ = nullptr;
  capturing_ = false;
  if (context_ != nullptr)
    dc1394_free(context_);
  context_ = nullptr;
}

void Dc1394Camera::open(const Bumblebee2Parameters& p)
{
  close();
  p.validate();
  context_ = dc1394_new();
  if (context_ == nullptr)
    throw CameraError(
        "libdc1394 cannot start: no IEEE-1394 stack (is the firewire-ohci module loaded, /dev/fw* "
        "readable by this user?)");
  dc1394camera_list_t* list = nullptr;
  const dc1394error_t listed = dc1394_camera_enumerate(context_, &list);
  if (listed != DC1394_SUCCESS || list == nullptr || list->num == 0)
  {
    if (list != nullptr)
      dc1394_camera_free_list(list);
    close();
    throw CameraError("no IEEE-1394 camera found (cable, power, /dev/fw* permissions: see docs/robot.md)");
  }
  uint64_t wanted = 0;
  if (!p.guid.empty())
    wanted = std::stoull(p.guid, nullptr, 16);
  uint64_t guid = 0;
  std::string seen;
  for (uint32_t i = 0; i < list->num; ++i)
  {
    seen += (seen.empty() ? "" : ", ") + hexGuid(list->ids[i].guid);
    if (guid == 0 && (wanted == 0 || list->ids[i].guid == wanted))
      guid = list->ids[i].guid;
  }
  dc1394_camera_free_list(list);
  if (guid == 0)
  {
    close();
    throw CameraError("camera " + p.guid + " not found among " + seen);
  }
  camera_ = dc1394_camera_new(context_, guid);
  if (camera_ == nullptr)
  {
    close();
    throw CameraError("cannot open camera " + hexGuid(guid));
  }
  guid_ = hexGuid(guid);
  model_ = std::string(camera_->vendor ? camera_->vendor : "") + " " + (camera_->model ? camera_->model : "");
  try
  {
    dc1394_memory_load(camera_, 0);  // factory defaults
    check(dc1394_set_control_register(camera_, kEndiannessRegister, kBigEndian), "setting the byte order (0x1048)");
    uint32_t bayer = 0;
    check(dc1394_get_control_register(camera_, kBayerRegister, &bayer), "reading the Bayer pattern (0x1040)");
    pattern_ = bayerPatternFromRegister(bayer);
    check(dc1394_video_set_operation_mode(camera_, DC1394_OPERATION_MODE_LEGACY), "set_operation_mode");
    check(dc1394_video_set_iso_speed(camera_, DC1394_ISO_SPEED_400), "set_iso_speed 400");
    check(dc1394_video_set_mode(camera_, DC1394_VIDEO_MODE_FORMAT7_3), "set_mode Format7 mode 3");
    // Frame rate by packet size: bytes per 125 µs bus cycle, in the camera's units.
    uint32_t unit = 0, max_bytes = 0;
    check(dc1394_format7_get_packet_parameters(camera_, DC1394_VIDEO_MODE_FORMAT7_3, &unit, &max_bytes),
          "format7_get_packet_parameters");
    const double frame_bytes = 2.0 * p.width * p.height;
    uint32_t packet = static_cast<uint32_t>(std::ceil(frame_bytes * p.frame_rate * 125e-6));
    if (unit > 0)
      packet = (packet + unit - 1) / unit * unit;
    packet = std::clamp(packet, std::max<uint32_t>(unit, 1), max_bytes);
    check(dc1394_format7_set_roi(camera_, DC1394_VIDEO_MODE_FORMAT7_3, DC1394_COLOR_CODING_RAW16,
                                 static_cast<int32_t>(packet), 0, 0, p.width, p.height),
          "format7_set_roi RAW16");
    setFeature(camera_, DC1394_FEATURE_EXPOSURE, p.exposure, "exposure");
    setFeature(camera_, DC1394_FEATURE_SHUTTER, p.shutter, "shutter");
    setFeature(camera_, DC1394_FEATURE_GAIN, p.gain, "gain");
    check(dc1394_capture_setup(camera_, 4, DC1394_CAPTURE_FLAGS_DEFAULT), "capture_setup");
    capturing_ = true;
    check(dc1394_video_set_transmission(camera_, DC1394_ON), "set_transmission on");
  }
  catch (const std::exception& e)
  {
    close();
    throw CameraError(std::string("camera ") + guid_ + ": " + e.what());
  }
  width_ = p.width;
  height_ = p.height;
}

std::vector<uint8_t> Dc1394Camera::grab()
{
  if (!capturing_)
    throw CameraError("grab: the camera is not open");
  dc1394video_frame_t* frame = nullptr;
  check(dc1394_capture_dequeue(camera_, DC1394_CAPTURE_POLICY_WAIT, &frame), "capture_dequeue");
  if (frame == nullptr)
    throw CameraError("capture_dequeue returned no frame");
  const size_t expected = static_cast<size_t>(width_) * height_ * 2;
  if (frame->image_bytes < expected)
  {
    dc1394_capture_enqueue(camera_, frame);
    std::ostringstream s;
    s << "frame of " << frame->image_bytes << " bytes, expected " << expected;
    throw CameraError(s.str());
  }
  std::vector<uint8_t> bytes(frame->image, frame->image + expected);
  dc1394_capture_enqueue(camera_, frame);
  return bytes;
}
}  // namespace bumblebee2_driver
