#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace mvw {

enum class ScalarType { UInt8, Int8, UInt16, Int16, UInt32, Int32, Float32, Float64 };

std::size_t scalarSize(ScalarType type);
std::string_view scalarName(ScalarType type);  // "uint8", "int16", "float32", ...
bool isInteger(ScalarType type);

template <class T>
constexpr ScalarType scalarTypeOf();
// Tables, one line per type: clang-format would spread each over four.
// clang-format off
template <> constexpr ScalarType scalarTypeOf<std::uint8_t>() { return ScalarType::UInt8; }
template <> constexpr ScalarType scalarTypeOf<std::int8_t>() { return ScalarType::Int8; }
template <> constexpr ScalarType scalarTypeOf<std::uint16_t>() { return ScalarType::UInt16; }
template <> constexpr ScalarType scalarTypeOf<std::int16_t>() { return ScalarType::Int16; }
template <> constexpr ScalarType scalarTypeOf<std::uint32_t>() { return ScalarType::UInt32; }
template <> constexpr ScalarType scalarTypeOf<std::int32_t>() { return ScalarType::Int32; }
template <> constexpr ScalarType scalarTypeOf<float>() { return ScalarType::Float32; }
template <> constexpr ScalarType scalarTypeOf<double>() { return ScalarType::Float64; }
// clang-format on

// Calls f(T{}) with T the C++ type of `type`; the one place that switches over scalar types.
template <class F>
decltype(auto) dispatchScalar(ScalarType type, F&& f) {
  switch (type) {
    // clang-format off
    case ScalarType::UInt8: return f(std::uint8_t{});
    case ScalarType::Int8: return f(std::int8_t{});
    case ScalarType::UInt16: return f(std::uint16_t{});
    case ScalarType::Int16: return f(std::int16_t{});
    case ScalarType::UInt32: return f(std::uint32_t{});
    case ScalarType::Int32: return f(std::int32_t{});
    case ScalarType::Float32: return f(float{});
    case ScalarType::Float64: break;
      // clang-format on
  }
  return f(double{});
}

}  // namespace mvw
