// render_bench: stereo frames per second of the simulator's renderer on one core, at 320x240, with
// and without anti-aliasing, on a world file. (No peer: no other renderer is packaged for this.)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include <opencv2/core/utility.hpp>

#include "biovision_sim/scene_renderer.hpp"

using namespace biovision_sim;

int main(int argc, char** argv)
{
  std::string world_file, json;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--world" && i + 1 < argc)
      world_file = argv[++i];
    else if (a == "--json" && i + 1 < argc)
      json = argv[++i];
    else
    {
      std::cerr << "usage: render_bench --world FILE [--json FILE]\n";
      return a == "--help" ? 0 : 2;
    }
  }
  if (world_file.empty())
  {
    std::cerr << "usage: render_bench --world FILE [--json FILE]\n";
    return 2;
  }
  cv::setNumThreads(1);  // the renderer is single-threaded; keep OpenCV's resize on one core too
  const World world = World::load(world_file);
  const PinholeCamera cam = PinholeCamera::fromFieldOfView(320, 240, 43 * M_PI / 180);
  // The robot's camera: 1.1 m high, looking along +x, 15 deg down; the right camera 0.12 m to its right.
  Eigen::Matrix3d optical;
  optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d left = Eigen::Isometry3d::Identity();
  left.linear() = Eigen::AngleAxisd(0.26, Eigen::Vector3d::UnitY()).toRotationMatrix() * optical;
  left.translation() << 0.0, 0.06, 1.1;
  Eigen::Isometry3d right = left * Eigen::Translation3d(0.12, 0, 0);
  char out[512];
  int n = 0;
  n += std::snprintf(out + n, sizeof out - n, "{\n  \"command\": \"rosrun biovision_sim render_bench --world %s --json FILE\",\n",
                     world_file.substr(world_file.find_last_of('/') + 1).c_str());
  for (int ss : {1, 2})
  {
    const SceneRenderer r(world, ss);
    cv::Mat img, depth;
    r.render(left, cam, img, depth);
    const int frames = 40;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i)
    {
      r.render(left, cam, img, depth);
      r.render(right, cam, img, depth);
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    n += std::snprintf(out + n, sizeof out - n, "  \"stereo_fps_320x240_supersample_%d\": %.1f,\n", ss, frames / s);
  }
  n += std::snprintf(out + n, sizeof out - n, "  \"triangles\": %zu,\n  \"notes\": \"One core. Goal: >= 30 stereo frames/s at 320x240.\"\n}\n",
                     SceneRenderer(world, 1).triangles());
  std::cout << out;
  if (!json.empty())
    std::ofstream(json) << out;
  return 0;
}
