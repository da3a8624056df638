// render_bench: stereo frames per second of the simulator's renderer on one core, at 320x240, with
// and without anti-aliasing, on a world file. (No peer: no other renderer is packaged for this.)
#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

#include <opencv2/core/utility.hpp>

#include "biovision_common/tool_options.hpp"
#include "biovision_sim/scene_renderer.hpp"

using namespace biovision_sim;

int main(int argc, char** argv)
{
  std::string world_file, json_path;
  biovision_common::ToolOptions options("render_bench",
                                        "Stereo frames per second of the simulator's renderer on one core at 320x240, "
                                        "with and without anti-aliasing. Prints the JSON figures.");
  options.app().add_option("--world", world_file, "world file (config/worlds/*.yaml)")->required();
  options.app().add_option("--json", json_path, "also write the figures to this file");
  options.parse(argc, argv);
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
  nlohmann::ordered_json figures;
  const std::string world_name = world_file.substr(world_file.find_last_of('/') + 1);
  figures["command"] = "rosrun biovision_sim render_bench --world " + world_name + " --json FILE";
  for (int supersample : {1, 2})
  {
    const SceneRenderer r(world, supersample);
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
    figures["stereo_fps_320x240_supersample_" + std::to_string(supersample)] = frames / s;
  }
  figures["triangles"] = SceneRenderer(world, 1).triangles();
  figures["notes"] = "One core. Goal: >= 30 stereo frames/s at 320x240.";
  std::cout << figures.dump(2) << "\n";
  if (!options.writeJson(json_path, figures))
    return 1;
  return 0;
}
