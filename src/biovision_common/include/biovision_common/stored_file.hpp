#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "biovision_common/payload_reader.hpp"

namespace biovision_common
{
/// Thrown when a stored file is refused: missing, foreign, wrong version, truncated or corrupt.
struct StoredFileError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// The container every stored BioVision file uses (descriptor models, object memories):
///   magic (8 bytes) | format version (u32) | byte-order mark 0x01020304 (u32) | payload size (u64) |
///   payload | CRC-32 of everything before it (u32).
/// write() is atomic: it writes a temporary file beside the target, fsyncs it and renames it over the
/// target, so a crash leaves either the old or the new file, never half of one. read() checks every
/// field and refuses the file with a StoredFileError that says what is wrong.
class StoredFile
{
public:
  static void write(const std::string& path, const std::string& magic, uint32_t version,
                    const std::vector<uint8_t>& payload);
  static std::vector<uint8_t> read(const std::string& path, const std::string& magic, uint32_t version);
  /// read(), then parse(PayloadReader&) -> T, which must consume the whole payload. Any failure of the
  /// parser (a short read, an inconsistent field) becomes a StoredFileError naming `what`: a file is
  /// loaded completely or not at all.
  template <typename T, typename Parse>
  static T load(const std::string& path, const std::string& magic, uint32_t version, const std::string& what,
                Parse&& parse)
  {
    const std::vector<uint8_t> bytes = read(path, magic, version);
    try
    {
      PayloadReader reader(bytes);
      T value = parse(reader);
      if (!reader.atEnd())
        throw std::runtime_error("trailing bytes");
      return value;
    }
    catch (const StoredFileError&)
    {
      throw;
    }
    catch (const std::exception& e)
    {
      throw StoredFileError(path + ": inconsistent " + what + ": " + e.what());
    }
  }
  /// CRC-32 (IEEE 802.3, reflected): zlib's crc32, continued from `crc`.
  static uint32_t crc32(const uint8_t* data, size_t size, uint32_t crc = 0);
};
}  // namespace biovision_common
