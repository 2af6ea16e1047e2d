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
// splitting a UTF-8 character) followed by "...".
inline std::string cut_for_message(std::string_view text, std::size_t max = kQuoteMax) {
  if (text.size() <= max) return std::string(text);
  std::size_t n = max;
  while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;  // a continuation byte
  return std::string(text.substr(0, n)) + "...";
}

}  // namespace whisker
