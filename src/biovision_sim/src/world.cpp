#include "biovision_sim/world.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

namespace biovision_sim
{
namespace
{
[[noreturn]] void fail(const std::string& origin, const YAML::Node& node, const std::string& what)
{
  std::string where = origin;
  if (node && node.Mark().line >= 0)
    where += ":" + std::to_string(node.Mark().line + 1);
  throw std::runtime_error("world " + where + ": " + what);
}

template <typename T>
T get(const std::string& origin, const YAML::Node& parent, const char* key, const T& fallback)
{
  const YAML::Node n = parent[key];
  if (!n)
    return fallback;
  try
  {
    return n.as<T>();
  }
  catch (const YAML::Exception&)
  {
    fail(origin, n, std::string("'") + key + "' has the wrong type");
  }
}

Eigen::Vector3d vec3(const std::string& origin, const YAML::Node& parent, const char* key,
                     const Eigen::Vector3d& fallback)
{
  const YAML::Node n = parent[key];
  if (!n)
    return fallback;
  if (!n.IsSequence() || n.size() != 3)
    fail(origin, n, std::string("'") + key + "' must be a list of 3 numbers");
  try
  {
    return {n[0].as<double>(), n[1].as<double>(), n[2].as<double>()};
  }
  catch (const YAML::Exception&)
  {
    fail(origin, n, std::string("'") + key + "' must be a list of 3 numbers");
  }
}

cv::Vec3b colour(const std::string& origin, const YAML::Node& parent, const char* key, const cv::Vec3b& fallback)
{
  // Colours are written RGB in world files (as people think of them) and stored BGR.
  const Eigen::Vector3d c = vec3(origin, parent, key, Eigen::Vector3d(fallback[2], fallback[1], fallback[0]));
  for (int i = 0; i < 3; ++i)
    if (c[i] < 0 || c[i] > 255)
      fail(origin, parent[key], std::string("'") + key + "' components must be 0..255");
  return cv::Vec3b(static_cast<uchar>(c[2]), static_cast<uchar>(c[1]), static_cast<uchar>(c[0]));
}

Texture::Spec textureSpec(const std::string& origin, const YAML::Node& n)
{
  Texture::Spec s;
  if (!n || n.IsNull())  // absent, or YAML::Node() for a missing parent
    return s;
  if (!n.IsMap())
    fail(origin, n, "'texture' must be a map");
  s.type = get<std::string>(origin, n, "type", "solid");
  s.colour_a = colour(origin, n, "colour", s.colour_a);
  s.colour_b = colour(origin, n, "colour_b", s.colour_b);
  s.period = get<double>(origin, n, "period", 1.0);
  s.feature = get<double>(origin, n, "feature", 0.1);
  s.contrast = get<double>(origin, n, "contrast", 1.0);
  s.seed = get<unsigned>(origin, n, "seed", 1);
  s.file = get<std::string>(origin, n, "file", "");
  if (!(s.period > 0) || !(s.feature > 0) || s.feature > s.period)
    fail(origin, n, "texture needs 0 < feature <= period");
  return s;
}
// YAML text that must be a map; errors name `origin` and the line.
YAML::Node loadMap(const std::string& yaml_text, const std::string& origin, const std::string& what)
{
  YAML::Node node;
  try
  {
    node = YAML::Load(yaml_text);
  }
  catch (const YAML::ParserException& e)
  {
    throw std::runtime_error("world " + origin + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax: " + e.msg);
  }
  if (!node.IsMap())
    throw std::runtime_error("world " + origin + ": " + what + " must be a map");
  return node;
}
}  // namespace

int World::addTexture(const Texture::Spec& spec)
{
  textures_.push_back(std::make_shared<Texture>(spec));
  return static_cast<int>(textures_.size()) - 1;
}

int World::addObject(const Object& object)
{
  objects_.push_back(object);
  return static_cast<int>(objects_.size()) - 1;
}

World::Object World::parseObject(const std::string& origin, const YAML::Node& o)
{
  Object obj;
  obj.label = get<std::string>(origin, o, "label", "");
  if (obj.label.empty())
    fail(origin, o, "every object needs a 'label'");
  obj.shape = get<std::string>(origin, o, "shape", "box");
  obj.position = vec3(origin, o, "position", obj.position);
  obj.yaw = get<double>(origin, o, "yaw", 0.0);
  obj.obstacle = get<bool>(origin, o, "obstacle", true);
  if (obj.shape == "box")
    obj.size = vec3(origin, o, "size", obj.size);
  else if (obj.shape == "cylinder")
  {
    const double r = get<double>(origin, o, "radius", 0.1), height = get<double>(origin, o, "height", 0.2);
    obj.size = Eigen::Vector3d(2 * r, 2 * r, height);
  }
  else
    fail(origin, o["shape"], "unknown shape '" + obj.shape + "' (box, cylinder)");
  if (!(obj.size.minCoeff() > 0))
    fail(origin, o, "object '" + obj.label + "' needs positive dimensions");
  try
  {
    obj.texture = addTexture(textureSpec(origin, o["texture"]));
  }
  catch (const std::runtime_error& e)
  {
    if (std::string(e.what()).rfind("world ", 0) == 0)
      throw;
    fail(origin, o["texture"] ? o["texture"] : o, e.what());
  }
  return obj;
}

int World::placeObject(const std::string& yaml_text, const std::string& origin)
{
  const Object object = parseObject(origin, loadMap(yaml_text, origin, "an object"));
  for (size_t i = 0; i < objects_.size(); ++i)
    if (objects_[i].label == object.label)
    {
      objects_[i] = object;  // its old texture stays in textures_ (a few per run; never looked up again)
      return static_cast<int>(i);
    }
  return addObject(object);
}

World World::load(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("world " + path + ": cannot open");
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path);
}

World World::parse(const std::string& yaml_text, const std::string& origin)
{
  const YAML::Node root = loadMap(yaml_text, origin, "top level");
  World w;
  w.name_ = get<std::string>(origin, root, "name", "world");
  const YAML::Node floor = root["floor"];
  w.floor_size_ = floor ? get<double>(origin, floor, "size", 40.0) : 40.0;
  try
  {
    w.floor_texture_ = w.addTexture(textureSpec(origin, floor ? floor["texture"] : YAML::Node()));
  }
  catch (const std::runtime_error& e)
  {
    if (std::string(e.what()).rfind("world ", 0) == 0)
      throw;
    fail(origin, floor, e.what());
  }
  if (const YAML::Node light = root["light"])
  {
    w.light_direction_ = vec3(origin, light, "direction", w.light_direction_).normalized();
    w.ambient_ = get<double>(origin, light, "ambient", w.ambient_);
    if (!(w.ambient_ >= 0 && w.ambient_ <= 1))
      fail(origin, light["ambient"], "'ambient' must be 0..1");
  }
  w.background_ = colour(origin, root, "background", w.background_);
  const YAML::Node objects = root["objects"];
  if (objects && !objects.IsSequence())
    fail(origin, objects, "'objects' must be a list");
  for (const YAML::Node& o : objects)
    w.addObject(w.parseObject(origin, o));
  return w;
}
}  // namespace biovision_sim
