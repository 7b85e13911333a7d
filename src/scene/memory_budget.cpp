// The host-memory budget of a scene load: its default from the machine, its text form for the
// options, and the one check every loader makes before expanding geometry or decoding textures.
#include "memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

#include "penumbra/error.h"
#include "penumbra/scene.h"

namespace penumbra {
namespace {

constexpr uint64_t kMiB = uint64_t(1) << 20;

// 10,000,000: counts a reader compares at a glance.
std::string groupedDigits(uint64_t n) {
  const std::string digits = std::to_string(n);
  std::string grouped;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped += ',';
    grouped += digits[i];
  }
  return grouped;
}

std::string rangeText() {
  return "[" + memorySizeText(kMinSceneMemoryBytes) + ", " + memorySizeText(kMaxSceneMemoryBytes) +
         "]";
}

}  // namespace

uint64_t defaultSceneMemoryLimit() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0) return uint64_t(4) << 30;
  const uint64_t half = scene::saturatingMultiply(uint64_t(pages), uint64_t(pageSize)) / 2;
  return std::clamp(half, kMinSceneMemoryBytes, kMaxSceneMemoryBytes);
}

std::string memorySizeText(uint64_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  static const char* kUnits[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = double(bytes) / 1024.0;
  int unit = 0;
  while (value >= 1024.0 && unit < 5) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text,
                value < 10.0    ? "%.2f %s"
                : value < 100.0 ? "%.1f %s"
                                : "%.0f %s",
                value, kUnits[unit]);
  return text;
}

uint64_t parseMemorySize(std::string_view text, std::string_view option) {
  const std::string given(text);
  const auto refuse = [&](const std::string& why) -> uint64_t {
    throw Error(std::string(option) + " '" + given + "' " + why);
  };
  const char* const end = text.data() + text.size();
  double number = 0.0;
  const auto [unitStart, fault] = std::from_chars(text.data(), end, number);
  if (fault != std::errc() || text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) {
    return refuse(
        "is not a memory size: give a number of MiB (512) or a number with a unit K, M, G or T "
        "(1.5G, 512MiB)");
  }
  std::string unit(unitStart, end);
  std::transform(unit.begin(), unit.end(), unit.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  double scale = 0.0;
  const std::string prefixes = "kmgt";
  if (unit.empty()) {
    scale = double(kMiB);
  } else if (const size_t power = prefixes.find(unit[0]);
             power != std::string::npos &&
             (unit.size() == 1 || unit.substr(1) == "b" || unit.substr(1) == "ib")) {
    scale = std::ldexp(1.0, 10 * int(power + 1));
  } else {
    return refuse("has an unknown unit '" + std::string(unitStart, end) +
                  "': use K, M, G or T (binary: K = 1024 bytes), or none for MiB");
  }
  const double bytes = number * scale;
  if (!(bytes >= double(kMinSceneMemoryBytes) && bytes <= double(kMaxSceneMemoryBytes))) {
    return refuse("is out of range " + rangeText());
  }
  return uint64_t(bytes);
}

namespace scene {

uint64_t saturatingAdd(uint64_t a, uint64_t b) {
  return a > std::numeric_limits<uint64_t>::max() - b ? std::numeric_limits<uint64_t>::max()
                                                      : a + b;
}

uint64_t saturatingMultiply(uint64_t a, uint64_t b) {
  if (a != 0 && b > std::numeric_limits<uint64_t>::max() / a) {
    return std::numeric_limits<uint64_t>::max();
  }
  return a * b;
}

void MemoryBudget::addFile(const std::string& source, const std::string& file, uint64_t bytes) {
  const uint64_t total = saturatingAdd(fileBytes_, bytes);
  if (total > limit_) {
    const std::string size = file + " is " + memorySizeText(bytes);
    throw Error(source + ": " +
                (fileBytes_ == 0
                     ? size
                     : size + ", which takes the files read to " + memorySizeText(total)) +
                ", above the " + memorySizeText(limit_) + " limit (--max-memory)");
  }
  fileBytes_ = total;
}

void MemoryBudget::addGeometry(uint64_t triangles, uint64_t bytes) {
  triangles_ = saturatingAdd(triangles_, triangles);
  geometryBytes_ = saturatingAdd(geometryBytes_, bytes);
}

void MemoryBudget::addTexture(uint64_t bytes) {
  ++textures_;
  textureBytes_ = saturatingAdd(textureBytes_, bytes);
}

void MemoryBudget::check(const std::string& source) const {
  const uint64_t total = saturatingAdd(saturatingAdd(geometryBytes_, textureBytes_), fileBytes_);
  if (total <= limit_) return;
  std::string parts = groupedDigits(triangles_) +
                      (triangles_ == 1 ? " triangle (" : " triangles (") +
                      memorySizeText(geometryBytes_) + ")";
  if (textures_ > 0) {
    parts += ", " + groupedDigits(textures_) + (textures_ == 1 ? " texture (" : " textures (") +
             memorySizeText(textureBytes_) + ")";
  }
  parts += " and the " + memorySizeText(fileBytes_) + " of files read";
  throw Error(source + ": needs " + memorySizeText(total) + " of host memory for " + parts +
              ", above the " + memorySizeText(limit_) + " limit (--max-memory)");
}

}  // namespace scene
}  // namespace penumbra
