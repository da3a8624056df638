#include "biovision_sim/scene_renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace biovision_sim
{
namespace
{
constexpr float kNear = 0.05f;  // [m]
constexpr int kCylinderSides = 32;

// One mip level of a texture, sampled inline (power-of-two sizes wrap with a mask).
struct TextureLevel
{
  const cv::Mat* m;
  float scale;  // texels per metre on this level
  int mask;
  cv::Vec3f sample(float u, float v) const
  {
    const float x = u * scale - 0.5f, y = v * scale - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    const int ix = static_cast<int>(fx), iy = static_cast<int>(fy);
    const int x0 = ix & mask, x1 = (ix + 1) & mask, y0 = iy & mask, y1 = (iy + 1) & mask;
    const cv::Vec3f* r0 = m->ptr<cv::Vec3f>(y0);
    const cv::Vec3f* r1 = m->ptr<cv::Vec3f>(y1);
    return (r0[x0] * (1 - ax) + r0[x1] * ax) * (1 - ay) + (r1[x0] * (1 - ax) + r1[x1] * ax) * ay;
  }
};

TextureLevel textureLevel(const Texture& t, int level)
{
  const cv::Mat& m = t.mip(level);
  return {&m, static_cast<float>(t.texelsPerMetre() * m.cols / t.image().cols), m.cols - 1};
}

struct ClipVertex
{
  Eigen::Vector3f c;  // camera coordinates
  float u, v;
};

// Sutherland-Hodgman against z >= kNear.
int clipNear(const std::array<ClipVertex, 3>& in, std::array<ClipVertex, 4>& out)
{
  int n = 0;
  for (int i = 0; i < 3; ++i)
  {
    const ClipVertex& a = in[i];
    const ClipVertex& b = in[(i + 1) % 3];
    const bool ain = a.c.z() >= kNear, bin = b.c.z() >= kNear;
    if (ain)
      out[n++] = a;
    if (ain != bin)
    {
      const float t = (kNear - a.c.z()) / (b.c.z() - a.c.z());
      out[n++] = {a.c + t * (b.c - a.c), a.u + t * (b.u - a.u), a.v + t * (b.v - a.v)};
    }
  }
  return n;
}
}  // namespace

SceneRenderer::SceneRenderer(const World& world, int supersample) : world_(world), supersample_(supersample)
{
  if (supersample < 1 || supersample > 4)
    throw std::invalid_argument("SceneRenderer: supersample must be 1..4");
  // Floor: a grid of quads (short triangles keep texture interpolation precise near the camera).
  const float half = static_cast<float>(world.floorSize() / 2);
  const int cells = 16;
  const float step = 2 * half / cells;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
    {
      const float x0 = -half + i * step, y0 = -half + j * step, x1 = x0 + step, y1 = y0 + step;
      addQuad({x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}, {x0, y0}, {x1, y0}, {x1, y1}, {x0, y1},
              world.floorTexture());
    }
  for (const auto& o : world.objects())
  {
    if (o.shape == "cylinder")
      addCylinder(o);
    else
      addBox(o);
  }
}

void SceneRenderer::addQuad(const Eigen::Vector3f& p0, const Eigen::Vector3f& p1, const Eigen::Vector3f& p2,
                            const Eigen::Vector3f& p3, const Eigen::Vector2f& t0, const Eigen::Vector2f& t1,
                            const Eigen::Vector2f& t2, const Eigen::Vector2f& t3, int texture)
{
  // Counter-clockwise seen from outside: the normal is (p1 - p0) x (p2 - p0).
  const Eigen::Vector3f n = (p1 - p0).cross(p2 - p0).normalized();
  triangles_.push_back({{p0, t0.x(), t0.y()}, {p1, t1.x(), t1.y()}, {p2, t2.x(), t2.y()}, n, texture});
  triangles_.push_back({{p0, t0.x(), t0.y()}, {p2, t2.x(), t2.y()}, {p3, t3.x(), t3.y()}, n, texture});
}

void SceneRenderer::addBox(const World::Object& o)
{
  const Eigen::Affine3f pose = Eigen::Translation3f(o.position.cast<float>()) *
                               Eigen::AngleAxisf(static_cast<float>(o.yaw), Eigen::Vector3f::UnitZ());
  const Eigen::Vector3f h = (o.size / 2).cast<float>();
  auto P = [&](float x, float y, float z) -> Eigen::Vector3f {
    return pose * Eigen::Vector3f(x * h.x(), y * h.y(), z * h.z());
  };
  const float sx = 2 * h.x(), sy = 2 * h.y(), sz = 2 * h.z();
  // Texture coordinates in metres along each face.
  addQuad(P(1, -1, -1), P(1, 1, -1), P(1, 1, 1), P(1, -1, 1), {0, sz}, {sy, sz}, {sy, 0}, {0, 0}, o.texture);      // +x
  addQuad(P(-1, 1, -1), P(-1, -1, -1), P(-1, -1, 1), P(-1, 1, 1), {0, sz}, {sy, sz}, {sy, 0}, {0, 0}, o.texture);  // -x
  addQuad(P(1, 1, -1), P(-1, 1, -1), P(-1, 1, 1), P(1, 1, 1), {0, sz}, {sx, sz}, {sx, 0}, {0, 0}, o.texture);      // +y
  addQuad(P(-1, -1, -1), P(1, -1, -1), P(1, -1, 1), P(-1, -1, 1), {0, sz}, {sx, sz}, {sx, 0}, {0, 0}, o.texture);  // -y
  addQuad(P(-1, -1, 1), P(1, -1, 1), P(1, 1, 1), P(-1, 1, 1), {0, 0}, {sx, 0}, {sx, sy}, {0, sy}, o.texture);      // +z
  addQuad(P(-1, 1, -1), P(1, 1, -1), P(1, -1, -1), P(-1, -1, -1), {0, 0}, {sx, 0}, {sx, sy}, {0, sy}, o.texture);  // -z
}

void SceneRenderer::addCylinder(const World::Object& o)
{
  const float r = static_cast<float>(o.size.x() / 2), hz = static_cast<float>(o.size.z() / 2);
  const Eigen::Vector3f c = o.position.cast<float>();
  const float circumference = 2 * static_cast<float>(M_PI) * r;
  for (int i = 0; i < kCylinderSides; ++i)
  {
    const float a0 = static_cast<float>(2 * M_PI * i / kCylinderSides + o.yaw);
    const float a1 = static_cast<float>(2 * M_PI * (i + 1) / kCylinderSides + o.yaw);
    const Eigen::Vector3f e0(std::cos(a0) * r, std::sin(a0) * r, 0), e1(std::cos(a1) * r, std::sin(a1) * r, 0);
    const float u0 = circumference * i / kCylinderSides, u1 = circumference * (i + 1) / kCylinderSides;
    addQuad(c + e0 + Eigen::Vector3f(0, 0, -hz), c + e1 + Eigen::Vector3f(0, 0, -hz),
            c + e1 + Eigen::Vector3f(0, 0, hz), c + e0 + Eigen::Vector3f(0, 0, hz), {u0, 2 * hz}, {u1, 2 * hz}, {u1, 0},
            {u0, 0}, o.texture);
    // Caps as fans around the centre.
    const Eigen::Vector3f top = c + Eigen::Vector3f(0, 0, hz), bottom = c + Eigen::Vector3f(0, 0, -hz);
    triangles_.push_back({{top, r, r},
                          {top + e0, r + e0.x(), r + e0.y()},
                          {top + e1, r + e1.x(), r + e1.y()},
                          Eigen::Vector3f::UnitZ(),
                          o.texture});
    triangles_.push_back({{bottom, r, r},
                          {bottom + e1, r + e1.x(), r + e1.y()},
                          {bottom + e0, r + e0.x(), r + e0.y()},
                          -Eigen::Vector3f::UnitZ(),
                          o.texture});
  }
}

void SceneRenderer::render(const Eigen::Isometry3d& world_from_camera, const PinholeCamera& camera, cv::Mat& bgr,
                           cv::Mat& depth) const
{
  const int s = supersample_;
  const int W = camera.width * s, H = camera.height * s;
  const float fx = static_cast<float>(camera.fx * s), fy = static_cast<float>(camera.fy * s);
  // Pixel centres: final pixel (x, y) covers samples whose centres average to x (OpenCV convention).
  const float cx = static_cast<float>((camera.cx + 0.5) * s - 0.5),
              cy = static_cast<float>((camera.cy + 0.5) * s - 0.5);
  const Eigen::Isometry3f camera_from_world = world_from_camera.inverse().cast<float>();
  const Eigen::Vector3f camera_position = world_from_camera.translation().cast<float>();
  const Eigen::Vector3f light = world_.lightDirection().cast<float>();
  const float ambient = static_cast<float>(world_.ambient());
  const cv::Vec3b bg = world_.background();

  cv::Mat colour(H, W, CV_8UC3, cv::Scalar(bg[0], bg[1], bg[2]));
  cv::Mat inverse_depth(H, W, CV_32F, cv::Scalar(0.f));  // 1/z, 0 = nothing (z-test: larger is nearer)

  for (const Triangle& t : triangles_)
  {
    // Back-face culling in the world: the camera must be on the outer side of the face.
    if (t.normal.dot(camera_position - t.a.p) <= 0)
      continue;
    const std::array<ClipVertex, 3> tri = {{{camera_from_world * t.a.p, t.a.u, t.a.v},
                                            {camera_from_world * t.b.p, t.b.u, t.b.v},
                                            {camera_from_world * t.c.p, t.c.u, t.c.v}}};
    if (tri[0].c.z() < kNear && tri[1].c.z() < kNear && tri[2].c.z() < kNear)
      continue;
    std::array<ClipVertex, 4> poly;
    const int n = clipNear(tri, poly);
    if (n < 3)
      continue;
    const Texture& tex = *world_.textures()[t.texture];
    const float shade = ambient + (1 - ambient) * std::max(0.f, -t.normal.dot(light));
    // Screen positions and perspective terms of the clipped polygon.
    std::array<float, 4> sx, sy, iz, uz, vz;
    for (int i = 0; i < n; ++i)
    {
      iz[i] = 1.f / poly[i].c.z();
      sx[i] = fx * poly[i].c.x() * iz[i] + cx;
      sy[i] = fy * poly[i].c.y() * iz[i] + cy;
      uz[i] = poly[i].u * iz[i];
      vz[i] = poly[i].v * iz[i];
    }
    for (int k = 1; k + 1 < n; ++k)  // fan
    {
      const int i0 = 0, i1 = k, i2 = k + 1;
      const float area = (sx[i1] - sx[i0]) * (sy[i2] - sy[i0]) - (sx[i2] - sx[i0]) * (sy[i1] - sy[i0]);
      if (std::abs(area) < 1e-6f)
        continue;
      // Mip level: texels per screen pixel, from the triangle's texture and screen areas.
      const float tex_area = std::abs((poly[i1].u - poly[i0].u) * (poly[i2].v - poly[i0].v) -
                                      (poly[i2].u - poly[i0].u) * (poly[i1].v - poly[i0].v)) *
                             static_cast<float>(tex.texelsPerMetre() * tex.texelsPerMetre());
      const int level = std::max(
          0, static_cast<int>(std::floor(0.5f * std::log2(std::max(1e-12f, tex_area / std::abs(area))))));
      const TextureLevel lv = textureLevel(tex, level);
      const int bx0 = std::max(0, static_cast<int>(std::floor(std::min({sx[i0], sx[i1], sx[i2]}))));
      const int bx1 = std::min(W - 1, static_cast<int>(std::ceil(std::max({sx[i0], sx[i1], sx[i2]}))));
      const int by0 = std::max(0, static_cast<int>(std::floor(std::min({sy[i0], sy[i1], sy[i2]}))));
      const int by1 = std::min(H - 1, static_cast<int>(std::ceil(std::max({sy[i0], sy[i1], sy[i2]}))));
      if (bx0 > bx1 || by0 > by1)
        continue;
      const float inv_area = 1.f / area;
      // Edge functions e_j(x, y) = a_j x + b_j y + c_j (>= 0 inside) are the barycentric weights.
      const int idx[3] = {i0, i1, i2};
      float ea[3], eb[3], ec[3];
      for (int j = 0; j < 3; ++j)
      {
        const int p = idx[(j + 1) % 3], q = idx[(j + 2) % 3];
        ea[j] = (sy[p] - sy[q]) * inv_area;
        eb[j] = (sx[q] - sx[p]) * inv_area;
        ec[j] = (sx[p] * sy[q] - sx[q] * sy[p]) * inv_area;
      }
      // Perspective terms are linear in screen space: attr(x, y) = sum_j e_j(x, y) attr_j.
      auto plane = [&](const std::array<float, 4>& attr, float& gx, float& gy, float& g0) {
        gx = ea[0] * attr[i0] + ea[1] * attr[i1] + ea[2] * attr[i2];
        gy = eb[0] * attr[i0] + eb[1] * attr[i1] + eb[2] * attr[i2];
        g0 = ec[0] * attr[i0] + ec[1] * attr[i1] + ec[2] * attr[i2];
      };
      float zx, zy, z0, ux, uy, u0, vx, vy, v0;
      plane(iz, zx, zy, z0);
      plane(uz, ux, uy, u0);
      plane(vz, vx, vy, v0);
      for (int y = by0; y <= by1; ++y)
      {
        const float py = static_cast<float>(y);
        // The row's inside span: every edge function >= 0.
        float lo = static_cast<float>(bx0), hi = static_cast<float>(bx1);
        bool empty = false;
        for (int j = 0; j < 3 && !empty; ++j)
        {
          const float rest = eb[j] * py + ec[j];
          if (std::abs(ea[j]) < 1e-12f)
            empty = rest < 0;
          else if (ea[j] > 0)
            lo = std::max(lo, -rest / ea[j]);
          else
            hi = std::min(hi, -rest / ea[j]);
        }
        if (empty || lo > hi)
          continue;
        const int xs = static_cast<int>(std::ceil(lo)), xe = static_cast<int>(std::floor(hi));
        float* zrow = inverse_depth.ptr<float>(y);
        cv::Vec3b* crow = colour.ptr<cv::Vec3b>(y);
        float z_inv = zx * xs + zy * py + z0, uzv = ux * xs + uy * py + u0, vzv = vx * xs + vy * py + v0;
        for (int x = xs; x <= xe; ++x, z_inv += zx, uzv += ux, vzv += vx)
        {
          if (z_inv <= zrow[x])
            continue;
          zrow[x] = z_inv;
          const float z = 1.f / z_inv;
          const cv::Vec3f c = lv.sample(uzv * z, vzv * z);
          crow[x] = cv::Vec3b(cv::saturate_cast<uchar>(c[0] * shade), cv::saturate_cast<uchar>(c[1] * shade),
                              cv::saturate_cast<uchar>(c[2] * shade));
        }
      }
    }
  }
  // Box-filter the samples down: anti-aliased colour, mean inverse depth (= mean disparity).
  if (s == 1)
    bgr = colour;
  else
    cv::resize(colour, bgr, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_AREA);
  // Background samples carry no depth: average over the samples that hit geometry, and call the pixel
  // background when most of it is.
  cv::Mat mean_inverse, hit_fraction, hits;
  cv::threshold(inverse_depth, hits, 0.0, 1.0, cv::THRESH_BINARY);
  if (s == 1)
  {
    mean_inverse = inverse_depth;
    hit_fraction = hits;
  }
  else
  {
    cv::resize(inverse_depth, mean_inverse, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_AREA);
    cv::resize(hits, hit_fraction, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_AREA);
  }
  depth.create(camera.height, camera.width, CV_32F);
  for (int y = 0; y < depth.rows; ++y)
  {
    const float* m = mean_inverse.ptr<float>(y);
    const float* f = hit_fraction.ptr<float>(y);
    float* d = depth.ptr<float>(y);
    for (int x = 0; x < depth.cols; ++x)
      d[x] = f[x] >= 0.5f ? f[x] / m[x] : std::numeric_limits<float>::infinity();
  }
}
}  // namespace biovision_sim
