#include "biovision_common/stored_file.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <zlib.h>

#include "biovision_common/atomic_file.hpp"

namespace biovision_common
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
  // zlib's crc32 takes uInt lengths: feed it in chunks so files over 4 GiB checksum correctly.
  uLong c = crc;
  while (size > 0)
  {
    const uInt n = static_cast<uInt>(std::min<size_t>(size, 1u << 30));
    c = ::crc32(c, data, n);
    data += n;
    size -= n;
  }
  return static_cast<uint32_t>(c);
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

  try
  {
    writeFileAtomically(path, bytes.data(), bytes.size());
  }
  catch (const FileError& e)
  {
    throw StoredFileError(e.what());
  }
}

std::vector<uint8_t> StoredFile::read(const std::string& path, const std::string& magic, uint32_t version)
{
  // Only regular files: a directory, a FIFO (would block) or /dev/zero (never ends) is no stored file.
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw StoredFileError(path + (std::filesystem::exists(path, error) ? ": not a regular file" : ": cannot open"));
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw StoredFileError(path + ": cannot open");
  std::vector<uint8_t> bytes;
  try
  {
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  catch (const std::exception& e)
  {
    throw StoredFileError(path + ": cannot read: " + e.what());
  }
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
}  // namespace biovision_common
