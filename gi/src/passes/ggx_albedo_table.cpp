#include "passes/ggx_albedo_table.h"

#include <span>
#include <vector>

#include "common/ggx_albedo.h"

namespace gi {

engine::Buffer createGgxAlbedoTable(engine::Context& ctx) {
  engine::Buffer table(ctx, sizeof(glm::vec2) * kGgxAlbedoTableSize * kGgxAlbedoTableSize,
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, engine::MemoryUsage::Upload);
  std::vector<glm::vec2> nodes;
  for (int i = 0; i < kGgxAlbedoTableSize; ++i)
    for (int j = 0; j < kGgxAlbedoTableSize; ++j) nodes.emplace_back(ggxSpecularAlbedoNode(i, j));
  table.upload(ctx, std::span<const glm::vec2>(nodes));
  return table;
}

}  // namespace gi
