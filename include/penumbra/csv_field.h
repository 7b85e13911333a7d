// One field of a CSV row as RFC 4180 writes it, for the tables penumbra writes beside its JSON:
// text with a comma ("plain separable blur, 9 taps"), a quote or a line break is quoted, its
// quotes doubled, so that every row keeps its header's columns.
#pragma once

#include <string>

namespace penumbra {

inline std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace penumbra
