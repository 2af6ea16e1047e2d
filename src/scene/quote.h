// Cutting what a message quotes: a scene name, an unknown key or a file
// name may be megabytes long, and a message echoes only its start.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace whisker {

// What messages quote of a name or value, at most.
inline constexpr std::size_t kQuoteMax = 200;

// `text` if it has at most `max` bytes; else its first `max` bytes (never
// splitting a UTF-8 character) followed by "...". Control characters are
// escaped (\n, \x1b): a message stays one line and sends no terminal codes.
inline std::string cut_for_message(std::string_view text, std::size_t max = kQuoteMax) {
  std::size_t n = text.size();
  if (n > max) {
    n = max;
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;  // a continuation byte
  }
  std::string out;
  out.reserve(n + 3);
  for (const char ch : text.substr(0, n)) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c != 0x7f) {
      out += ch;
    } else if (c == '\n') {
      out += "\\n";
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return n < text.size() ? out + "..." : out;
}

}  // namespace whisker
