// OBJ and MTL: the material mapping and the errors that name the OBJ or MTL line.

#include <gtest/gtest.h>

#include "util/ExpectContains.h"

#include "scene/MtlMaterials.h"
#include "scene/SceneLoader.h"
#include "scene/TestScenes.h"

namespace igi {
namespace {

using test::sceneErrorOf;

const char* kOneMesh =
    R"({"meshes": [{"file": "m.obj"}], "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]}})";

const char* kTriangles =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    "usemtl a\nf 1 2 3\n";

Scene loadObjText(const std::string& obj, const std::string& mtl,
                  std::map<std::string, std::string> extra = {}) {
    extra["m.obj"] = "mtllib m.mtl\n" + obj;
    extra["m.mtl"] = mtl;
    return test::parseInline(kOneMesh, extra);
}

Material onlyMaterial(const std::string& mtlBody) {
    const Scene s = loadObjText(kTriangles, "newmtl a\n" + mtlBody);
    EXPECT_EQ(s.materials.size(), 1u);
    return s.materials.at(0);
}

TEST(MtlMapping, DiffuseAndEmission) {
    const Material m = onlyMaterial("Kd 0.1 0.2 0.3\nKe 17 12 4\nillum 2\n");
    EXPECT_EQ(m.name, "a");
    EXPECT_EQ(m.diffuse, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(m.emission, glm::vec3(17, 12, 4));
    EXPECT_TRUE(m.isEmissive());
    EXPECT_EQ(m.reflection, Reflection::None);  // illum 2 without Ks
    EXPECT_FALSE(onlyMaterial("Kd 0.5 0.5 0.5\nKe 0 0 0\n").isEmissive());
}

TEST(MtlMapping, Illum3And5AreMirrors) {
    for (const char* illum : {"3", "5"}) {
        const Material m =
            onlyMaterial(std::string("Kd 0.01 0.01 0.01\nKs 0.9 0.8 0.7\nillum ") + illum + "\n");
        EXPECT_EQ(m.reflection, Reflection::Mirror) << illum;
        EXPECT_EQ(m.specular, glm::vec3(0.9f, 0.8f, 0.7f));
        EXPECT_EQ(m.diffuse, glm::vec3(0.01f));  // kept
        EXPECT_FALSE(m.glass);
    }
}

TEST(MtlMapping, Illum4To7AreGlassWithNiAndNoTf) {
    for (const char* illum : {"4", "6", "7"}) {
        const Material m = onlyMaterial(
            std::string("Ks 0.3 0.3 0.3\nTf 0.1 0.1 0.1\nNi 2.5\nillum ") + illum + "\n");
        EXPECT_TRUE(m.glass) << illum;
        EXPECT_FLOAT_EQ(m.ior, 2.5f);
        EXPECT_EQ(m.transmittance, glm::vec3(1.0f));  // Tf ignored
    }
    EXPECT_FLOAT_EQ(onlyMaterial("Ni 1.0\nillum 7\n").ior, 1.5f);  // unusable Ni
    EXPECT_FLOAT_EQ(onlyMaterial("illum 4\n").ior, 1.5f);          // no Ni
}

TEST(MtlMapping, Illum2WithKsIsGlossyOrMirrorAbove1000) {
    const Material glossy = onlyMaterial("Kd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs 50\nillum 2\n");
    EXPECT_EQ(glossy.reflection, Reflection::Glossy);
    EXPECT_FLOAT_EQ(glossy.phongExponent, 50.0f);
    EXPECT_EQ(glossy.specular, glm::vec3(0.2f));
    EXPECT_EQ(onlyMaterial("Kd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs 1000\nillum 2\n").reflection,
              Reflection::Mirror);
    EXPECT_EQ(onlyMaterial("Kd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs 50\nillum 1\n").reflection,
              Reflection::None);
}

TEST(MtlMapping, EnergyIsConserved) {
    const Material m = onlyMaterial("Kd 0.8 0.4 0.2\nKs 0.8 0.1 0.1\nNs 10\nillum 2\n");
    // max(Kd + Ks) = 1.6 in red: both scaled by 1 / 1.6.
    EXPECT_NEAR(m.diffuse.x, 0.5f, 1e-6f);
    EXPECT_NEAR(m.specular.x, 0.5f, 1e-6f);
    EXPECT_NEAR(m.diffuse.y, 0.25f, 1e-6f);
    EXPECT_NEAR(m.specular.z, 0.0625f, 1e-6f);
}

TEST(ObjLoader, FacesWithoutMaterialGetTheDefaultGrey) {
    const Scene s = test::parseInline(
        kOneMesh, {{"m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n"}});
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].name, "default");
    EXPECT_EQ(s.materials[0].diffuse, glm::vec3(0.8f));
    EXPECT_EQ(s.meshes[0].materialIds, (std::vector<std::uint32_t>{0, 0}));
    // Shared corners are shared vertices; no normals or uvs in the file, none in the mesh.
    EXPECT_EQ(s.meshes[0].positions.size(), 4u);
    EXPECT_TRUE(s.meshes[0].normals.empty());
    EXPECT_TRUE(s.meshes[0].uvs.empty());
}

TEST(ObjLoader, NegativeIndicesAndDegenerateTrianglesAreKept) {
    const Scene s =
        test::parseInline(kOneMesh, {{"m.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf -3 -2 -1\n"}});
    ASSERT_EQ(s.meshes[0].triangles.size(), 1u);  // zero area, kept
    EXPECT_EQ(s.meshes[0].positions[s.meshes[0].triangles[0].z], glm::vec3(2, 0, 0));
}

