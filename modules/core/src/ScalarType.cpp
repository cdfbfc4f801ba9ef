#include "mvw/core/ScalarType.h"

namespace mvw {

std::size_t scalarSize(ScalarType type) {
  return dispatchScalar(type, [](auto v) { return sizeof(v); });
}

std::string_view scalarName(ScalarType type) {
  switch (type) {
    case ScalarType::UInt8:
      return "uint8";
    case ScalarType::Int8:
      return "int8";
    case ScalarType::UInt16:
      return "uint16";
    case ScalarType::Int16:
      return "int16";
    case ScalarType::UInt32:
      return "uint32";
    case ScalarType::Int32:
      return "int32";
    case ScalarType::Float32:
      return "float32";
    case ScalarType::Float64:
      return "float64";
  }
  return "unknown";
}

bool isInteger(ScalarType type) {
  return type != ScalarType::Float32 && type != ScalarType::Float64;
}

}  // namespace mvw
