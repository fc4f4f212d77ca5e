#pragma once
// Results of farmed tasks as bytes (mpi_farm.hpp sends them between ranks): values written
// bit for bit, so that a result computed on another rank is the one computed here.

#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace cranesim {

class ByteWriter {
 public:
  template <class T> void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  template <class T> void putArray(const T* values, long count) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(count);
    bytes_.append(reinterpret_cast<const char*>(values), sizeof(T) * static_cast<std::size_t>(count));
  }
  void put(const std::string& text) { putArray(text.data(), static_cast<long>(text.size())); }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

/// Reads what a ByteWriter wrote, in the same order; throws on bytes that end too early.
class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
  template <class T> T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  /// An array's length, before its values (getArrayValues).
  long getLength() {
    const long count = get<long>();
    if (count < 0) throw std::runtime_error("corrupt task result: negative length");
    return count;
  }
  template <class T> void getArrayValues(T* values, long count) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::size_t size = sizeof(T) * static_cast<std::size_t>(count);
    std::memcpy(values, take(size), size);
  }
  std::string getString() {
    std::string text(static_cast<std::size_t>(getLength()), '\0');
    getArrayValues(text.data(), static_cast<long>(text.size()));
    return text;
  }

 private:
  const char* take(std::size_t size) {
    if (size > bytes_.size() - offset_) throw std::runtime_error("corrupt task result: it ends too early");
    const char* at = bytes_.data() + offset_;
    offset_ += size;
    return at;
  }
  const std::string& bytes_;
  std::size_t offset_ = 0;
};

}  // namespace cranesim
