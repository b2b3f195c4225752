#pragma once
// Little-endian field access for MAVLink payloads, independent of the host byte order.
// Reads past the end of a (trimmed) payload yield zero: that is MAVLink 2's re-extension rule.

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>

namespace irgs::comms::mavlink::wire {

template <std::size_t N>
struct UnsignedOfSize;
template <>
struct UnsignedOfSize<1> {
  using Type = std::uint8_t;
};
template <>
struct UnsignedOfSize<2> {
  using Type = std::uint16_t;
};
template <>
struct UnsignedOfSize<4> {
  using Type = std::uint32_t;
};
template <>
struct UnsignedOfSize<8> {
  using Type = std::uint64_t;
};

template <class T>
concept Scalar = std::is_arithmetic_v<T>;

template <Scalar T>
void put(std::uint8_t* out, T value) {
  using U = typename UnsignedOfSize<sizeof(T)>::Type;
  const auto bits = static_cast<std::uint64_t>(std::bit_cast<U>(value));
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out[i] = static_cast<std::uint8_t>(bits >> (8 * i));
  }
}

template <Scalar T, std::size_t N>
void putArray(std::uint8_t* out, const std::array<T, N>& values) {
  for (std::size_t i = 0; i < N; ++i) {
    put(out + i * sizeof(T), values[i]);
  }
}

template <Scalar T>
void get(std::span<const std::uint8_t> in, std::size_t offset, T& value) {
  using U = typename UnsignedOfSize<sizeof(T)>::Type;
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < sizeof(T) && offset + i < in.size(); ++i) {
    bits |= static_cast<std::uint64_t>(in[offset + i]) << (8 * i);
  }
  value = std::bit_cast<T>(static_cast<U>(bits));
}

template <Scalar T, std::size_t N>
void getArray(std::span<const std::uint8_t> in, std::size_t offset, std::array<T, N>& values) {
  for (std::size_t i = 0; i < N; ++i) {
    get(in, offset + i * sizeof(T), values[i]);
  }
}

}  // namespace irgs::comms::mavlink::wire

namespace irgs::comms::mavlink {

// MAVLink char[N] fields are NUL-terminated only when shorter than N.
template <std::size_t N>
std::string_view toStringView(const std::array<char, N>& chars) {
  std::size_t n = 0;
  while (n < N && chars[n] != '\0') {
    ++n;
  }
  return {chars.data(), n};
}

// Copies at most N characters (longer text is cut) and zero-fills the rest.
template <std::size_t N>
void setString(std::array<char, N>& chars, std::string_view text) {
  chars.fill('\0');
  for (std::size_t i = 0; i < N && i < text.size(); ++i) {
    chars[i] = text[i];
  }
}

}  // namespace irgs::comms::mavlink
