#include "biovision_recognition/stored_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

namespace biovision_recognition
{
namespace
{
constexpr uint32_t kByteOrderMark = 0x01020304u;
constexpr size_t kHeader = 8 + 4 + 4 + 8;

template <typename T>
void append(std::vector<uint8_t>& out, const T& v)
{
  const auto* p = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}

template <typename T>
T loadField(const std::vector<uint8_t>& in, size_t at)
{
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  return v;
}

std::string paddedMagic(const std::string& magic)
{
  if (magic.empty() || magic.size() > 8)
    throw std::invalid_argument("StoredFile: magic must be 1..8 characters");
  std::string m = magic;
  m.resize(8, '\0');
  return m;
}
}  // namespace

uint32_t StoredFile::crc32(const uint8_t* data, size_t size, uint32_t crc)
{
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i)
    {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k)
        c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (size_t i = 0; i < size; ++i)
    crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
  return ~crc;
}

void StoredFile::write(const std::string& path, const std::string& magic, uint32_t version,
                       const std::vector<uint8_t>& payload)
{
  std::vector<uint8_t> bytes;
  bytes.reserve(kHeader + payload.size() + 4);
  const std::string m = paddedMagic(magic);
  bytes.insert(bytes.end(), m.begin(), m.end());
  append(bytes, version);
  append(bytes, kByteOrderMark);
  append(bytes, static_cast<uint64_t>(payload.size()));
  bytes.insert(bytes.end(), payload.begin(), payload.end());
  append(bytes, crc32(bytes.data(), bytes.size()));

  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0)
    throw StoredFileError("cannot write " + tmp + ": " + std::strerror(errno));
  size_t done = 0;
  while (done < bytes.size())
  {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0)
    {
      const std::string why = std::strerror(errno);
      ::close(fd);
      ::unlink(tmp.c_str());
      throw StoredFileError("cannot write " + tmp + ": " + why);
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0)
  {
    ::unlink(tmp.c_str());
    throw StoredFileError("cannot flush " + tmp);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0)
  {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw StoredFileError("cannot replace " + path + ": " + why);
  }
}

std::vector<uint8_t> StoredFile::read(const std::string& path, const std::string& magic, uint32_t version)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw StoredFileError(path + ": cannot open");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < kHeader + 4)
    throw StoredFileError(path + ": too short to be a stored file (" + std::to_string(bytes.size()) + " bytes)");
  const std::string m = paddedMagic(magic);
  if (std::memcmp(bytes.data(), m.data(), 8) != 0)
    throw StoredFileError(path + ": not a " + magic + " file (foreign magic)");
  const auto file_version = loadField<uint32_t>(bytes, 8);
  if (loadField<uint32_t>(bytes, 12) != kByteOrderMark)
    throw StoredFileError(path + ": written with another byte order");
  if (file_version != version)
    throw StoredFileError(path + ": format version " + std::to_string(file_version) + ", this build reads " +
                          std::to_string(version));
  const auto size = loadField<uint64_t>(bytes, 16);
  if (size != bytes.size() - kHeader - 4)
    throw StoredFileError(path + ": payload size " + std::to_string(size) + " does not match the file (" +
                          std::to_string(bytes.size() - kHeader - 4) + " bytes): truncated or padded");
  const auto stored_crc = loadField<uint32_t>(bytes, bytes.size() - 4);
  if (crc32(bytes.data(), bytes.size() - 4) != stored_crc)
    throw StoredFileError(path + ": checksum mismatch (corrupt file)");
  return std::vector<uint8_t>(bytes.begin() + kHeader, bytes.end() - 4);
}
}  // namespace biovision_recognition
