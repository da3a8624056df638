#include "biovision_common/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>

namespace biovision_common
{
void writeFileAtomically(const std::string& path, const void* data, size_t size)
{
  // <pid>.<n>: two threads of one process writing the same path must not share a temporary (one would
  // rename the other's half-written file into place).
  static std::atomic<unsigned long> count{0};
  const std::string tmp = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(count++);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0)
    throw FileError("cannot write " + tmp + ": " + std::strerror(errno));
  const auto* bytes = static_cast<const char*>(data);
  size_t done = 0;
  while (done < size)
  {
    const ssize_t n = ::write(fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR)
      continue;
    if (n < 0)
    {
      const std::string why = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      throw FileError("cannot write " + tmp + ": " + why);
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0)
  {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw FileError("cannot flush " + tmp + ": " + why);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0)
  {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw FileError("cannot replace " + path + ": " + why);
  }
}

namespace
{
// A process with this id exists (it may belong to another user: EPERM still means it runs).
bool processRuns(long pid)
{
  if (pid <= 0 || pid > 0x3fffffff)
    return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}
}  // namespace

std::vector<std::string> removeStaleTemporaries(const std::string& path)
{
  namespace fs = std::filesystem;
  std::vector<std::string> removed;
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string prefix = target.filename().string() + ".tmp.";
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(folder, error))
  {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0)
      continue;
    // <pid> (older builds) or <pid>.<n>.
    const std::string suffix = name.substr(prefix.size());
    const size_t dot = suffix.find('.');
    const std::string digits = suffix.substr(0, dot), count = dot == std::string::npos ? "0" : suffix.substr(dot + 1);
    if (digits.empty() || digits.size() > 10 || digits.find_first_not_of("0123456789") != std::string::npos ||
        count.empty() || count.size() > 20 || count.find_first_not_of("0123456789") != std::string::npos)
      continue;  // not one of ours
    const long pid = std::stol(digits);
    if (pid == static_cast<long>(::getpid()) || processRuns(pid))
      continue;  // a write in progress
    std::error_code remove_error;
    if (fs::remove(entry.path(), remove_error))
      removed.push_back(entry.path().string());
  }
  std::sort(removed.begin(), removed.end());
  return removed;
}

bool moveWithoutOverwriting(const std::string& from, const std::string& to)
{
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0)
    return true;
  if (errno == EEXIST)
    return false;
  if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP)
    throw FileError("cannot move " + from + " to " + to + ": " + std::strerror(errno));
  // The file system cannot rename without replacing: a hard link fails on an existing name too.
  if (::link(from.c_str(), to.c_str()) != 0)
  {
    if (errno == EEXIST)
      return false;
    throw FileError("cannot move " + from + " to " + to + ": " + std::strerror(errno));
  }
  if (::unlink(from.c_str()) != 0)
    throw FileError("moved " + from + " to " + to + " but cannot remove the original: " + std::strerror(errno));
  return true;
}

std::string keepAside(const std::string& path, const std::string& tag)
{
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y%m%dT%H%M%SZ", &utc);
  const std::string base = path + "." + tag + "-" + stamp;
  for (int n = 1; n < 10000; ++n)
  {
    const std::string candidate = n == 1 ? base : base + "-" + std::to_string(n);
    if (moveWithoutOverwriting(path, candidate))
      return candidate;
  }
  throw FileError("cannot keep " + path + " aside: 9999 copies named " + base + "-N exist already");
}

std::vector<std::string> listDirectory(const std::string& directory)
{
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error))
  {
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name[0] != '.')
      names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}
}  // namespace biovision_common
