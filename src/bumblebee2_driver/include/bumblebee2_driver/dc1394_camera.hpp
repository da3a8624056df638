#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "bumblebee2_driver/bumblebee2_parameters.hpp"
#include "bumblebee2_driver/stereo_frame.hpp"

struct __dc1394_camera;
struct __dc1394_t;

namespace bumblebee2_driver
{
/// Thrown when no camera is there, it cannot be configured or a frame cannot be captured; the message says
/// which and what to check.
struct CameraError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// A Bumblebee-2 on IEEE-1394 through libdc1394 (Debian libdc1394-dev): Format7 mode 3, RAW16 (two
/// interleaved 8-bit sensors), ROI width × height, big-endian byte order (register 0x1048), frame rate by
/// packet size, exposure/shutter/gain manual or automatic; the Bayer pattern read from register 0x1040.
/// The capture code runs only with a camera; without one open() throws CameraError.
class Dc1394Camera
{
public:
  Dc1394Camera() = default;
  ~Dc1394Camera();
  Dc1394Camera(const Dc1394Camera&) = delete;
  Dc1394Camera& operator=(const Dc1394Camera&) = delete;

  /// Finds the camera (`guid` hex, "" = the first) and starts capture. Throws CameraError: "no
  /// IEEE-1394 camera found", "camera <guid> not found among …", or the failing libdc1394 call.
  void open(const Bumblebee2Parameters& parameters);
  void close();
  bool isOpen() const { return camera_ != nullptr; }
  /// The next frame's RAW16 bytes (width × height × 2), waiting for it. Throws CameraError on failure
  /// (unplugged camera): close() and open() again.
  std::vector<uint8_t> grab();
  /// The pattern register 0x1040 reported at open().
  BayerPattern bayerPattern() const { return pattern_; }
  std::string model() const { return model_; }
  std::string guid() const { return guid_; }

private:
  __dc1394_t* context_ = nullptr;
  __dc1394_camera* camera_ = nullptr;
  bool capturing_ = false;
  BayerPattern pattern_ = BayerPattern::kMono;
  std::string model_, guid_;
  int width_ = 0, height_ = 0;
};
}  // namespace bumblebee2_driver
