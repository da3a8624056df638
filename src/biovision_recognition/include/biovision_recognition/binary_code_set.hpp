#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace biovision_recognition
{
/// Binary descriptors of equal length stored back to back, 64 bits per word, bit i of a code in word
/// i / 64 at bit i % 64. Contiguous so the Hamming kernels stream through it.
class BinaryCodeSet
{
public:
  BinaryCodeSet() = default;
  /// bits: 64, 128, 256 or 512.
  explicit BinaryCodeSet(int bits, size_t count = 0) : words_(wordsFor(bits)), data_(count * words_, 0) {}

  static int wordsFor(int bits)
  {
    if (bits != 64 && bits != 128 && bits != 256 && bits != 512)
      throw std::invalid_argument("BinaryCodeSet: bits must be 64, 128, 256 or 512, got " + std::to_string(bits));
    return bits / 64;
  }

  int bits() const { return words_ * 64; }
  int words() const { return words_; }
  size_t size() const { return words_ == 0 ? 0 : data_.size() / words_; }
  bool empty() const { return data_.empty(); }

  const uint64_t* code(size_t i) const { return data_.data() + i * words_; }
  uint64_t* code(size_t i) { return data_.data() + i * words_; }
  const uint64_t* data() const { return data_.data(); }
  uint64_t* data() { return data_.data(); }

  bool bit(size_t i, int b) const { return (code(i)[b >> 6] >> (b & 63)) & 1u; }
  void setBit(size_t i, int b, bool value)
  {
    const uint64_t mask = uint64_t(1) << (b & 63);
    if (value)
      code(i)[b >> 6] |= mask;
    else
      code(i)[b >> 6] &= ~mask;
  }

  void resize(size_t count) { data_.resize(count * words_, 0); }
  void append(const uint64_t* code_words) { data_.insert(data_.end(), code_words, code_words + words_); }
  void append(const BinaryCodeSet& other)
  {
    if (other.words_ != words_)
      throw std::invalid_argument("BinaryCodeSet::append: code lengths differ");
    data_.insert(data_.end(), other.data_.begin(), other.data_.end());
  }
  /// Removes codes [first, first + count).
  void erase(size_t first, size_t count)
  {
    data_.erase(data_.begin() + first * words_, data_.begin() + (first + count) * words_);
  }

private:
  int words_ = 2;
  std::vector<uint64_t> data_;
};
}  // namespace biovision_recognition
