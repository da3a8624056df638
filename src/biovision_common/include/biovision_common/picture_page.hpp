#pragma once

#include <string>
#include <vector>

namespace biovision_common
{
/// The self-contained report.html of the *_eval tools (mission_eval, navigation_eval): a title, a
/// preformatted summary (e.g. the overall JSON) and PNG pictures embedded as base64 data: URIs, two per
/// row, so that one file shows a whole evaluation. biovision_monitor's run_report uses base64() too.
class PicturePage
{
public:
  /// Standard base64 of `bytes` (RFC 4648, with padding), for data: URIs.
  static std::string base64(const std::vector<unsigned char>& bytes);

  /// Writes `folder`/report.html atomically: `title` (HTML-escaped) as the heading, `summary` (escaped)
  /// in <pre>, then each of `pictures` (file names in `folder`) as an embedded PNG; a picture that cannot
  /// be read is named as missing instead. Returns the number of pictures embedded. Throws FileError
  /// (atomic_file.hpp) when the page cannot be written.
  static int write(const std::string& folder, const std::string& title, const std::string& summary,
                   const std::vector<std::string>& pictures);
};
}  // namespace biovision_common
