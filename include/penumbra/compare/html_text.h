// Text for the HTML pages (report, bench, figures): escaping and fixed-point numbers.
#pragma once

#include <cstdio>
#include <string>

namespace penumbra::compare {

// Escapes the characters HTML gives meaning to, quotes included (text may land in attributes).
inline std::string escapeHtml(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

// `value` with `digits` decimals.
inline std::string fixedDigits(double value, int digits = 3) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

}  // namespace penumbra::compare
