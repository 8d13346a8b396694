#include "scene/RenderSettingsJson.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "scene/TestScenes.h"

namespace igi {
namespace {

TEST(RenderSettingsJson, AbsentKeysKeepTheirValue) {
    RenderSettings s;
    s.tileSize = 7;
    applyRenderSettingsJson(nlohmann::json::parse(R"({"direct_samples": 2, "integrator": "igi"})"),
                            s, "f.json", "/render");
    EXPECT_EQ(s.directSamples, 2);
    EXPECT_EQ(s.tileSize, 7);
    EXPECT_EQ(s.integrator, IntegratorKind::Igi);
}

TEST(RenderSettingsJson, LightSamplingChoices) {
    RenderSettings s;
    EXPECT_EQ(s.lightSampling, LightSampling::Auto);
    for (const auto& [name, value] :
         {std::pair{"power", LightSampling::Power}, std::pair{"tree", LightSampling::Tree},
          std::pair{"auto", LightSampling::Auto}}) {
        applyRenderSettingsJson(nlohmann::json{{"light_sampling", name}}, s, "f", "");
        EXPECT_EQ(s.lightSampling, value) << name;
    }
    EXPECT_THROW(
        applyRenderSettingsJson(nlohmann::json{{"light_sampling", "lightcuts"}}, s, "f", ""),
        SceneError);
    // Auto: the tree from kLightTreeMinLights emitters on.
    EXPECT_FALSE(usesLightTree(LightSampling::Auto, kLightTreeMinLights - 1));
    EXPECT_TRUE(usesLightTree(LightSampling::Auto, kLightTreeMinLights));
    EXPECT_TRUE(usesLightTree(LightSampling::Tree, 1));
    EXPECT_FALSE(usesLightTree(LightSampling::Power, 1000));
}

TEST(RenderSettingsJson, VplSamplingChoicesAndPool) {
    RenderSettings s;
    EXPECT_EQ(s.vplSampling, VplSampling::Auto);
    EXPECT_EQ(s.effectiveVplPool(), kVplPoolFactor * s.indirectVpls);
    for (const auto& [name, value] :
         {std::pair{"all", VplSampling::All}, std::pair{"importance", VplSampling::Importance},
          std::pair{"auto", VplSampling::Auto}}) {
        applyRenderSettingsJson(nlohmann::json{{"vpl_sampling", name}}, s, "f", "");
        EXPECT_EQ(s.vplSampling, value) << name;
    }
    applyRenderSettingsJson(nlohmann::json{{"vpl_pool", 100}, {"indirect_vpls", 9}}, s, "f", "");
    EXPECT_EQ(s.effectiveVplPool(), 100);
    EXPECT_EQ(s.firstFrameDivisor, 0);  // auto
    applyRenderSettingsJson(nlohmann::json{{"first_frame_divisor", 2}}, s, "f", "");
    EXPECT_EQ(s.firstFrameDivisor, 2);
    EXPECT_THROW(applyRenderSettingsJson(nlohmann::json{{"vpl_sampling", "tree"}}, s, "f", ""),
                 SceneError);
    EXPECT_THROW(applyRenderSettingsJson(nlohmann::json{{"vpl_pool", -1}}, s, "f", ""), SceneError);
    // Auto: by importance from kLightTreeMinLights emitters on, as the light tree.
    EXPECT_FALSE(usesVplChoice(VplSampling::Auto, kLightTreeMinLights - 1));
    EXPECT_TRUE(usesVplChoice(VplSampling::Auto, kLightTreeMinLights));
    EXPECT_TRUE(usesVplChoice(VplSampling::Importance, 1));
    EXPECT_FALSE(usesVplChoice(VplSampling::All, 1000));
}

// "converge" sets every mean of the converging estimator at once; keys beside it win.
TEST(RenderSettingsJson, ConvergeSetsEveryMeanAndKeysBesideItWin) {
    RenderSettings s;
    applyRenderSettingsJson(nlohmann::json{{"converge", false}}, s, "f", "");
    EXPECT_FALSE(s.roulette);
    EXPECT_EQ(s.clampCompensation, ClampCompensation::Off);
    EXPECT_EQ(s.indirectCausticPhotons, 0);
    EXPECT_FALSE(s.progressiveRadius);
    EXPECT_FALSE(s.progressiveFilter);
    EXPECT_FALSE(s.poolCaustics);
    applyRenderSettingsJson(nlohmann::json{{"converge", true}, {"pool_caustics", false}}, s, "f",
                            "");
    EXPECT_TRUE(s.roulette);
    EXPECT_TRUE(s.progressiveFilter);
    EXPECT_FALSE(s.poolCaustics);
    applyRenderSettingsJson(nlohmann::json{{"pool_caustics", true}}, s, "f", "");
    EXPECT_TRUE(s.poolCaustics);
}

// The cache modes' keys, and the values they refuse.
TEST(RenderSettingsJson, CacheAndPhotonmapKeys) {
    RenderSettings s;
    applyRenderSettingsJson(nlohmann::json{{"gi", "cache"}, {"cache_spacing", 0.05}}, s, "f", "");
    EXPECT_EQ(s.gi, GiMode::Cache);
    EXPECT_FLOAT_EQ(s.cacheSpacing, 0.05f);
    applyRenderSettingsJson(nlohmann::json{{"gi", "photonmap"},
                                           {"photonmap_caustics", "grid"},
                                           {"photonmap_groups", 64},
                                           {"photonmap_gather", 16}},
                            s, "f", "");
    EXPECT_EQ(s.gi, GiMode::PhotonMap);
    EXPECT_FALSE(s.photonmapScreenCaustics);
    EXPECT_EQ(s.photonmapGroups, 64);
    EXPECT_EQ(s.photonmapGather, 16);
    EXPECT_EQ(giModeName(s.gi), std::string("photonmap"));
    for (const char* bad : {R"({"cache_spacing": 0})", R"({"cache_radius": 0.1})",
                            R"({"photonmap_caustics": "hashed"})", R"({"photonmap_photons": 0})",
                            R"({"photonmap_groups": 65536, "photonmap_photons": 64})"})
        EXPECT_THROW(applyRenderSettingsJson(nlohmann::json::parse(bad), s, "f", ""), SceneError)
            << bad;
    EXPECT_FALSE(s.photonmapScreenCaustics);
}

TEST(RenderSettingsJson, ErrorsUseTheGivenFileAndPrefix) {
    RenderSettings s;
    auto apply = [&](const char* text) {
        return test::sceneErrorOf(
            [&] { applyRenderSettingsJson(nlohmann::json::parse(text), s, "cli", "/override"); });
    };
    EXPECT_EQ(apply(R"({"interleave": [0, 3]})"),
              "cli: /override/interleave/0: must be in [1, 16], got 0");
    EXPECT_EQ(apply(R"({"interleave": [3]})"),
              "cli: /override/interleave: expected an array of 2 elements, got 1");
    EXPECT_EQ(apply(R"({"filter": [32, 1]})"),
              "cli: /override/filter/0: must be in [0, 31], got 32");
    EXPECT_EQ(apply(R"({"clamp_distance": 1})"),
              "cli: /override/clamp_distance: must be in [0, 1), got 1");
    EXPECT_EQ(apply(R"({"caustic_radius": 0})"),
              "cli: /override/caustic_radius: must be in (0, 1), got 0");
    EXPECT_EQ(apply(R"({"filter_normal_threshold": -1.5})"),
              "cli: /override/filter_normal_threshold: must be in [-1, 1], got -1.5");
    EXPECT_EQ(apply(R"({"filter_depth_threshold": 0})"),
              "cli: /override/filter_depth_threshold: must be in (0, inf], got 0");
    EXPECT_EQ(apply(R"({"seed": -1})"), "cli: /override/seed: must not be negative, got -1");
    EXPECT_EQ(apply(R"({"max_path_length": 2000})"),
              "cli: /override/max_path_length: must be in [1, 1024], got 2000");
    EXPECT_EQ(apply(R"({"caustic_photons": 10000001})"),
              "cli: /override/caustic_photons: must be in [0, 10000000], got 10000001");
    EXPECT_EQ(apply(R"({"first_frame_divisor": 65})"),
              "cli: /override/first_frame_divisor: must be in [0, 64], got 65");
    EXPECT_EQ(apply(R"({"accumulate": 1})"),
              "cli: /override/accumulate: expected true or false, got 1");
    EXPECT_EQ(apply("[]"), "cli: /override: expected an object, got array");
}

TEST(RenderSettingsJson, AFailureLeavesTheSettingsUntouched) {
    RenderSettings s;
    EXPECT_THROW(applyRenderSettingsJson(
                     nlohmann::json::parse(R"({"direct_samples": 9, "tile_size": 0})"), s, "f", ""),
                 SceneError);
    EXPECT_EQ(s, RenderSettings{});
}

TEST(RenderSettingsJson, LargestSeed) {
    RenderSettings s;
    applyRenderSettingsJson(nlohmann::json::parse(R"({"seed": 18446744073709551615})"), s, "f", "");
    EXPECT_EQ(s.seed, 18446744073709551615ull);
}

// Issue 40: a run's statistics must say every setting that shaped it, readable back.
TEST(RenderSettingsJson, EverySettingWrittenReadsBackTheSame) {
    RenderSettings s;
    s.integrator = IntegratorKind::Path;
    s.gi = GiMode::PhotonMap;
    s.interleaveX = 4;
    s.filterY = 5;
    s.lightSampling = LightSampling::Tree;
    s.vplSampling = VplSampling::Importance;
    s.clampCompensation = ClampCompensation::Shrink;
    s.clampDistance = 0.0123f;
    s.progressiveAlpha = 0.3f;
    s.photonmapScreenCaustics = false;
    s.accumulate = false;
    s.roulette = false;
    s.seed = 18446744073709551615ull;
    s.sptPaths = 9;
    s.sptPilots = 7;
    s.firstFrameDivisor = 5;
    const nlohmann::json j = renderSettingsJson(s);
    EXPECT_TRUE(j["seed"].is_number_unsigned());
    EXPECT_EQ(j["gi"], "photonmap");
    RenderSettings back;
    applyRenderSettingsJson(nlohmann::json::parse(j.dump()), back, "stats.json", "/render");
    EXPECT_EQ(back, s);
    RenderSettings defaults;
    applyRenderSettingsJson(renderSettingsJson(RenderSettings{}), defaults, "f", "");
    EXPECT_EQ(defaults, RenderSettings{});
}

}  // namespace
}  // namespace igi
