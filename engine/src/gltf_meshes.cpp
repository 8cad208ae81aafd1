// Mesh baking: each primitive's triangles go into the Scene's flat arrays in world space, with
// smooth normals generated where the file has none.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gltf_accessors.h"
#include "gltf_scene_builder.h"

namespace engine::gltf_detail {
namespace {

bool isFinite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Vertex order of the primitive's triangles, as indices local to the primitive.
std::vector<uint32_t> assembleTriangles(int mode, const std::vector<uint32_t>& corners) {
  std::vector<uint32_t> triangles;
  if (mode == TINYGLTF_MODE_TRIANGLES) return corners;
  if (corners.size() < 3) return triangles;
  triangles.reserve((corners.size() - 2) * 3);
  for (size_t i = 0; i + 2 < corners.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      // glTF 2.0 spec 3.7.2.1: odd triangles swap two corners to keep the winding.
      const size_t odd = i % 2;
      triangles.insert(triangles.end(), {corners[i], corners[i + 1 + odd], corners[i + 2 - odd]});
    } else {
      triangles.insert(triangles.end(), {corners[i + 1], corners[i + 2], corners[0]});
    }
  }
  return triangles;
}

}  // namespace

uint32_t SceneBuilder::materialFor(const tinygltf::Primitive& primitive, const std::string& where) {
  if (primitive.material >= 0) {
    at(model_.materials, primitive.material, "material", where);
    return static_cast<uint32_t>(primitive.material);
  }
  if (!defaultMaterial_) {
    defaultMaterial_ = Material{};
    defaultMaterial_->name = "default";
    defaultMaterial_->metallicFactor = 0.0f;
    defaultMaterial_->roughnessFactor = 0.5f;
  }
  // Appended after all glTF materials once the whole scene is read.
  return static_cast<uint32_t>(model_.materials.size());
}

void SceneBuilder::addMesh(int meshIndex, const glm::dmat4& world, const std::string& nodeWhere) {
  const tinygltf::Mesh& mesh = at(model_.meshes, meshIndex, "mesh", nodeWhere);
  const std::string meshWhere = label("mesh", mesh.name, static_cast<size_t>(meshIndex));
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    addPrimitive(mesh.primitives[p], world, meshWhere + " primitive " + std::to_string(p));
  }
}

