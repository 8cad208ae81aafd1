#include "reference_cache.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "engine/error.h"

namespace truth {
namespace {

constexpr char kMagic[8] = {'V', 'S', 'G', 'L', 'R', 'E', 'F', '1'};
// Bump when the references' meaning or the file layout changes: older entries then miss.
constexpr uint32_t kFormatVersion = 4;  // 4: single-sided back faces bounce no light

struct Header {
  char magic[8];
  uint32_t version;
  uint32_t channels;
  uint64_t key;
  uint32_t width;
  uint32_t height;
  uint32_t scalars;
  uint32_t reserved;
};

}  // namespace

CacheKey& CacheKey::add(const void* data, size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) {
    hash_ ^= p[i];
    hash_ *= 0x100000001b3ull;
  }
  return *this;
}

CacheKey& CacheKey::add(const std::string& text) {
  add(text.size());
  return add(text.data(), text.size());
}

CacheKey& CacheKey::add(const engine::TextureTransform& t) {
  return add(t.offset).add(t.rotation).add(t.scale);
}

CacheKey& CacheKey::add(const engine::Scene& scene) {
  addVector(scene.positions).addVector(scene.normals).addVector(scene.uvs);
  addVector(scene.indices).addVector(scene.triangleMaterial);
  add(scene.materials.size());
  for (const engine::Material& m : scene.materials) {
    add(m.baseColorFactor).add(m.metallicFactor).add(m.roughnessFactor);
    add(m.baseColorTexture).add(m.metallicRoughnessTexture).add(m.doubleSided);
    // Only where it differs from the extension's defaults, so that the keys of scenes without it
    // (the cached references) stay what they were.
    if (m.specularFactor != 1.0f || m.specularColorFactor != glm::vec3(1.0f))
      add(std::string("KHR_materials_specular")).add(m.specularFactor).add(m.specularColorFactor);
    const engine::TextureTransform* transforms[] = {&m.baseColorTransform,
                                                    &m.metallicRoughnessTransform};
    for (uint32_t i = 0; i < 2; ++i)
      if (!transforms[i]->identity())
        add(std::string("KHR_texture_transform")).add(i).add(*transforms[i]);
    // Only with emission or a normal map, so that the keys of scenes without them stay what they
    // were.
    if (m.emissiveFactor != glm::vec3(0.0f))
      add(std::string("emission"))
          .add(m.emissiveFactor)
          .add(m.emissiveTexture)
          .add(m.emissiveTransform);
    if (m.normalTexture >= 0)
      add(std::string("normalTexture"))
          .add(m.normalTexture)
          .add(m.normalScale)
          .add(m.normalTransform);
    if (m.alphaCutoff > 0.0f) add(std::string("alphaCutoff")).add(m.alphaCutoff);
  }
  add(scene.textures.size());
  for (const engine::Texture& t : scene.textures) add(t.width).add(t.height).addVector(t.rgba8);
  add(scene.lights.size());
  for (const engine::Light& l : scene.lights) {
    add(l.type).add(l.position).add(l.direction).add(l.color).add(l.intensity).add(l.range);
    add(l.innerConeAngle).add(l.outerConeAngle);
  }
  return *this;
}

CacheKey& CacheKey::add(const engine::View& view) {
  return add(view.viewProj).add(view.invViewProj).add(view.width).add(view.height);
}

std::string CacheKey::hex() const {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash_));
  return text;
}

ReferenceCache::ReferenceCache(std::string directory) : directory_(std::move(directory)) {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (ec) throw engine::Error(directory_ + ": cannot create the reference cache: " + ec.message());
}

std::string ReferenceCache::path(const std::string& kind, const CacheKey& key) const {
  return (std::filesystem::path(directory_) / (kind + "-" + key.hex() + ".bin")).string();
}

std::optional<CachedImage> ReferenceCache::load(const std::string& kind,
                                                const CacheKey& key) const {
  const std::string file = path(kind, key);
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  Header h{};
  in.read(reinterpret_cast<char*>(&h), sizeof(h));
  CachedImage image;
  if (in && std::memcmp(h.magic, kMagic, sizeof(kMagic)) == 0 && h.version == kFormatVersion &&
      h.key == key.value()) {
    image.width = h.width;
    image.height = h.height;
    image.channels = h.channels;
    image.values.resize(size_t{h.width} * h.height * h.channels);
    image.scalars.resize(h.scalars);
    in.read(reinterpret_cast<char*>(image.values.data()),
            static_cast<std::streamsize>(image.values.size() * sizeof(double)));
    in.read(reinterpret_cast<char*>(image.scalars.data()),
            static_cast<std::streamsize>(image.scalars.size() * sizeof(double)));
    if (in && in.peek() == std::char_traits<char>::eof()) return image;
  }
  std::fprintf(stderr, "%s: not a valid reference of this version; rendering it again\n",
               file.c_str());
  return std::nullopt;
}

void ReferenceCache::store(const std::string& kind, const CacheKey& key,
                           const CachedImage& image) const {
  const std::string file = path(kind, key);
  const std::string temporary = file + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    Header h{};
    std::memcpy(h.magic, kMagic, sizeof(kMagic));
    h.version = kFormatVersion;
    h.channels = image.channels;
    h.key = key.value();
    h.width = image.width;
    h.height = image.height;
    h.scalars = static_cast<uint32_t>(image.scalars.size());
    if (image.values.size() != size_t{image.width} * image.height * image.channels)
      throw engine::Error(file + ": image size does not match its channels");
    out.write(reinterpret_cast<const char*>(&h), sizeof(h));
    out.write(reinterpret_cast<const char*>(image.values.data()),
              static_cast<std::streamsize>(image.values.size() * sizeof(double)));
    out.write(reinterpret_cast<const char*>(image.scalars.data()),
              static_cast<std::streamsize>(image.scalars.size() * sizeof(double)));
    if (!out) {
      std::filesystem::remove(temporary);
      throw engine::Error(file + ": cannot write the reference");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, file, ec);
  if (ec) {
    std::filesystem::remove(temporary);
    throw engine::Error(file + ": cannot write the reference: " + ec.message());
  }
}

ReferenceCache::EntryLock::EntryLock(const ReferenceCache& cache, const std::string& kind,
                                     const CacheKey& key)
    : fd_(::open((cache.path(kind, key) + ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
  if (fd_ >= 0 && ::flock(fd_, LOCK_EX) != 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

ReferenceCache::EntryLock::~EntryLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the flock
}

}  // namespace truth