// As Blender and tinyobjloader do, a missing material is the default one (with a warning that
// names the line), under its own name so that a scene file can still set it.
// Statements that are read but not rendered are named, once per MTL file, never dropped
// silently.
TEST(MtlMapping, UnmodelledStatementsAreNamedOncePerFile) {
    test::CapturedLog log;
    loadObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n",
                "newmtl a\nKd 0.5 0.5 0.5\nd 0.5\ndisp h.png\n"
                "newmtl b\nKd 0.5 0.5 0.5\ndisp h.png\nmap_Ks s.png\n");
    const std::string text = log.text();
    EXPECT_CONTAINS(text, "m.mtl: statements not modelled, rendered without them: ");
    EXPECT_CONTAINS(text, "disp");
    EXPECT_CONTAINS(text, "map_Ks");
    // d is modelled now (stochastic coverage): not named.
    EXPECT_EQ(text.find("d / Tr"), std::string::npos) << text;
    EXPECT_EQ(text.find("disp"), text.rfind("disp")) << text;
    test::CapturedLog quiet;
    loadObjText(kTriangles, "newmtl a\nKd 0.5 0.5 0.5\nd 1\n");
    EXPECT_EQ(quiet.text().find("not modelled"), std::string::npos) << quiet.text();
}

TEST(ObjLoader, UsemtlOfAMissingMaterialIsTheDefaultOneUnderItsName) {
    test::CapturedLog log;
    const Scene s = loadObjText(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n"
        "usemtl b\nf 2 1 3\n",
        "newmtl a\nKd 0.1 0.2 0.3\n");
    EXPECT_CONTAINS(log.text(), "m.obj:7: usemtl 'b': no material of that name in m.mtl");
    ASSERT_EQ(s.meshes[0].materialIds.size(), 3u);
    const Material& a = s.materials[s.meshes[0].materialIds[0]];
    const Material& b = s.materials[s.meshes[0].materialIds[1]];
    EXPECT_EQ(a.name, "a");
    EXPECT_EQ(a.diffuse, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(b.name, "b");
    EXPECT_EQ(b.diffuse, defaultMaterial().diffuse);
    EXPECT_EQ(s.meshes[0].materialIds[2], s.meshes[0].materialIds[1]);  // one material b
    // A scene file's "materials" section sets it like any other.
    const Scene set = test::parseInline(
        R"({"meshes": [{"file": "m.obj"}], "materials": {"b": {"diffuse": [0.5, 0.5, 0.5]}}})",
        {{"m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl b\nf 1 2 3\n"},
         {"m.mtl", "newmtl a\n"}});
    EXPECT_EQ(set.materials[set.meshes[0].materialIds[0]].diffuse, glm::vec3(0.5f));
}

TEST(ObjLoader, MissingMtllibNamesTheLine) {
    const std::string what = sceneErrorOf([] {
        test::parseInline(
            kOneMesh,
            {{"m.obj", "# comment\nmtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"}});
    });
    EXPECT_CONTAINS(what, "m.obj:2: material library 'gone.mtl' not found");
}

TEST(ObjLoader, MissingTextureNamesTheMtlLine) {
    const std::string what = sceneErrorOf(
        [] { loadObjText(kTriangles, "# x\nnewmtl a\nKd 1 1 1\nmap_Kd stone.png\n"); });
    EXPECT_CONTAINS(what, "m.mtl:4: texture 'stone.png' not found");
}

TEST(ObjLoader, TextureWithDifferentCaseIsFound) {
    DiskFileSource disk(test::testdataDir() / "minimal");
    BundleFileSource files(
        std::map<std::string, std::string>{{"m.obj", "mtllib m.mtl\n" + std::string(kTriangles)},
                                           {"m.mtl", "newmtl a\nmap_Kd CHECKER.PPM\n"},
                                           {"checker.ppm", disk.read("checker.ppm")}});
    const Scene s = parseScene(kOneMesh, "inline.json", files);
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].path, "checker.ppm");
    EXPECT_EQ(s.materials[0].diffuseTexture, 0);
}

TEST(ObjLoader, NonFiniteVertexNamesTheLine) {
    EXPECT_CONTAINS(
        sceneErrorOf(
            [] { loadObjText("v 0 0 0\nv 1 nan 0\nv 0 1 0\nusemtl a\nf 1 2 3\n", "newmtl a\n"); }),
        "m.obj:3: coordinate is not a finite number");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        loadObjText("v 0 0 0\nv 1 0 0\nv 0 1 1e999\nusemtl a\nf 1 2 3\n",
                                    "newmtl a\n");
                    }),
                    "m.obj:4: v coordinate is not finite");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        loadObjText(
                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 inf\nusemtl a\nf 1//1 2//1 3//1\n",
                            "newmtl a\n");
                    }),
                    "m.obj:5: coordinate is not a finite number");
}

TEST(ObjLoader, OutOfRangeIndicesNameTheLine) {
    EXPECT_CONTAINS(sceneErrorOf([] {
                        loadObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 4\n", "newmtl a\n");
                    }),
                    "m.obj:6: vertex index 4 is out of range (3 defined so far)");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        loadObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nusemtl a\nf 1 2 3 9\n",
                                    "newmtl a\n");
                    }),
                    "m.obj:7: vertex index 9 is out of range");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        loadObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1/1 2/1 3/1\n",
                                    "newmtl a\n");
                    }),
                    "m.obj:6: texture coordinate index 1 is out of range (0 defined so far)");
    EXPECT_CONTAINS(sceneErrorOf([] {
                        loadObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 0 1 2\n", "newmtl a\n");
                    }),
                    "m.obj:6: vertex index 0 is out of range");
}

}  // namespace
}  // namespace igi
