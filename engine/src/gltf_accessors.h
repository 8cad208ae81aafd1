// Private to the glTF loader: checked access to a parsed tinygltf model. tinygltf hands back
// indices and byte ranges unchecked, so every index goes through at() and every accessor through
// viewAccessor(), which checks it against its bufferView and buffer before a byte is read.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "engine/error.h"

namespace engine::gltf_detail {

// One accessor's elements, checked to lie inside its buffer.
struct AccessorView {
  const uint8_t* data = nullptr;  // first element
  size_t count = 0;
  size_t stride = 0;  // bytes between elements
  int componentType = 0;
  bool normalized = false;
};

// Component c of element i as float; normalized integers map to [0, 1] or [-1, 1] (glTF 3.11).
float readFloat(const AccessorView& view, size_t i, size_t c);

// Element i of an index accessor (u8, u16 or u32).
uint32_t readIndex(const AccessorView& view, size_t i);

// The model and the path its errors name; every problem becomes Error("<path>: <problem>").
class ModelReader {
 public:
  ModelReader(const std::string& path, const tinygltf::Model& model) : model_(model), path_(path) {}

  [[noreturn]] void fail(const std::string& problem) const { throw Error(path_ + ": " + problem); }
  std::string located(const std::string& problem) const { return path_ + ": " + problem; }

  template <typename T>
  const T& at(const std::vector<T>& items, int index, const std::string& kind,
              const std::string& where) const {
    if (index < 0 || static_cast<size_t>(index) >= items.size()) {
      fail(where + ": " + kind + " " + std::to_string(index) + " does not exist");
    }
    return items[static_cast<size_t>(index)];
  }

  // Accessor accessorIndex, required to be of expectedType with one of allowedComponentTypes.
  AccessorView viewAccessor(int accessorIndex, const std::string& where, int expectedType,
                            std::initializer_list<int> allowedComponentTypes) const;

 protected:
  const tinygltf::Model& model_;

 private:
  const std::string& path_;
};

}  // namespace engine::gltf_detail
