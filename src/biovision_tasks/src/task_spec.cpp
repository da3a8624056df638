#include "biovision_tasks/task_spec.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

namespace biovision_tasks
{
namespace
{
const std::set<std::string> kTypes = {"turn",   "forward", "wait",  "stop",        "look_ahead", "look_around",
                                      "search", "explore", "go_to", "return_home", "greet",      "sequence"};
const std::set<std::string> kKeys = {"type",     "task",       "name",     "object",     "x",
                                     "y",        "distance",   "angle",    "duration",   "timeout",
                                     "priority", "concurrent", "optional", "on_failure", "steps"};

std::string where(const std::string& origin, const YAML::Node& n)
{
  std::ostringstream s;
  s << origin;
  if (n.Mark().line >= 0)
    s << ":" << n.Mark().line + 1;
  return s.str();
}

template <typename T>
T get(const YAML::Node& item, const char* key, T fallback, const std::string& origin)
{
  const YAML::Node v = item[key];
  if (!v)
    return fallback;
  try
  {
    return v.as<T>();
  }
  catch (const YAML::Exception&)
  {
    throw std::invalid_argument(where(origin, v) + ": '" + key + "' has the wrong kind of value");
  }
}

TaskSpec fromNode(const YAML::Node& item, const std::string& origin)
{
  if (!item.IsMap())
    throw std::invalid_argument(where(origin, item) + ": a task must be a map (type: ..., ...)");
  for (const auto& kv : item)
    if (!kKeys.count(kv.first.as<std::string>()))
      throw std::invalid_argument(where(origin, kv.first) + ": unknown key '" + kv.first.as<std::string>() + "'");
  TaskSpec t;
  t.type = get<std::string>(item, "type", get<std::string>(item, "task", "", origin), origin);
  t.name = get<std::string>(item, "name", "", origin);
  t.object = get<std::string>(item, "object", "", origin);
  t.has_place = item["x"] || item["y"];
  t.x = get<double>(item, "x", 0.0, origin);
  t.y = get<double>(item, "y", 0.0, origin);
  t.distance = get<double>(item, "distance", 0.0, origin);
  t.angle = get<double>(item, "angle", 0.0, origin);
  t.duration = get<double>(item, "duration", 0.0, origin);
  t.timeout = get<double>(item, "timeout", -1.0, origin);
  t.priority = get<int>(item, "priority", 0, origin);
  t.concurrent = get<bool>(item, "concurrent", false, origin);
  t.optional = get<bool>(item, "optional", false, origin);
  t.on_failure = get<std::string>(item, "on_failure", "continue", origin);
  if (const YAML::Node steps = item["steps"])
  {
    if (!steps.IsSequence())
      throw std::invalid_argument(where(origin, steps) + ": 'steps' must be a list");
    for (const auto& s : steps)
      t.steps.push_back(fromNode(s, origin));
  }
  try
  {
    t.validate();
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(where(origin, item) + ": " + e.what());
  }
  return t;
}
}  // namespace

void TaskSpec::validate() const
{
  if (!kTypes.count(type))
    throw std::invalid_argument("unknown task type '" + type +
                                "' (turn, forward, wait, stop, look_ahead, look_around, search, explore, go_to, "
                                "return_home, greet, sequence)");
  for (double v : {x, y, distance, angle, duration, timeout})
    if (!std::isfinite(v))
      throw std::invalid_argument(type + ": non-finite value");
  if (type == "search" && object.empty())
    throw std::invalid_argument("search needs an object");
  if (type == "go_to" && object.empty() && !has_place)
    throw std::invalid_argument("go_to needs an object or x and y");
  if (duration < 0)
    throw std::invalid_argument(type + ": duration must be >= 0");
  if (type == "sequence" && steps.empty())
    throw std::invalid_argument("sequence needs steps");
  if (on_failure != "continue" && on_failure != "abort" && (!kTypes.count(on_failure) || on_failure == "sequence"))
    throw std::invalid_argument("on_failure must be continue, abort or a task type, not '" + on_failure + "'");
  for (const auto& s : steps)
    s.validate();
}

std::string TaskSpec::displayName() const
{
  if (!name.empty())
    return name;
  std::ostringstream s;
  s << type;
  if (!object.empty())
    s << " " << object;
  else if (type == "go_to")
    s << " (" << x << ", " << y << ")";
  return s.str();
}

std::vector<TaskSpec> TaskSpec::parseYaml(const std::string& text, const std::string& origin)
{
  YAML::Node root;
  try
  {
    root = YAML::Load(text);
  }
  catch (const YAML::Exception& e)
  {
    throw std::invalid_argument(origin + ": " + e.what());
  }
  YAML::Node list = root.IsMap() ? root["tasks"] : root;
  if (!list || !list.IsSequence() || list.size() == 0)
    throw std::invalid_argument(origin + ": expected a non-empty 'tasks:' list");
  std::vector<TaskSpec> out;
  for (const auto& item : list)
    out.push_back(fromNode(item, origin));
  return out;
}

std::vector<TaskSpec> TaskSpec::loadFile(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw std::invalid_argument("cannot read mission file '" + path + "'");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parseYaml(buffer.str(), path);
}

std::vector<TaskSpec> TaskSpec::parseText(const std::string& text)
{
  std::vector<TaskSpec> out;
  std::stringstream all(text);
  std::string item;
  while (std::getline(all, item, ';'))
  {
    std::stringstream words(item);
    std::string word;
    YAML::Node node;
    while (words >> word)
    {
      const auto eq = word.find('=');
      if (eq != std::string::npos)
        node[word.substr(0, eq)] = YAML::Load(word.substr(eq + 1));
      else if (!node["type"])
        node["type"] = word;
      else if (!node["object"])
        node["object"] = word;
      else
        throw std::invalid_argument("'" + item + "': unexpected word '" + word + "' (use key=value)");
    }
    if (node.size() > 0)
      out.push_back(fromNode(node, "'" + item + "'"));
  }
  if (out.empty())
    throw std::invalid_argument("no task in '" + text + "'");
  return out;
}
}  // namespace biovision_tasks
