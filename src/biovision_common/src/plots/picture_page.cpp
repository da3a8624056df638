#include "biovision_common/picture_page.hpp"

#include <fstream>
#include <iterator>
#include <sstream>

#include "biovision_common/atomic_file.hpp"

namespace biovision_common
{
namespace
{
std::string escape(const std::string& text)
{
  std::string out;
  for (char c : text)
    out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : c == '"' ? "&quot;" : std::string(1, c);
  return out;
}
}  // namespace

std::string PicturePage::base64(const std::vector<unsigned char>& bytes)
{
  static const char* kTable = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3)
  {
    const unsigned v = unsigned(bytes[i]) << 16 | (i + 1 < bytes.size() ? unsigned(bytes[i + 1]) << 8 : 0u) |
                       (i + 2 < bytes.size() ? unsigned(bytes[i + 2]) : 0u);
    out += kTable[(v >> 18) & 63];
    out += kTable[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kTable[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kTable[v & 63] : '=';
  }
  return out;
}

int PicturePage::write(const std::string& folder, const std::string& title, const std::string& summary,
                       const std::vector<std::string>& pictures)
{
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << escape(title)
       << "</title><style>body{font-family:sans-serif;margin:1em}img{width:48%;border:1px solid #ccc;margin:2px}"
          "</style></head><body>\n<h1>"
       << escape(title) << "</h1>\n<pre>" << escape(summary) << "</pre>\n";
  int embedded = 0;
  for (const auto& name : pictures)
  {
    std::ifstream f(folder + "/" + name, std::ios::binary);
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (!f.good() && bytes.empty())
    {
      page << "<p>missing picture: " << escape(name) << "</p>\n";
      continue;
    }
    page << "<img alt=\"" << escape(name) << "\" src=\"data:image/png;base64," << base64(bytes) << "\">\n";
    ++embedded;
  }
  page << "</body></html>\n";
  writeFileAtomically(folder + "/report.html", page.str());
  return embedded;
}
}  // namespace biovision_common