void SceneBuilder::addPrimitive(const tinygltf::Primitive& primitive, const glm::dmat4& world,
                                const std::string& where) {
  const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
  if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
      mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
    // Points and lines have no area to light or to be lit: the rest of the file still renders.
    scene_.warnings.push_back(located(where + ": skipped (" +
                                      (mode == TINYGLTF_MODE_POINTS ? "points" : "lines") +
                                      "; only triangles are rendered)"));
    return;
  }
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    fail(where + ": unknown primitive mode " + std::to_string(mode));
  }
  const auto attribute = [&](const char* name) {
    const auto it = primitive.attributes.find(name);
    return it == primitive.attributes.end() ? -1 : it->second;
  };
  const int positionAccessor = attribute("POSITION");
  if (positionAccessor < 0) fail(where + ": no POSITION attribute");
  const AccessorView positions = viewAccessor(positionAccessor, where + " POSITION",
                                              TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
  const size_t vertexCount = positions.count;
  std::optional<AccessorView> normals;
  if (const int a = attribute("NORMAL"); a >= 0) {
    normals =
        viewAccessor(a, where + " NORMAL", TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
  }
  // The texture coordinate set the material's textures sample (convertMaterials).
  const uint32_t material = materialFor(primitive, where);
  const int set = material < materialCoordinateSets_.size() ? materialCoordinateSets_[material] : 0;
  const std::string uvName = "TEXCOORD_" + std::to_string(set);
  std::optional<AccessorView> uvs;
  if (const int a = attribute(uvName.c_str()); a >= 0) {
    uvs = viewAccessor(a, where + " " + uvName, TINYGLTF_TYPE_VEC2,
                       {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
    if (uvs->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !uvs->normalized) {
      fail(where + " " + uvName + ": integer texture coordinates must be normalized");
    }
  } else if (set > 0) {
    fail(where + ": its material's textures sample " + uvName + ", which the primitive lacks");
  }
  if ((normals && normals->count != vertexCount) || (uvs && uvs->count != vertexCount)) {
    fail(where + ": NORMAL/" + uvName + " counts differ from the POSITION count " +
         std::to_string(vertexCount));
  }

  std::vector<uint32_t> corners;
  if (primitive.indices >= 0) {
    const AccessorView indices =
        viewAccessor(primitive.indices, where + " indices", TINYGLTF_TYPE_SCALAR,
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    corners.resize(indices.count);
    for (size_t i = 0; i < indices.count; ++i) {
      corners[i] = readIndex(indices, i);
      if (corners[i] >= vertexCount) {
        fail(where + ": index " + std::to_string(corners[i]) + " at position " + std::to_string(i) +
             " is out of range (" + std::to_string(vertexCount) + " vertices)");
      }
    }
  } else {
    if (vertexCount > std::numeric_limits<uint32_t>::max()) fail(where + ": too many vertices");
    corners.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) corners[i] = static_cast<uint32_t>(i);
  }
  if (mode == TINYGLTF_MODE_TRIANGLES && corners.size() % 3 != 0) {
    fail(where + ": triangle list with " + std::to_string(corners.size()) +
         " corners (not a multiple of 3)");
  }
  std::vector<uint32_t> triangles = assembleTriangles(mode, corners);

  const size_t base = scene_.positions.size();
  if (vertexCount > std::numeric_limits<uint32_t>::max() - base) {
    fail(where + ": the scene has more than 2^32 vertices");
  }

  // World-space positions; normals by the inverse-transpose, which keeps them perpendicular to
  // the surface under non-uniform scale.
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(world)));
  std::vector<glm::vec3> worldPositions(vertexCount);
  for (size_t v = 0; v < vertexCount; ++v) {
    const glm::dvec3 local(readFloat(positions, v, 0), readFloat(positions, v, 1),
                           readFloat(positions, v, 2));
    const glm::dvec3 p = glm::dvec3(world * glm::dvec4(local, 1.0));
    if (!isFinite(p)) fail(where + " POSITION: non-finite position at vertex " + std::to_string(v));
    worldPositions[v] = glm::vec3(p);
  }
  // A mirroring transform turns counter-clockwise triangles clockwise: swap two corners.
  if (glm::determinant(glm::dmat3(world)) < 0.0) {
    for (size_t t = 0; t + 2 < triangles.size(); t += 3)
      std::swap(triangles[t + 1], triangles[t + 2]);
  }

  // Face normals (unnormalised: length = twice the area) of the final, world-space winding.
  // Each vertex remembers one non-degenerate face as the fallback for a zero normal.
  std::vector<glm::dvec3> fallback(vertexCount, glm::dvec3(0.0, 1.0, 0.0));
  std::vector<bool> hasFallback(vertexCount, false);
  std::vector<glm::dvec3> faceNormals(triangles.size() / 3);
  for (size_t t = 0; t < faceNormals.size(); ++t) {
    const glm::dvec3 p0(worldPositions[triangles[3 * t]]);
    const glm::dvec3 p1(worldPositions[triangles[3 * t + 1]]);
    const glm::dvec3 p2(worldPositions[triangles[3 * t + 2]]);
    faceNormals[t] = glm::cross(p1 - p0, p2 - p0);
    if (const auto unit = tryNormalize(faceNormals[t])) {
      for (size_t k = 0; k < 3; ++k) {
        const uint32_t v = triangles[3 * t + k];
        if (!hasFallback[v]) {
          fallback[v] = *unit;
          hasFallback[v] = true;
        }
      }
    }
  }

  std::vector<glm::dvec3> vertexNormals(vertexCount, glm::dvec3(0.0));
  if (normals) {
    for (size_t v = 0; v < vertexCount; ++v) {
      const glm::dvec3 n(readFloat(*normals, v, 0), readFloat(*normals, v, 1),
                         readFloat(*normals, v, 2));
      if (!isFinite(n)) fail(where + " NORMAL: non-finite normal at vertex " + std::to_string(v));
      vertexNormals[v] = normalMatrix * n;
    }
  } else {
    // Area-weighted smooth normals: vertices at exactly the same position share one sum.
    std::vector<uint32_t> order(vertexCount);
    for (size_t v = 0; v < vertexCount; ++v) order[v] = static_cast<uint32_t>(v);
    const auto less = [&](uint32_t a, uint32_t b) {
      const glm::vec3& pa = worldPositions[a];
      const glm::vec3& pb = worldPositions[b];
      if (pa.x != pb.x) return pa.x < pb.x;
      if (pa.y != pb.y) return pa.y < pb.y;
      return pa.z < pb.z;
    };
    std::sort(order.begin(), order.end(), less);
    std::vector<uint32_t> group(vertexCount, 0);
    uint32_t groupCount = 0;
    for (size_t i = 0; i < order.size(); ++i) {
      if (i > 0 && less(order[i - 1], order[i])) ++groupCount;
      group[order[i]] = groupCount;
    }
    std::vector<glm::dvec3> sums(vertexCount == 0 ? 0 : groupCount + 1, glm::dvec3(0.0));
    for (size_t t = 0; t < faceNormals.size(); ++t) {
      for (size_t k = 0; k < 3; ++k) sums[group[triangles[3 * t + k]]] += faceNormals[t];
    }
    for (size_t v = 0; v < vertexCount; ++v) vertexNormals[v] = sums[group[v]];
  }

  scene_.positions.insert(scene_.positions.end(), worldPositions.begin(), worldPositions.end());
  for (size_t v = 0; v < vertexCount; ++v) {
    scene_.normals.emplace_back(tryNormalize(vertexNormals[v]).value_or(fallback[v]));
    const glm::dvec2 uv =
        uvs ? glm::dvec2(readFloat(*uvs, v, 0), readFloat(*uvs, v, 1)) : glm::dvec2(0.0);
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
      fail(where + " " + uvName + ": non-finite texture coordinate at vertex " + std::to_string(v));
    scene_.uvs.emplace_back(uv);
  }
  for (uint32_t corner : triangles) scene_.indices.push_back(static_cast<uint32_t>(base) + corner);
  scene_.triangleMaterial.insert(scene_.triangleMaterial.end(), triangles.size() / 3, material);
}

}  // namespace engine::gltf_detail
