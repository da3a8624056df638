#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace biovision_common
{
/// Reads what PayloadWriter wrote; throws std::runtime_error on any read past the end, so a
/// truncated or inconsistent payload is refused instead of half-read.
class PayloadReader
{
public:
  explicit PayloadReader(const std::vector<uint8_t>& bytes) : bytes_(bytes) {}

  template <typename T>
  T get()
  {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  /// max_count guards against absurd counts from damaged files.
  template <typename T>
  std::vector<T> getArray(uint64_t max_count)
  {
    const auto count = get<uint64_t>();
    if (count > max_count)
      throw std::runtime_error("payload array of " + std::to_string(count) + " entries exceeds the limit " +
                               std::to_string(max_count));
    need(count * sizeof(T));
    std::vector<T> values(count);
    if (count)
      std::memcpy(values.data(), bytes_.data() + pos_, count * sizeof(T));
    pos_ += count * sizeof(T);
    return values;
  }
  std::string getString(uint64_t max_length = 4096)
  {
    const auto chars = getArray<char>(max_length);
    return std::string(chars.begin(), chars.end());
  }
  bool atEnd() const { return pos_ == bytes_.size(); }

private:
  void need(uint64_t n) const
  {
    if (n > bytes_.size() - pos_)
      throw std::runtime_error("payload ends early (truncated or inconsistent file)");
  }
  const std::vector<uint8_t>& bytes_;
  size_t pos_ = 0;
};
}  // namespace biovision_common
