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
/// half of one. The temporary is `<path>.tmp.<pid>.<n>`, unique per call, so threads writing the same path
/// do not share one. Throws FileError (and removes the temporary file) on any failure.
void writeFileAtomically(const std::string& path, const void* data, size_t size);
inline void writeFileAtomically(const std::string& path, const std::string& text)
{
  writeFileAtomically(path, text.data(), text.size());
}

/// Removes the temporaries `<path>.tmp.<pid>.<n>` (and older builds' `<path>.tmp.<pid>`) that
/// writeFileAtomically(path, ...) left behind in processes
/// that no longer run (killed during a write: kill -9, power cut). Temporaries of live processes, and of this
/// one, are kept. Call it before the first write of a stored file; returns the removed files (for the log).
/// Never throws: a temporary that cannot be removed is skipped.
std::vector<std::string> removeStaleTemporaries(const std::string& path);

/// Moves `from` to `to` only if `to` does not exist (renameat2 RENAME_NOREPLACE, or link + unlink where the file
/// system lacks it): an existing file is never replaced. Returns false when `to` exists; throws FileError on
/// any other failure.
bool moveWithoutOverwriting(const std::string& from, const std::string& to);

/// Keeps a refused file for inspection: moves `path` to `<path>.<tag>-<UTC time YYYYMMDDTHHMMSSZ>` (with
/// `-2`, `-3`, ... appended when that exists), never overwriting an earlier kept copy. Returns the new
/// name; throws FileError when the file cannot be moved.
std::string keepAside(const std::string& path, const std::string& tag = "refused");

/// Entries of a folder (no hidden ones), in name order; empty when it cannot be read.
std::vector<std::string> listDirectory(const std::string& directory);
}  // namespace biovision_common
