// io/markup: text made safe inside XML and HTML element content and quoted attribute values, for
// every markup file rupture writes (VTK XML, report.html).
#pragma once

#include <string>
#include <string_view>

namespace rupture::io {

inline std::string escape_markup(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
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
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace rupture::io
