// Byte-level encoding of protocol messages: fixed-width integers and IEEE
// doubles in host order (all programs of a job run one build on one
// cluster), length-prefixed strings, vectors and maps, fixed-size arrays
// element by element, and any struct that
// lists its members with PBMS_FIELDS. A message type is therefore just a
// struct; its wire layout is its field list, in order.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "pbms/error.hpp"

// Declares the members that make up a struct's wire form, in order.
#define PBMS_FIELDS(...)          \
  auto fields() {                 \
    return std::tie(__VA_ARGS__); \
  }                               \
  auto fields() const {           \
    return std::tie(__VA_ARGS__); \
  }

namespace pbms::protocol {

template <typename T>
struct IsVector : std::false_type {};
template <typename T>
struct IsVector<std::vector<T>> : std::true_type {};
template <typename T>
struct IsArray : std::false_type {};
template <typename T, size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};
template <typename T>
struct IsMap : std::false_type {};
template <typename K, typename V>
struct IsMap<std::map<K, V>> : std::true_type {};

class Encoder {
 public:
  template <typename T>
  void put(const T& v) {
    if constexpr (std::is_arithmetic_v<T>) {
      raw(&v, sizeof(T));
    } else if constexpr (std::is_same_v<T, std::string>) {
      put<uint64_t>(v.size());
      raw(v.data(), v.size());
    } else if constexpr (IsVector<T>::value) {
      put<uint64_t>(v.size());
      if constexpr (std::is_arithmetic_v<typename T::value_type>) {
        raw(v.data(), v.size() * sizeof(typename T::value_type));
      } else {
        for (const auto& x : v) put(x);
      }
    } else if constexpr (IsArray<T>::value) {
      for (const auto& x : v) put(x);
    } else if constexpr (IsMap<T>::value) {
      put<uint64_t>(v.size());
      for (const auto& [k, x] : v) {
        put(k);
        put(x);
      }
    } else {
      std::apply([this](const auto&... f) { (put(f), ...); }, v.fields());
    }
  }
  [[nodiscard]] std::vector<std::byte> take() { return std::move(bytes_); }

 private:
  void raw(const void* p, size_t n) {
    const auto* b = static_cast<const std::byte*>(p);
    bytes_.insert(bytes_.end(), b, b + n);
  }
  std::vector<std::byte> bytes_;
};

class Decoder {
 public:
  Decoder(const std::byte* data, size_t size) : data_(data), size_(size) {}

  template <typename T>
  void get(T& out) {
    if constexpr (std::is_arithmetic_v<T>) {
      raw(&out, sizeof(T));
    } else if constexpr (std::is_same_v<T, std::string>) {
      const auto n = length(1);
      out.assign(reinterpret_cast<const char*>(data_ + pos_), n);
      pos_ += n;
    } else if constexpr (IsVector<T>::value) {
      using V = typename T::value_type;
      if constexpr (std::is_arithmetic_v<V>) {
        out.resize(length(sizeof(V)));
        raw(out.data(), out.size() * sizeof(V));
      } else {
        out.clear();
        const auto n = length(1);
        for (uint64_t i = 0; i < n; ++i) get(out.emplace_back());
      }
    } else if constexpr (IsArray<T>::value) {
      for (auto& x : out) get(x);
    } else if constexpr (IsMap<T>::value) {
      out.clear();
      const auto n = length(1);
      for (uint64_t i = 0; i < n; ++i) {
        typename T::key_type k;
        get(k);
        get(out[k]);
      }
    } else {
      std::apply([this](auto&... f) { (get(f), ...); }, out.fields());
    }
  }
  template <typename T>
  T get() {
    T v{};
    get(v);
    return v;
  }
  [[nodiscard]] bool at_end() const { return pos_ == size_; }

 private:
  // A count, checked against the bytes left (each element is >= `unit`).
  uint64_t length(size_t unit) {
    const auto n = get<uint64_t>();
    if (n > (size_ - pos_) / unit) throw Error("protocol: corrupt message (bad length field)");
    return n;
  }
  void raw(void* out, size_t n) {
    if (n > size_ - pos_) throw Error("protocol: truncated message");
    std::memcpy(out, data_ + pos_, n);
    pos_ += n;
  }
  const std::byte* data_;
  size_t size_;
  size_t pos_ = 0;
};

}  // namespace pbms::protocol
