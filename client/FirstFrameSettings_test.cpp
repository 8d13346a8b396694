// The first frame after a change rendered with its own settings
// (RenderSettings::firstFrameDivisor): what each divisor makes of the settings, and, through
// TileRenderer, that the first frame is that of a session started with the divided settings while
// the accumulated frames keep the full ones.

#include <gtest/gtest.h>

#include "TileRenderer.h"
#include "render/RenderSettings.h"
#include "testing/TestScenes.h"

namespace igi {
namespace {

TEST(FirstFrameSettings, TheDivisorDividesSamplesAndVplsRoundingUpAndKeepsThePool) {
    RenderSettings s;
    s.firstFrameDivisor = 3;
    s.directSamples = 4, s.indirectVpls = 18;
    const RenderSettings f = s.firstFrameSettings(1);
    EXPECT_EQ(f.directSamples, 2);
    EXPECT_EQ(f.indirectVpls, 6);
    EXPECT_EQ(f.vplPool, kVplPoolFactor * 18);  // the accumulated frames' pool, made explicit
    EXPECT_EQ(f.effectiveVplPool(), s.effectiveVplPool());
    EXPECT_EQ(f.firstFrameDivisor, 1);
    // Everything else is the accumulated frames'.
    RenderSettings rest = f;
    rest.directSamples = s.directSamples, rest.indirectVpls = s.indirectVpls;
    rest.vplPool = s.vplPool, rest.firstFrameDivisor = 3;
    EXPECT_EQ(rest, s);
    // A count of 1 stays 1, 0 stays 0; an explicit pool and light paths are kept.
    s.directSamples = 1, s.indirectVpls = 0, s.vplPool = 100, s.vplPaths = 7;
    EXPECT_EQ(s.firstFrameSettings(1).directSamples, 1);
    EXPECT_EQ(s.firstFrameSettings(1).indirectVpls, 0);
    EXPECT_EQ(s.firstFrameSettings(1).vplPool, 100);
    EXPECT_EQ(s.firstFrameSettings(1).vplPaths, 7);
}

TEST(FirstFrameSettings, AutoDividesWhereVplsAreChosenByImportanceOnly) {
    RenderSettings s;  // firstFrameDivisor 0: auto
    EXPECT_EQ(s.effectiveFirstFrameDivisor(kLightTreeMinLights - 1), 1);
    EXPECT_EQ(s.firstFrameSettings(kLightTreeMinLights - 1), s);
    EXPECT_EQ(s.effectiveFirstFrameDivisor(kLightTreeMinLights), kAutoFirstFrameDivisor);
    s.vplSampling = VplSampling::All;
    EXPECT_EQ(s.effectiveFirstFrameDivisor(1000), 1);
    s.vplSampling = VplSampling::Importance;
    EXPECT_EQ(s.effectiveFirstFrameDivisor(1), kAutoFirstFrameDivisor);
    s.firstFrameDivisor = 1;
    EXPECT_EQ(s.firstFrameSettings(1000), s);
}

TEST(FirstFrameSettings, OnlyIgisOwnFirstFrameIsDivided) {
    RenderSettings s;
    s.firstFrameDivisor = 4;
    for (GiMode mode : {GiMode::Stream, GiMode::Spt, GiMode::Cache, GiMode::PhotonMap}) {
        s.gi = mode;
        EXPECT_EQ(s.firstFrameSettings(1000), s) << giModeName(mode);
    }
    s.gi = GiMode::Igi;
    s.integrator = IntegratorKind::Path;
    EXPECT_EQ(s.firstFrameSettings(1000), s);
}

// The Cornell box of the tests with its ceiling light cut into 3 x 3 small lights: 18
// emissive triangles, so that auto chooses VPLs by importance and divides the first frame.
Scene manyLightBox() {
    Scene scene = testing::cornellBox(1.0f);
    const QuadLight whole = scene.quadLights.front();
    scene.quadLights.clear();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            QuadLight q = whole;
            q.name = "light " + std::to_string(3 * i + j);
            q.edge1 = whole.edge1 / 3.0f, q.edge2 = whole.edge2 / 3.0f;
            q.corner = whole.corner + float(i) * q.edge1 + float(j) * q.edge2;
            scene.quadLights.push_back(q);
        }
    scene.image = {36, 27, 0};
    return scene;
}

bool samePixels(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.pixels == b.pixels;
}

TEST(FirstFrameSettings, AFirstFrameIsThatOfASessionWithTheDividedSettings) {
    const Scene scene = manyLightBox();  // auto: a quarter of 4 + 18
    static_assert(kAutoFirstFrameDivisor == 4, "the divided settings below are 4 + 18's");
    Scene divided = scene, full = scene;
    divided.render.directSamples = 1, divided.render.indirectVpls = 5;
    divided.render.vplPool = kVplPoolFactor * 18;  // the full settings' pool
    divided.render.firstFrameDivisor = 1;
    full.render.firstFrameDivisor = 1;
    testing::InProcessRenderer automatic(scene), small(divided), whole(full);
    ASSERT_TRUE(automatic.renderer().firstFrameDiffers());
    EXPECT_FALSE(whole.renderer().firstFrameDiffers());
    EXPECT_EQ(automatic.renderer().firstFrameSettings().indirectVpls, 5);

    // The first frame after a change: the divided session's, bit for bit, and not the full one's.
    const Image first = automatic.render(1, 5, 0);
    EXPECT_TRUE(samePixels(first, small.render(1, 5, 0)));
    EXPECT_FALSE(samePixels(first, whole.render(1, 5, 0)));
    // It traces fewer shadow rays than the full first frame: 6 to the lights and VPLs per
    // point where the full one traces 22.
    EXPECT_LT(double(automatic.shadowRays()), 0.6 * double(whole.shadowRays()));

    // An accumulated frame keeps the full settings.
    const Image later = automatic.render(1, 6, 1);
    EXPECT_TRUE(samePixels(later, whole.render(1, 6, 1)));
    EXPECT_FALSE(samePixels(later, small.render(1, 6, 1)));
}

TEST(FirstFrameSettings, TheFewLightBoxKeepsItsFirstFrame) {
    const Scene scene = testing::cornellBox(1.0f);  // one quad light and a point light
    Scene full = scene;
    full.render.firstFrameDivisor = 1;
    testing::InProcessRenderer automatic(scene), whole(full);
    EXPECT_FALSE(automatic.renderer().firstFrameDiffers());
    EXPECT_TRUE(samePixels(automatic.render(1, 5, 0), whole.render(1, 5, 0)));
}

}  // namespace
}  // namespace igi
