// glTF accessors, bufferViews and buffers: each accessor is checked against its bufferView and its
// buffer (type, component type, stride, byte ranges) before any element is read.
#include "gltf_accessors.h"

#include <algorithm>
#include <cstring>

namespace engine::gltf_detail {
namespace {

size_t componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

size_t componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    default:
      return 0;
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    default:
      return "a matrix or unknown type";
  }
}

template <typename T>
T loadUnaligned(const uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

}  // namespace

float readFloat(const AccessorView& view, size_t i, size_t c) {
  const uint8_t* p = view.data + i * view.stride + c * componentSize(view.componentType);
  switch (view.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return loadUnaligned<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return static_cast<float>(p[0]) / (view.normalized ? 255.0f : 1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return static_cast<float>(loadUnaligned<uint16_t>(p)) / (view.normalized ? 65535.0f : 1.0f);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float v = static_cast<float>(loadUnaligned<int8_t>(p));
      return view.normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float v = static_cast<float>(loadUnaligned<int16_t>(p));
      return view.normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    default:
      return 0.0f;  // unreachable: viewAccessor() admits only the types above
  }
}

uint32_t readIndex(const AccessorView& view, size_t i) {
  const uint8_t* p = view.data + i * view.stride;
  switch (view.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return loadUnaligned<uint16_t>(p);
    default:
      return loadUnaligned<uint32_t>(p);
  }
}

AccessorView ModelReader::viewAccessor(int accessorIndex, const std::string& where,
                                       int expectedType,
                                       std::initializer_list<int> allowedComponentTypes) const {
  const tinygltf::Accessor& accessor = at(model_.accessors, accessorIndex, "accessor", where);
  const std::string what = where + " (accessor " + std::to_string(accessorIndex) + ")";
  if (accessor.sparse.isSparse) fail(what + ": sparse accessors are not supported");
  if (accessor.type != expectedType) {
    fail(what + ": expected type " + typeName(expectedType) + ", got " + typeName(accessor.type));
  }
  if (std::find(allowedComponentTypes.begin(), allowedComponentTypes.end(),
                accessor.componentType) == allowedComponentTypes.end()) {
    fail(what + ": unsupported componentType " + std::to_string(accessor.componentType));
  }
  if (accessor.bufferView < 0) fail(what + ": accessors without a bufferView are not supported");
  const tinygltf::BufferView& view =
      at(model_.bufferViews, accessor.bufferView, "bufferView", what);
  const auto& data = at(model_.buffers, view.buffer, "buffer", what).data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
    fail(what + ": bufferView " + std::to_string(accessor.bufferView) +
         " runs past the end of buffer " + std::to_string(view.buffer) + " (" +
         std::to_string(data.size()) + " bytes)");
  }
  const size_t elementSize = componentSize(accessor.componentType) * componentCount(expectedType);
  const size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
  if (stride < elementSize) fail(what + ": byteStride is smaller than one element");
  // The last element must end inside the view: offset + stride * (count - 1) + elementSize,
  // compared by division so that a huge count cannot overflow.
  if (accessor.count > 0) {
    const bool fits =
        accessor.byteOffset <= view.byteLength &&
        elementSize <= view.byteLength - accessor.byteOffset &&
        accessor.count - 1 <= (view.byteLength - accessor.byteOffset - elementSize) / stride;
    if (!fits) {
      fail(what + ": " + std::to_string(accessor.count) + " elements at byteOffset " +
           std::to_string(accessor.byteOffset) + " do not fit in bufferView " +
           std::to_string(accessor.bufferView) + " (" + std::to_string(view.byteLength) +
           " bytes)");
    }
  }
  AccessorView out;
  out.data = data.data() + view.byteOffset + accessor.byteOffset;
  out.count = accessor.count;
  out.stride = stride;
  out.componentType = accessor.componentType;
  out.normalized = accessor.normalized;
  return out;
}

}  // namespace engine::gltf_detail
