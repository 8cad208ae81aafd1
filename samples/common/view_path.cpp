#include "view_path.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <numbers>
#include <optional>
#include <system_error>

#include "engine/error.h"
#include "scene_files.h"

namespace samples {
namespace {

constexpr std::string_view kHeader = "# vsgl view path v1";
constexpr size_t kCameraNumbers = 16 + 7;  // cameraToWorld, then perspective .. ymag
constexpr size_t kLightNumbers = 13;       // position, direction, colour, intensity .. outer

const std::pair<std::string_view, engine::LightType> kLightTypes[] = {
    {"point", engine::LightType::Point},
    {"spot", engine::LightType::Spot},
    {"directional", engine::LightType::Directional}};

// Shortest text that reads back as the same float: what makes a replay bit-exact.
void appendNumber(std::string& out, float value) {
  char text[32];
  const std::to_chars_result r = std::to_chars(text, text + sizeof(text), value);
  out += ' ';
  out.append(text, r.ptr);
}

void appendVec3(std::string& out, const glm::vec3& v) {
  for (int i = 0; i < 3; ++i) appendNumber(out, v[i]);
}

std::string_view typeWord(engine::LightType type) {
  for (const auto& [word, t] : kLightTypes)
    if (t == type) return word;
  return "point";  // unreachable: every LightType has a word
}

// 'word', for messages (appended, not "'" + std::string(word), which GCC 12 warns about).
std::string quoted(std::string_view word) {
  std::string out = "'";
  out.append(word);
  out += '\'';
  return out;
}

// The whitespace-separated words of a line.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (true) {
    i = line.find_first_not_of(" \t", i);
    if (i == std::string_view::npos) return out;
    const size_t end = std::min(line.find_first_of(" \t", i), line.size());
    out.push_back(line.substr(i, end - i));
    i = end;
  }
}

// Reads one path's lines, keeping the line number for its messages.
class Reader {
 public:
  explicit Reader(const std::string& source) : source_(source) {}

  [[noreturn]] void fail(size_t line, const std::string& problem) const {
    throw engine::Error(source_ + ":" + std::to_string(line) + ": " + problem);
  }

  float number(size_t line, std::string_view word) const {
    float value = 0.0f;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (end != word.data() + word.size() ||
        (error != std::errc() && error != std::errc::result_out_of_range))
      fail(line, quoted(word) + " is not a number");
    if (error == std::errc::result_out_of_range)
      fail(line, quoted(word) + " is outside a float's range");
    if (!std::isfinite(value)) fail(line, quoted(word) + " is not a finite number");
    return value;
  }

  uint32_t frameIndex(size_t line, std::string_view word) const {
    uint32_t value = 0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size())
      fail(line, "frame: " + quoted(word) + " is not a frame index");
    return value;
  }

  // The numbers after a line's first `skip` words, exactly `count` of them.
  std::vector<float> numbers(size_t line, const std::vector<std::string_view>& w, size_t skip,
                             size_t count, const std::string& what) const {
    if (w.size() != skip + count)
      fail(line, what + ": expected " + std::to_string(count) + " numbers, got " +
                     std::to_string(w.size() - skip));
    std::vector<float> out;
    for (size_t i = skip; i < w.size(); ++i) out.push_back(number(line, w[i]));
    return out;
  }

  engine::Camera camera(size_t line, const std::vector<std::string_view>& w) const {
    const std::vector<float> n = numbers(line, w, 1, kCameraNumbers, "camera");
    engine::Camera c;
    for (int column = 0; column < 4; ++column)
      for (int row = 0; row < 4; ++row) c.cameraToWorld[column][row] = n[size_t(column * 4 + row)];
    if (n[16] != 0.0f && n[16] != 1.0f)
      fail(line, "camera: perspective is " + quoted(w[17]) + ", not 0 or 1");
    c.perspective = n[16] == 1.0f;
    c.yfov = n[17];
    c.aspectRatio = n[18];
    c.znear = n[19];
    c.zfar = n[20];
    c.xmag = n[21];
    c.ymag = n[22];
    // The glTF loader's rules (engine/src/gltf_definitions.cpp): what a view can be made from.
    if (c.aspectRatio < 0.0f) fail(line, "camera: aspectRatio must be >= 0 (0: the image's)");
    if (c.perspective) {
      if (!(c.yfov > 0.0f && c.yfov < std::numbers::pi_v<float>))
        fail(line, "camera: yfov must be in (0, pi)");
      if (!(c.znear > 0.0f)) fail(line, "camera: znear must be > 0");
      if (!(c.zfar == 0.0f || c.zfar > c.znear))
        fail(line, "camera: zfar must be > znear (or 0 for an infinite projection)");
    } else {
      if (!(c.xmag > 0.0f && c.ymag > 0.0f)) fail(line, "camera: xmag and ymag must be > 0");
      if (!(c.znear >= 0.0f && c.zfar > c.znear))
        fail(line, "camera: an orthographic camera needs zfar > znear >= 0");
    }
    return c;
  }

  engine::Light light(size_t line, const std::vector<std::string_view>& w) const {
    if (w.size() < 2)
      fail(line, "light: expected a type and " + std::to_string(kLightNumbers) + " numbers");
    engine::Light l;
    std::optional<engine::LightType> type;
    for (const auto& [word, t] : kLightTypes)
      if (word == w[1]) type = t;
    if (!type) fail(line, "light: " + quoted(w[1]) + " is not one of point, spot, directional");
    l.type = *type;
    const std::vector<float> n = numbers(line, w, 2, kLightNumbers, "light");
    l.position = {n[0], n[1], n[2]};
    l.direction = {n[3], n[4], n[5]};
    l.color = {n[6], n[7], n[8]};
    l.intensity = n[9];
    l.range = n[10];
    l.innerConeAngle = n[11];
    l.outerConeAngle = n[12];
    // A point light's direction and cones are unused (engine::Light): only a spot or a
    // directional light must point somewhere.
    if (l.type != engine::LightType::Point && l.direction == glm::vec3(0.0f))
      fail(line, "light: zero-length direction");
    if (l.color.r < 0.0f || l.color.g < 0.0f || l.color.b < 0.0f)
      fail(line, "light: color must be >= 0");
    if (l.intensity < 0.0f) fail(line, "light: intensity must be >= 0");
    if (l.range < 0.0f) fail(line, "light: range must be >= 0 (0: infinite)");
    if (l.type == engine::LightType::Spot &&
        !(l.innerConeAngle >= 0.0f && l.innerConeAngle < l.outerConeAngle &&
          l.outerConeAngle <= 0.5f * std::numbers::pi_v<float>))
      fail(line, "light: spot cone angles must satisfy 0 <= inner < outer <= pi/2");
    return l;
  }

 private:
  const std::string& source_;
};

}  // namespace

