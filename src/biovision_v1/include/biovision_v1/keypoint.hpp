#pragma once

namespace biovision_v1
{
/// A V1 keypoint in image coordinates.
struct Keypoint
{
  float x = 0.f;            ///< column [image px]
  float y = 0.f;            ///< row [image px]
  float wavelength = 0.f;   ///< lambda of its scale [image px]
  float strength = 0.f;     ///< keypoint-map value K_s, relative to the scale's contrast
  float orientation = 0.f;  ///< theta of the strongest end-stopped orientation [rad, 0..pi)
};
}  // namespace biovision_v1
