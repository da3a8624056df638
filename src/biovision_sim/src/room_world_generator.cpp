#include "biovision_sim/room_world_generator.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "biovision_sim/floor_plan.hpp"

namespace biovision_sim
{
namespace
{
constexpr double kWallThickness = 0.1, kWallHeight = 2.0;

// Whether a disc of `radius` can go from (ax, ay) to (bx, by): BFS over the raster's free cells after
// growing every footprint by the radius.
bool reachable(const FloorPlan& plan, double width, double depth, double cell, double radius, double ax, double ay,
               double bx, double by)
{
  const double margin = 0.5;
  const double ox = -margin, oy = -depth / 2 - margin;
  const int cols = static_cast<int>(std::ceil((width + 2 * margin) / cell));
  const int rows = static_cast<int>(std::ceil((depth + 2 * margin) / cell));
  cv::Mat1b occupied = plan.rasterize(ox, oy, cell, rows, cols);
  const int grow = static_cast<int>(std::ceil(radius / cell));
  cv::dilate(occupied, occupied, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * grow + 1, 2 * grow + 1)));
  auto cellOf = [&](double x, double y) {
    return cv::Point(static_cast<int>((x - ox) / cell), static_cast<int>((y - oy) / cell));
  };
  const cv::Point a = cellOf(ax, ay), b = cellOf(bx, by);
  const cv::Rect inside(0, 0, cols, rows);
  if (!inside.contains(a) || !inside.contains(b) || occupied(a) || occupied(b))
    return false;
  cv::Mat1b seen(rows, cols, uchar(0));
  std::queue<cv::Point> open;
  open.push(a);
  seen(a) = 1;
  const cv::Point steps[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  while (!open.empty())
  {
    const cv::Point p = open.front();
    open.pop();
    if (p == b)
      return true;
    for (const cv::Point& s : steps)
    {
      const cv::Point q = p + s;
      if (inside.contains(q) && !seen(q) && !occupied(q))
      {
        seen(q) = 1;
        open.push(q);
      }
    }
  }
  return false;
}
}  // namespace

void RoomWorldGenerator::Options::validate() const
{
  auto fail = [](const std::string& what) { throw std::invalid_argument("RoomWorldGenerator::Options: " + what); };
  if (!(min_side > 2 && max_side <= 50 && min_side <= max_side))
    fail("min_side/max_side outside (2, 50] m or min_side > max_side");
  if (min_clutter < 0 || max_clutter > 50 || min_clutter > max_clutter)
    fail("min_clutter/max_clutter outside [0, 50] or min_clutter > max_clutter");
  if (!(partition_probability >= 0 && partition_probability <= 1))
    fail("partition_probability outside [0, 1]");
  if (!(min_start_goal > 0 && robot_radius > 0 && free_radius >= robot_radius && raster_cell > 0))
    fail("min_start_goal, robot_radius, raster_cell must be > 0 and free_radius >= robot_radius");
  if (std::hypot(min_side, min_side) - 2 * free_radius < min_start_goal)
    fail("min_side too small for min_start_goal (the diagonal minus 2 free_radius)");
  if (max_attempts < 1)
    fail("max_attempts must be >= 1");
}

RoomWorldGenerator::RoomWorldGenerator() : RoomWorldGenerator(Options())
{
}

RoomWorldGenerator::RoomWorldGenerator(const Options& options) : options_(options)
{
  options_.validate();
}

