// File names as the program reads them: one rule for an extension, so that
// the command line, the image writers and the viewer's drop target agree
// (x.PNG is a PNG everywhere). In the scene layer, the lowest that names
// files, so that io/, app/ and viewer/ may all include it.
#pragma once

#include <cctype>
#include <filesystem>
#include <string>

namespace whisker {

// ".png" of "x.PNG": the extension, lower case ("" if there is none).
inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace whisker
