// The film's channel names (what the EXR writer labels) and the kernels' accumulation layout
// (kernels/pt_codes.h) agree for every set of AOVs.
#include <kdray/render.h>

#include <kernels/pt_codes.h>

#include <gtest/gtest.h>

namespace kdray {
namespace {

TEST(FilmChannels, NamesFollowTheKernelLayoutForEveryAovSet) {
  for (uint32_t mask = 0; mask < 8; ++mask) {
    RenderSettings settings;
    settings.aov_albedo = mask & PT_AOV_ALBEDO;
    settings.aov_normal = mask & PT_AOV_NORMAL;
    settings.aov_depth = mask & PT_AOV_DEPTH;
    const std::vector<std::string> names = film_channel_names(settings);
    EXPECT_EQ(film_channel_count(settings), pt_film_channel_count(mask)) << "mask " << mask;
    ASSERT_EQ(names.size(), pt_film_channel_count(mask)) << "mask " << mask;
    EXPECT_LE(names.size(), size_t(PT_MAX_FILM_CHANNELS));
    // Radiance first, then each enabled AOV in the order of its bit.
    std::vector<std::string> expected = {"R", "G", "B"};
    if (mask & PT_AOV_ALBEDO) expected.insert(expected.end(), {"albedo.R", "albedo.G", "albedo.B"});
    if (mask & PT_AOV_NORMAL) expected.insert(expected.end(), {"N.X", "N.Y", "N.Z"});
    if (mask & PT_AOV_DEPTH) expected.push_back("Z");
    EXPECT_EQ(names, expected) << "mask " << mask;
  }
  RenderSettings all;
  all.aov_albedo = all.aov_normal = all.aov_depth = true;
  EXPECT_EQ(film_channel_count(all), uint32_t(PT_MAX_FILM_CHANNELS));
}

}  // namespace
}  // namespace kdray
