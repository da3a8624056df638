#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace biovision_common
{
/// Thrown when a file cannot be written or read; the message names the file and the reason.
struct FileError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Writes `size` bytes to `path` atomically: a temporary file beside it (same folder, so rename cannot
/// cross file systems), fsync, then rename over `path`. A crash leaves the old file or the new one, never
/// half of one. Throws FileError (and removes the temporary file) on any failure.
void writeFileAtomically(const std::string& path, const void* data, size_t size);
inline void writeFileAtomically(const std::string& path, const std::string& text)
{
  writeFileAtomically(path, text.data(), text.size());
}

/// Entries of a folder (no hidden ones), in name order; empty when it cannot be read.
std::vector<std::string> listDirectory(const std::string& directory);
}  // namespace biovision_common
