#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace biovision_common
{
/// Appends plain values to a byte buffer (host byte order: the files are checked for it, see StoredFile).
class PayloadWriter
{
public:
  template <typename T>
  void put(const T& value)
  {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  template <typename T>
  void putArray(const T* values, size_t count)
  {
    put<uint64_t>(count);
    const auto* p = reinterpret_cast<const uint8_t*>(values);
    bytes_.insert(bytes_.end(), p, p + count * sizeof(T));
  }
  void putString(const std::string& s) { putArray(s.data(), s.size()); }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

private:
  std::vector<uint8_t> bytes_;
};
}  // namespace biovision_common
