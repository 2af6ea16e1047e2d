// The settings' table (scene/settings.h): every setting reaches the scene
// file and back and counts in equality, the file's and the command line's
// ranges come from the table, and the enums' names round-trip.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <variant>
#include <vector>

#include "scene/scene_io.h"
#include "scene_refusal.h"
#include "scene/settings.h"

using namespace whisker;

namespace {

// A value other than the default for every setting, as command-line text: a
// boolean flips; the others are listed.
const std::map<std::string, std::string> kOtherValues = {
    {"spp", "7"},        {"max_depth", "3"},     {"seed", "12345"},
    {"target_spp", "99"}, {"accel", "bbox"},     {"sampler", "independent"},
    {"split", "2,3"},    {"split_weights", "0.5,0.25,1"}};

std::string other_value(const SettingField& f, const RenderSettings& defaults) {
  if (const auto* m = std::get_if<bool RenderSettings::*>(&f.member))
    return defaults.*(*m) ? "off" : "on";
  return kOtherValues.count(f.key) ? kOtherValues.at(f.key) : "";
}

}  // namespace

TEST(SettingsTable, EveryFieldReachesTheFileAndBackAndCountsInEquality) {
  Scene all = load_scene(resolve_scene("three-balls"));
  const RenderSettings defaults = all.settings;
  for (const SettingField& f : setting_fields()) {
    const std::string text = other_value(f, defaults);
    ASSERT_NE(text, "") << "no test value for setting " << f.key;
    RenderSettings one = defaults;
    EXPECT_EQ(set_from_text(f, text, one), "") << f.key;
    EXPECT_NE(one, defaults) << f.key << ": not part of operator==";
    EXPECT_EQ(set_from_text(f, text, all.settings), "") << f.key;
  }
  const Scene back = parse_scene(scene_to_json(all), "roundtrip.json");
  EXPECT_EQ(back.settings, all.settings);
  EXPECT_EQ(back.settings.split, std::vector<int>({2, 3}));
  EXPECT_EQ(back.settings.accel, BvhMethod::BBox);
}

TEST(SettingsTable, RangesOfTheFileAndTheCommandLineComeFromTheTable) {
  for (const SettingField& f : setting_fields()) {
    if (!std::holds_alternative<int RenderSettings::*>(f.member)) continue;
    const long long above = (long long)f.hi + 1;
    const std::string e = scene_refusal(R"({"settings": {")" + std::string(f.key) +
                                   "\": " + std::to_string(above) + "}}");
    EXPECT_NE(e.find("settings." + std::string(f.key) + ": must be in [" +
                     std::to_string((long long)f.lo) + ", " + std::to_string((long long)f.hi) +
                     "], got " + std::to_string(above)),
              std::string::npos)
        << e;
    RenderSettings r;
    const double option_hi = f.option_hi > 0 ? f.option_hi : f.hi;
    EXPECT_EQ(set_from_text(f, std::to_string((long long)option_hi), r), "") << f.key;
    EXPECT_NE(set_from_text(f, std::to_string((long long)option_hi + 1), r).find("must be in"),
              std::string::npos)
        << f.key;
  }
  RenderSettings r;
  const SettingField& w = setting_field("split_weights");
  EXPECT_EQ(w.lo, 0.01);
  EXPECT_NE(set_from_text(w, "1,0.009,1", r).find("in [0.01, 1]"), std::string::npos);
  EXPECT_EQ(set_from_text(w, "1,0.01,1", r), "");
  EXPECT_EQ(r.split_weights, vec3(1.0f, 0.01f, 1.0f));
}

TEST(SettingsTable, EnumNamesRoundTrip) {
  for (const auto& [kind, name] : enum_names(MaterialKind{})) {
    MaterialKind k{};
    EXPECT_TRUE(parse(name, k));
    EXPECT_EQ(k, kind);
    EXPECT_STREQ(to_string(kind), name);
  }
  EXPECT_EQ(name_list(BvhMethod{}), "brute, bbox, midpoint or sah");
  SamplerKind s = SamplerKind::Sobol;
  EXPECT_FALSE(parse("halton", s));
  EXPECT_EQ(s, SamplerKind::Sobol);
}
