#pragma once

// MTL materials: reading MTL files through a FileSource for tinyobjloader, and mapping the
// MTL statements to igi::Material (docs/SCENE_FORMAT.md, "OBJ and MTL").

#include <map>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "scene/FileSource.h"
#include "scene/Material.h"
#include "scene/SceneAssets.h"
#include "scene/SceneLimits.h"

namespace igi {

/// Serves `mtllib` statements from a FileSource and remembers, for error messages, which MTL
/// file each material came from and what it said. It never throws (tinyobjloader calls it);
/// libraries it cannot read are listed in missing(), with the reason in problem(). It refuses
/// a library whose `newmtl` statements would bring the scene's materials (`sceneMaterials`
/// before this OBJ) past `maxMaterials`.
class FileSourceMtlReader : public tinyobj::MaterialReader {
  public:
    FileSourceMtlReader(FileSource& files, std::string objPath,
                        std::size_t maxMaterials = SceneLimits{}.maxMaterials,
                        std::size_t sceneMaterials = 0);

    bool operator()(const std::string& matId, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* matMap, std::string* warn,
                    std::string* err) override;

    /// Library names, as the OBJ wrote them, that could not be read.
    const std::vector<std::string>& missing() const { return missing_; }
    /// Why a missing library could not be read, when it exists but may not be used ("" when
    /// it does not exist).
    std::string problem(const std::string& library) const;
    /// Names of the libraries that were read, relative to the scene file.
    const std::vector<std::string>& libraries() const { return libraries_; }
    /// The MTL file (relative to the scene file) of each material, by index.
    const std::vector<std::string>& materialFiles() const { return materialFiles_; }
    const std::string& text(const std::string& mtlPath) const { return texts_.at(mtlPath); }

    /// Serves `library` as a library of placeholder materials, the default grey one under each
    /// of `names`: what the faces of an OBJ's `usemtl` of a name no library defines get.
    /// Throws SceneError when they would bring the scene past maxMaterials.
    void addPlaceholders(const std::string& library, const std::vector<std::string>& names);
    /// Forgets what was read (not the placeholders), for a second parse of the same OBJ.
    void restart();

  private:
    FileSource& files_;
    std::string objPath_;
    std::size_t maxMaterials_;
    std::size_t sceneMaterials_;
    std::vector<std::string> missing_;
    std::map<std::string, std::string> problems_;
    std::vector<std::string> libraries_;
    std::vector<std::string> materialFiles_;
    std::map<std::string, std::string> texts_;
    std::map<std::string, std::string> placeholders_;  ///< library name -> MTL text
};

/// Maps one MTL material to a Material, loading its map_Kd texture through `assets`.
/// Throws SceneError naming the MTL file and line when the texture does not exist.
Material materialFromMtl(const tinyobj::material_t& mtl, const std::string& mtlPath,
                         const std::string& mtlText, SceneAssets& assets);

/// The grey diffuse material of faces that name none.
Material defaultMaterial();

/// Scales diffuse and specular down so that no channel reflects more than it receives
/// (max over channels of Kd + Ks <= 1), with one warning naming `where`. Glass is left alone
/// (its diffuse and specular are not used).
void conserveEnergy(Material& material, const std::string& where);

/// The statements of an MTL material that igi reads but does not render (`d` or `Tr` below
/// opacity one on glass, `bump`/`map_bump`, `norm`, `disp`, `map_Ks`, `map_Ns`, `map_Ke`), for
/// the loader's one warning per MTL file.
std::vector<std::string> unmodelledMtlStatements(const tinyobj::material_t& mtl);

}  // namespace igi
