#include "scene/SceneError.h"

#include <gtest/gtest.h>

namespace igi {
namespace {

TEST(SceneError, FormatsFileAndLine) {
    const SceneError e = SceneError::atLine("box.obj", 12, "usemtl 'x': no such material");
    EXPECT_STREQ(e.what(), "box.obj:12: usemtl 'x': no such material");
    EXPECT_EQ(e.line(), 12);
    EXPECT_EQ(e.file(), "box.obj");
    EXPECT_EQ(e.message(), "usemtl 'x': no such material");
}

TEST(SceneError, FormatsFileAndJsonPath) {
    const SceneError e = SceneError::atPath("scene.json", "/meshes/1/transfrom", "unknown key");
    EXPECT_STREQ(e.what(), "scene.json: /meshes/1/transfrom: unknown key");
    EXPECT_EQ(e.jsonPath(), "/meshes/1/transfrom");
    EXPECT_EQ(e.line(), 0);
}

TEST(SceneError, FormatsFileOnly) {
    EXPECT_STREQ(SceneError::inFile("a.png", "cannot read file").what(), "a.png: cannot read file");
}

}  // namespace
}  // namespace igi