RoomWorldGenerator::Room RoomWorldGenerator::generate(unsigned seed) const
{
  const Options& o = options_;
  std::mt19937 rng(seed);
  auto uniform = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (int attempt = 1; attempt <= o.max_attempts; ++attempt)
  {
    Room room;
    room.seed = seed;
    room.attempts = attempt;
    room.width = uniform(o.min_side, o.max_side);
    room.depth = uniform(o.min_side, o.max_side);
    World& w = room.world;
    const int wall_texture = w.addTexture({"solid", {200, 205, 210}, {0, 0, 0}, 1.0, 0.1, 1.0, seed, ""});
    const int table_texture = w.addTexture({"solid", {60, 100, 150}, {0, 0, 0}, 1.0, 0.1, 1.0, seed, ""});
    const int box_texture = w.addTexture({"solid", {70, 130, 170}, {0, 0, 0}, 1.0, 0.1, 1.0, seed, ""});
    const int bin_texture = w.addTexture({"solid", {80, 80, 80}, {0, 0, 0}, 1.0, 0.1, 1.0, seed, ""});
    auto box = [&](const std::string& label, double x, double y, double yaw, double sx, double sy, double sz,
                   int texture) {
      World::Object b;
      b.label = label;
      b.shape = "box";
      b.position = {x, y, sz / 2};
      b.yaw = yaw;
      b.size = {sx, sy, sz};
      b.texture = texture;
      return b;
    };
    const double W = room.width, D = room.depth;
    w.addObject(box("wall_south", W / 2, -D / 2, 0, W + kWallThickness, kWallThickness, kWallHeight, wall_texture));
    w.addObject(box("wall_north", W / 2, D / 2, 0, W + kWallThickness, kWallThickness, kWallHeight, wall_texture));
    w.addObject(box("wall_west", 0, 0, 0, kWallThickness, D, kWallHeight, wall_texture));
    w.addObject(box("wall_east", W, 0, 0, kWallThickness, D, kWallHeight, wall_texture));

    // Start and goal first, far enough apart, inside the room with a margin.
    const double m = o.free_radius + kWallThickness / 2;
    int tries = 0;
    do
    {
      room.start_x = uniform(m, W - m);
      room.start_y = uniform(-D / 2 + m, D / 2 - m);
      room.goal_x = uniform(m, W - m);
      room.goal_y = uniform(-D / 2 + m, D / 2 - m);
    } while (std::hypot(room.goal_x - room.start_x, room.goal_y - room.start_y) < o.min_start_goal && ++tries < 1000);
    room.start_yaw = uniform(-M_PI, M_PI);

    // An object is kept only when start and goal stay clear of it.
    auto addIfClear = [&](const World::Object& object) {
      World single;
      single.addObject(object);
      const FloorPlan::Footprint f = FloorPlan(single).footprints().front();
      if (distanceTo(f, room.start_x, room.start_y) >= o.free_radius &&
          distanceTo(f, room.goal_x, room.goal_y) >= o.free_radius)
        w.addObject(object);
    };
    if (uniform(0, 1) < o.partition_probability)
    {
      // A partition from the south or north wall, along y, somewhere in the middle of the room in x.
      const double length = uniform(0.35, 0.6) * D;
      const double x = uniform(0.3 * W, 0.7 * W);
      const bool south = uniform(0, 1) < 0.5;
      const double y = south ? -D / 2 + length / 2 : D / 2 - length / 2;
      addIfClear(box("partition", x, y, 0, kWallThickness, length, kWallHeight, wall_texture));
    }

    const int clutter = std::uniform_int_distribution<int>(o.min_clutter, o.max_clutter)(rng);
    for (int i = 0; i < clutter; ++i)
    {
      double x, y;
      if (i == 0)
      {
        // On the straight route, a little off it.
        const double s = uniform(0.35, 0.65);
        x = room.start_x + s * (room.goal_x - room.start_x) + uniform(-0.3, 0.3);
        y = room.start_y + s * (room.goal_y - room.start_y) + uniform(-0.3, 0.3);
      }
      else
      {
        x = uniform(0.3, W - 0.3);
        y = uniform(-D / 2 + 0.3, D / 2 - 0.3);
      }
      const double yaw = uniform(-M_PI, M_PI);
      const int kind = std::uniform_int_distribution<int>(0, 2)(rng);
      const std::string label = (kind == 0 ? "table_" : kind == 1 ? "box_" : "bin_") + std::to_string(i);
      if (kind == 0)
      {
        const double sx = uniform(0.8, 1.4), sy = uniform(0.6, 0.9);
        addIfClear(box(label, x, y, yaw, sx, sy, 0.75, table_texture));
      }
      else if (kind == 1)
      {
        const double sx = uniform(0.3, 0.7), sy = uniform(0.3, 0.7), sz = uniform(0.3, 0.8);
        addIfClear(box(label, x, y, yaw, sx, sy, sz, box_texture));
      }
      else
      {
        World::Object bin;
        bin.label = label;
        bin.shape = "cylinder";
        const double r = uniform(0.15, 0.3), h = uniform(0.4, 0.9);
        bin.position = {x, y, h / 2};
        bin.size = {2 * r, 2 * r, h};
        bin.texture = bin_texture;
        addIfClear(bin);
      }
    }
    const FloorPlan plan(w);
    if (plan.clearance(room.start_x, room.start_y) < o.free_radius ||
        plan.clearance(room.goal_x, room.goal_y) < o.free_radius ||
        std::hypot(room.goal_x - room.start_x, room.goal_y - room.start_y) < o.min_start_goal)
      continue;
    if (!reachable(plan, W, D, o.raster_cell, o.robot_radius, room.start_x, room.start_y, room.goal_x, room.goal_y))
      continue;
    return room;
  }
  throw std::runtime_error("RoomWorldGenerator: no reachable room for seed " + std::to_string(seed) + " in " +
                           std::to_string(o.max_attempts) + " draws");
}
}  // namespace biovision_sim
