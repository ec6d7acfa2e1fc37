// Byte-level encoding of protocol messages: little-endian fixed-width
// integers, IEEE doubles, length-prefixed strings and vectors. Both ends run
// on the same cluster, but a fixed layout keeps the format independent of
// compiler padding and lets tests pin it down.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "pbms/error.hpp"

namespace pbms::protocol {

class Encoder {
 public:
  template <typename T>
  requires std::is_arithmetic_v<T>
  void put(T v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void put(const std::string& s) {
    put<uint64_t>(s.size());
    const auto* p = reinterpret_cast<const std::byte*>(s.data());
    bytes_.insert(bytes_.end(), p, p + s.size());
  }
  template <typename T>
  void put(const std::vector<T>& v) {
    put<uint64_t>(v.size());
    if constexpr (std::is_arithmetic_v<T>) {
      const auto* p = reinterpret_cast<const std::byte*>(v.data());
      bytes_.insert(bytes_.end(), p, p + v.size() * sizeof(T));
    } else {
      for (const auto& x : v) put(x);
    }
  }
  [[nodiscard]] std::vector<std::byte> take() { return std::move(bytes_); }
  [[nodiscard]] const std::vector<std::byte>& bytes() const { return bytes_; }

 private:
  std::vector<std::byte> bytes_;
};

class Decoder {
 public:
  Decoder(const std::byte* data, size_t size) : data_(data), size_(size) {}

  template <typename T>
  requires std::is_arithmetic_v<T> T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  template <typename T>
  void get(T& out) {
    if constexpr (std::is_arithmetic_v<T>) {
      out = get<T>();
    } else if constexpr (std::is_same_v<T, std::string>) {
      const auto n = length();
      need(n);
      out.assign(reinterpret_cast<const char*>(data_ + pos_), n);
      pos_ += n;
    } else {
      get_vector(out);
    }
  }
  [[nodiscard]] bool at_end() const { return pos_ == size_; }

 private:
  template <typename T>
  void get_vector(std::vector<T>& out) {
    const auto n = length();
    if constexpr (std::is_arithmetic_v<T>) {
      need(n * sizeof(T));
      out.resize(n);
      std::memcpy(out.data(), data_ + pos_, n * sizeof(T));
      pos_ += n * sizeof(T);
    } else {
      out.clear();
      for (uint64_t i = 0; i < n; ++i) {
        T x;
        get(x);
        out.push_back(std::move(x));
      }
    }
  }
  uint64_t length() {
    const auto n = get<uint64_t>();
    if (n > size_) throw Error("protocol: corrupt message (length field exceeds message size)");
    return n;
  }
  void need(size_t n) const {
    if (pos_ + n > size_) throw Error("protocol: truncated message");
  }
  const std::byte* data_;
  size_t size_;
  size_t pos_ = 0;
};

}  // namespace pbms::protocol
