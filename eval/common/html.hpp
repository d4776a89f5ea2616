// HTML text helpers shared by the report's writers.
#pragma once

#include <string>

namespace lifelong::eval {

/// Escapes &, <, > and " for HTML text and attribute values.
inline std::string HtmlEscape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace lifelong::eval
