// The "environment" section of a scene file: the sky.

#include <cmath>
#include <string>

#include "scene/SceneError.h"
#include "scene/SceneSections.h"

namespace igi {

namespace {

// A map whose texels are not finite would make every pixel that sees it NaN (the decoder reads
// them as 0, which would hide a broken file): say which texel.
void checkTexels(const JsonNode& fileNode, const Texture& t) {
    if (t.firstNonFinite < 0) return;
    const long long x = t.firstNonFinite % t.width, y = t.firstNonFinite / t.width;
    fileNode.fail("'" + t.path + "': texel (" + std::to_string(x) + ", " + std::to_string(y) +
                  ") is " + std::to_string(t.nonFiniteValue) +
                  ", expected a finite radiance (x from the left, y from the top)");
}

}  // namespace

void parseEnvironment(const JsonNode& node, SceneAssets& assets) {
    node.requireObject();
    Environment& e = assets.scene().environment;
    if (node.find("file")) {
        node.checkKeys({"file", "scale", "rotate_deg"});
        const JsonNode fileNode = node.at("file");
        const std::string path = fileNode.string();
        std::optional<int> texture;
        try {
            texture = assets.textureFile(path);
        } catch (const SceneError& error) {
            fileNode.fail("'" + path + "': " + error.message());  // not an image
        }
        if (!texture) fileNode.fail("file '" + path + "' not found");
        checkTexels(fileNode, assets.scene().textures[std::size_t(*texture)]);
        e.texture = *texture;
        e.radiance = glm::vec3(1.0f);
        // The map's radiance is multiplied by this (one number or per channel).
        if (auto scale = node.find("scale")) e.radiance = scale->rgb(NumberRange::atLeast(0));
    } else {
        node.checkKeys({"radiance", "rotate_deg"});
        // A constant sky: radiance W/(m^2 sr) from every direction.
        e.radiance = node.at("radiance").rgb(NumberRange::atLeast(0));
    }
    if (auto rotate = node.find("rotate_deg")) e.rotateDeg = rotate->real();
}

}  // namespace igi
