#include "scene/FileSource.h"

#include <gtest/gtest.h>

#include "scene/SceneError.h"
#include "scene/TestScenes.h"

namespace igi {
namespace {

TEST(ResolveRelative, JoinsToTheReferencingFilesFolder) {
    EXPECT_EQ(resolveRelative("a/b.obj", "c.mtl"), "a/c.mtl");
    EXPECT_EQ(resolveRelative("../x/y.obj", "../t.png"), "../t.png");
    EXPECT_EQ(resolveRelative("scene.obj", "./tex/a.png"), "tex/a.png");
    EXPECT_EQ(resolveRelative("", "../../s/x.obj"), "../../s/x.obj");
    EXPECT_EQ(resolveRelative("a/b/c.gltf", "../../d.bin"), "d.bin");
}

TEST(DiskFileSource, RecordsEveryFileReadKeyedAsRequested) {
    DiskFileSource disk(test::testdataDir() / "gltf", test::trusted());
    EXPECT_TRUE(disk.exists("../minimal/box.mtl"));
    EXPECT_FALSE(disk.exists("../minimal"));  // a folder is not a file
    const std::string mtl = disk.read("../minimal/box.mtl");
    EXPECT_NE(mtl.find("newmtl floor"), std::string::npos);
    ASSERT_EQ(disk.filesRead().size(), 1u);
    EXPECT_EQ(disk.filesRead().begin()->first, "../minimal/box.mtl");
    EXPECT_EQ(disk.filesRead().begin()->second, mtl);
}

TEST(DiskFileSource, MissingFileNamesThePath) {
    DiskFileSource disk(test::testdataDir());
    const std::string what = test::sceneErrorOf([&] { disk.read("minimal/nope.obj"); });
    EXPECT_NE(what.find("minimal/nope.obj"), std::string::npos) << what;
    EXPECT_NE(what.find("cannot read"), std::string::npos) << what;
    EXPECT_TRUE(disk.filesRead().empty());
}

TEST(DiskFileSource, ListsAFolderSorted) {
    DiskFileSource disk(test::testdataDir());
    const auto names = disk.list("minimal");
    const std::vector<std::string> expected{"box.mtl", "box.obj", "checker.ppm", "scene.json"};
    EXPECT_EQ(names, expected);
}

TEST(BundleFileSource, ServesReadsExistsAndListsFromMemory) {
    BundleFileSource bundle(std::map<std::string, std::string>{
        {"a.obj", "A"}, {"tex/b.png", "B"}, {"tex/c.png", "C"}, {"../up.mtl", "U"}});
    EXPECT_EQ(bundle.read("tex/b.png"), "B");
    EXPECT_TRUE(bundle.exists("../up.mtl"));
    EXPECT_FALSE(bundle.exists("tex/d.png"));
    EXPECT_EQ(bundle.list("tex"), (std::vector<std::string>{"b.png", "c.png"}));
    EXPECT_EQ(bundle.list(""), (std::vector<std::string>{"a.obj"}));
    EXPECT_EQ(bundle.list(".."), (std::vector<std::string>{"up.mtl"}));
    const std::string what = test::sceneErrorOf([&] { bundle.read("tex/d.png"); });
    EXPECT_NE(what.find("tex/d.png"), std::string::npos) << what;
}

}  // namespace
}  // namespace igi
