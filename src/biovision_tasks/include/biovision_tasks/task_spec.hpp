#pragma once

#include <string>
#include <vector>

namespace biovision_tasks
{
/// A task as a user writes it: in a mission file (YAML, see config/missions/ and parse()), on the
/// `tasks/execute` action, or as one line of text ("search target_box timeout=120; return_home").
///
/// Types: micro-tasks `turn` (angle [rad]), `forward` (distance [m]), `wait` (duration [s]), `stop`,
/// `look_ahead` / `look_around` (duration [s]); simple macro-tasks `search` (object), `explore`
/// (duration [s]), `go_to` (object, or x and y [m] in map), `return_home`; `sequence` (steps, recursive).
struct TaskSpec
{
  std::string type;
  std::string name;                     ///< shown in the status; default: type and object
  std::string object;                   ///< search, go_to
  double x = 0, y = 0;                  ///< go_to a place [m, map]
  bool has_place = false;               ///< x and y were given
  double distance = 0;                  ///< forward [m]
  double angle = 0;                     ///< turn [rad, + = left]
  double duration = 0;                  ///< wait, look_ahead, look_around, explore [s]
  double timeout = -1;                  ///< [s]; < 0 = the type's default (TaskParameters), 0 = none
  int priority = 0;                     ///< higher drives first (the visuomotor buffer's order)
  bool concurrent = false;              ///< detection and conclusion run from the start, beside the active task
  bool optional = false;                ///< in a sequence: its failure does not fail the sequence
  std::string on_failure = "continue";  ///< "continue", "abort" (cancel the rest) or a task type run instead
  std::vector<TaskSpec> steps;          ///< sequence

  /// Parses a mission: YAML text with a `tasks:` list (each item a map with the fields above, `steps:`
  /// nested), or a plain list. Throws std::invalid_argument naming `origin`, the item and the problem
  /// (unknown type or key, missing object, a value of the wrong kind).
  static std::vector<TaskSpec> parseYaml(const std::string& text, const std::string& origin = "<mission>");
  /// The same from a file.
  static std::vector<TaskSpec> loadFile(const std::string& path);
  /// One line: tasks separated by ';', each "type [object] [key=value ...]", e.g.
  /// "search target_box timeout=120 on_failure=continue; return_home". Throws std::invalid_argument.
  static std::vector<TaskSpec> parseText(const std::string& text);
  /// Throws std::invalid_argument when the spec cannot be built (unknown type, missing argument, NaN).
  void validate() const;
  /// "search target_box", "go_to (1.0, 2.0)", ...
  std::string displayName() const;
};
}  // namespace biovision_tasks
