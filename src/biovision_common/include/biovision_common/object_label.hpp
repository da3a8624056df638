#pragma once

#include <cstddef>
#include <string>

namespace biovision_common
{
/// The rule for an object's label that every store shares (the recognition memory file, the memory
/// database): checked when an object is learned and again when a stored one is loaded, so that what one
/// side accepts the other reads back. A label goes into logs, diagnostics, messages and SQLite.
struct ObjectLabel
{
  static constexpr size_t kMaxBytes = 256;  ///< [bytes of UTF-8]

  /// Why `label` cannot be used ("" when it can): empty, longer than kMaxBytes, or holding a control
  /// character (codes 0–31 and 127).
  static std::string problem(const std::string& label)
  {
    if (label.empty())
      return "empty label";
    if (label.size() > kMaxBytes)
      return "label of " + std::to_string(label.size()) + " bytes, the limit is " + std::to_string(kMaxBytes);
    for (const char c : label)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        return "label holds a control character (code " + std::to_string(static_cast<unsigned char>(c)) + ")";
    return "";
  }
};
}  // namespace biovision_common
