// Cutting what a message quotes: a scene name, an unknown key or a file
// name may be megabytes long, and a message echoes only its start.
#pragma once

#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>

namespace whisker {

// What messages quote of a name or value, at most.
inline constexpr std::size_t kQuoteMax = 200;

// `text` with control characters escaped (\n, \x1b; the C1 controls U+0080
// to U+009F, which some terminals also obey, as \xc2\x9b): whatever it
// echoes, a message stays one line and sends no terminal codes. Every line
// Whisker writes about its input goes through this (usage_error() does it
// for the whole refusal), so no caller has to remember it.
inline std::string printable(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  const auto hex = [&out](unsigned char c) {
    out += "\\x";
    out += kHex[c >> 4];
    out += kHex[c & 15];
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      out += "\\n";
    } else if (c < 0x20 || c == 0x7f) {
      hex(c);
    } else if (c == 0xc2 && i + 1 < text.size() &&
               (static_cast<unsigned char>(text[i + 1]) & 0xe0) == 0x80) {
      hex(c);
      hex(static_cast<unsigned char>(text[++i]));
    } else {
      out += text[i];
    }
  }
  return out;
}

// A number as it was read: the shortest decimal that reads back as the same
// double (1e-320, not the 9.99989e-321 of six significant digits; 1e+308).
inline std::string shortest(double x) {
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

// `text` if it has at most `max` bytes; else its first `max` bytes (never
// splitting a UTF-8 character) followed by "...". Control characters are
// escaped (\n, \x1b): a message stays one line and sends no terminal codes.
inline std::string cut_for_message(std::string_view text, std::size_t max = kQuoteMax) {
  std::size_t n = text.size();
  if (n > max) {
    n = max;
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;  // a continuation byte
  }
  const std::string out = printable(text.substr(0, n));
  return n < text.size() ? out + "..." : out;
}

}  // namespace whisker
