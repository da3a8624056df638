#include "biovision_common/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

namespace biovision_common
{
void writeFileAtomically(const std::string& path, const void* data, size_t size)
{
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
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
