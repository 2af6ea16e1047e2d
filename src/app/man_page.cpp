// The render settings' part of packaging/whisker.1, written from the
// settings table (`whisker --man-settings`; scripts/update_man.sh puts it in
// the page, and a test fails when the page differs from it).
#include <string>

#include "app/cli.h"

namespace whisker {

namespace {

// Text as roff source: the dashes of an option ("--frames", every word that
// starts with a dash, or all of `text` when `name`) as "\-", a minus that
// copies as typed, the others hyphens; a line that would start with a
// control character guarded by "\&".
std::string roff(const std::string& text, bool name = false) {
  std::string out;
  bool option = name;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == ' ') option = name;
    if (text[i] == '-' && (i == 0 || text[i - 1] == ' ')) option = true;
    out += text[i] == '-' && option ? std::string("\\-") : std::string(1, text[i]);
  }
  if (!out.empty() && (out[0] == '.' || out[0] == '\'')) out.insert(0, "\\&");
  return out;
}

std::string entry(const SettingField& f) {
  const RenderSettings defaults;
  std::string help = f.help;
  if (!help.empty() && help.back() != '.') help += '.';
  return ".TP\n.BI " + roff(f.option, true) + " \" " + roff(value_syntax(f), true) + "\"\n" + roff(help) +
         "\nScene file:\n.BR " + roff(f.key, true) + " ;\ndefault " + roff(value_text(f, defaults)) +
         ".\n";
}

}  // namespace

std::string settings_man_page() {
  std::string page;
  for (const SettingField& f : setting_fields()) page += entry(f);
  return page;
}

}  // namespace whisker