std::string formatPathFrame(const PathFrame& frame, uint32_t index) {
  std::string out = "frame " + std::to_string(index) + "\ncamera";
  const engine::Camera& c = frame.camera;
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row) appendNumber(out, c.cameraToWorld[column][row]);
  out += c.perspective ? " 1" : " 0";
  for (float v : {c.yfov, c.aspectRatio, c.znear, c.zfar, c.xmag, c.ymag}) appendNumber(out, v);
  out += '\n';
  for (const engine::Light& l : frame.lights) {
    out += "light ";
    out += typeWord(l.type);
    appendVec3(out, l.position);
    appendVec3(out, l.direction);
    appendVec3(out, l.color);
    for (float v : {l.intensity, l.range, l.innerConeAngle, l.outerConeAngle}) appendNumber(out, v);
    out += '\n';
  }
  return out;
}

namespace {

// The file's directory made first, as every output of the sample programs.
const std::string& withDirectory(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) createOutputDirectory(parent.string());
  return path;
}

}  // namespace

ViewPathWriter::ViewPathWriter(const std::string& path)
    : path_(path), file_(withDirectory(path), std::ios::binary | std::ios::trunc) {
  file_ << kHeader << '\n' << std::flush;
  if (!file_) throw engine::Error(path_ + ": cannot write");
}

void ViewPathWriter::add(const PathFrame& frame) {
  if (frames_ == kMaxPathFrames)
    throw engine::Error(path_ + ": more than " + std::to_string(kMaxPathFrames) + " frames");
  file_ << formatPathFrame(frame, frames_) << std::flush;
  if (!file_) throw engine::Error(path_ + ": cannot write");
  ++frames_;
}

std::vector<PathFrame> parseViewPath(std::string_view text, const std::string& source) {
  const Reader reader(source);
  std::vector<PathFrame> frames;
  size_t frameLine = 0;  // the line of the last frame's "frame" line
  bool hasCamera = false;
  size_t lineNumber = 0;
  for (size_t start = 0; start <= text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const bool last = end == text.size();
    start = end + 1;
    if (last && line.empty() && lineNumber > 0) break;  // the final newline ends the last line
    ++lineNumber;
    if (lineNumber == 1) {
      if (line != kHeader) reader.fail(1, "missing header '" + std::string(kHeader) + "'");
      continue;
    }
    const std::vector<std::string_view> w = words(line);
    if (w.empty()) continue;
    if (w[0] == "frame") {
      if (!frames.empty() && !hasCamera)
        reader.fail(frameLine,
                    "frame " + std::to_string(frames.size() - 1) + " has no camera line");
      if (w.size() != 2)
        reader.fail(lineNumber, "frame: expected 1 number, got " + std::to_string(w.size() - 1));
      const uint32_t index = reader.frameIndex(lineNumber, w[1]);
      if (frames.size() == kMaxPathFrames)
        reader.fail(lineNumber, "more than " + std::to_string(kMaxPathFrames) + " frames");
      if (index != frames.size())
        reader.fail(lineNumber, "frame " + std::to_string(index) + " where frame " +
                                    std::to_string(frames.size()) + " was expected");
      frames.emplace_back();
      frameLine = lineNumber;
      hasCamera = false;
    } else if (w[0] == "camera" || w[0] == "light") {
      if (frames.empty())
        reader.fail(lineNumber, std::string(w[0]) + " line before the first frame line");
      if (w[0] == "light") {
        frames.back().lights.push_back(reader.light(lineNumber, w));
      } else {
        if (hasCamera)
          reader.fail(lineNumber,
                      "frame " + std::to_string(frames.size() - 1) + " has a second camera line");
        frames.back().camera = reader.camera(lineNumber, w);
        hasCamera = true;
      }
    } else {
      reader.fail(lineNumber, "unknown line kind " + quoted(w[0]) + " (frame, camera or light)");
    }
  }
  if (frames.empty()) reader.fail(lineNumber, "no frame");
  if (!hasCamera)
    reader.fail(frameLine, "frame " + std::to_string(frames.size() - 1) + " has no camera line");
  return frames;
}

std::vector<PathFrame> readViewPath(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::error_code ec;
  if (!file || std::filesystem::is_directory(path, ec)) throw engine::Error(path + ": cannot read");
  const std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (file.bad()) throw engine::Error(path + ": cannot read");
  return parseViewPath(text, path);
}

}  // namespace samples
