#pragma once

#include <string>
#include <vector>

#include "render/RenderSettings.h"
#include "scene/Camera.h"
#include "scene/Environment.h"
#include "scene/Light.h"
#include "scene/Material.h"
#include "scene/Mesh.h"
#include "scene/Texture.h"

namespace igi {

/// The output image's size and how it is shown.
struct ImageSettings {
    int width = 640;
    int height = 480;
    float exposure = 0.0f;  ///< stops applied before tone mapping to the PNG
};

/// A whole scene as plain data: what a scene file says, with every mesh and texture it
/// references loaded. It knows nothing of Embree; the client turns it into a traceable scene.
struct Scene {
    std::string sourcePath;  ///< the scene file, for messages
    Camera camera;
    ImageSettings image;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Mesh> meshes;
    std::vector<PunctualLight> punctualLights;
    std::vector<QuadLight> quadLights;
    Environment environment;
    RenderSettings render;
};

}  // namespace igi
