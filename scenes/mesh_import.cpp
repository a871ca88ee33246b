#include "scenes/mesh_import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/importerdesc.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "scenes/errors.h"
#include "scenes/ply_check.h"

#define STB_IMAGE_IMPLEMENTATION
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>

namespace voxgi {

namespace fs = std::filesystem;

namespace {

Texture textureFromPixels(const std::string& name, stbi_uc* pixels, int w, int h) {
    Texture t;
    t.path = name;
    t.width = w;
    t.height = h;
    t.rgba.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
    stbi_image_free(pixels);
    // The decode table, not pow per texel: Sponza's textures took seconds of every load.
    const float* decode = srgbDecodeTable();
    glm::dvec3 sum(0.0);
    for (std::size_t i = 0; i < t.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) sum[c] += double(decode[t.rgba[i + std::size_t(c)]]);
    t.averageLinear = glm::vec3(sum / double(std::size_t(w) * std::size_t(h)));
    return t;
}

struct Importer {
    const aiScene* ai;
    fs::path dir;
    Scene& scene;
    std::map<std::string, int> textureIndex;

    int texture(const aiMaterial* mat) {
        aiString file;
        if (mat->GetTexture(aiTextureType_BASE_COLOR, 0, &file) != AI_SUCCESS &&
            mat->GetTexture(aiTextureType_DIFFUSE, 0, &file) != AI_SUCCESS)
            return -1;
        std::string key = file.C_Str();
        auto it = textureIndex.find(key);
        if (it != textureIndex.end()) return it->second;
        Texture t;
        if (const aiTexture* embedded = ai->GetEmbeddedTexture(file.C_Str())) {
            int w = 0, h = 0, n = 0;
            stbi_uc* px = nullptr;
            if (embedded->mHeight == 0)
                px = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(embedded->pcData),
                                           int(embedded->mWidth), &w, &h, &n, 4);
            if (!px) throw InputError(dir.string() + ": embedded texture " + key + ": cannot decode");
            t = textureFromPixels(key, px, w, h);
        } else {
            std::string rel = key;
            for (char& c : rel)
                if (c == '\\') c = '/';
            t = loadTexture((dir / rel).string());
        }
        scene.textures.push_back(std::move(t));
        int index = int(scene.textures.size() - 1);
        textureIndex[key] = index;
        return index;
    }

    std::uint32_t material(const aiMaterial* mat) {
        Material m;
        aiString name;
        if (mat->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) m.name = name.C_Str();
        aiColor4D c;
        if (mat->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS ||
            mat->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
            m.albedo = glm::vec3(c.r, c.g, c.b);
        aiColor3D e;
        if (mat->Get(AI_MATKEY_COLOR_EMISSIVE, e) == AI_SUCCESS) m.emission = glm::vec3(e.r, e.g, e.b);
        float f = 0.0f;
        if (mat->Get(AI_MATKEY_ROUGHNESS_FACTOR, f) == AI_SUCCESS) m.roughness = f;
        if (mat->Get(AI_MATKEY_METALLIC_FACTOR, f) == AI_SUCCESS) {
            m.metallic = f;
            m.specular = 0.04f;  // glTF's dielectric F0
        }
        if (mat->Get(AI_MATKEY_REFRACTI, f) == AI_SUCCESS && f >= 1.0f) m.ior = f;
        // OBJ: a specular colour with a Phong exponent maps to a GGX roughness (Walter et al.).
        aiColor3D ks;
        float shininess = 0.0f;
        if (mat->Get(AI_MATKEY_COLOR_SPECULAR, ks) == AI_SUCCESS && ks.r + ks.g + ks.b > 0.0f &&
            mat->Get(AI_MATKEY_SHININESS, shininess) == AI_SUCCESS && shininess > 0.0f)
        {
            m.roughness = std::sqrt(std::sqrt(2.0f / (shininess + 2.0f)));
            m.specular = std::min(0.08f, std::max({ks.r, ks.g, ks.b}));
        }
        m.albedoTexture = texture(mat);
        scene.materials.push_back(m);
        return std::uint32_t(scene.materials.size() - 1);
    }
};

}  // namespace

Texture loadTexture(const std::string& path) {
    int w = 0, h = 0, n = 0;
    stbi_uc* px = stbi_load(path.c_str(), &w, &h, &n, 4);
    if (!px) throw InputError(path + ": cannot load texture (" + stbi_failure_reason() + ")");
    return textureFromPixels(path, px, w, h);
}

namespace {

// The importer assimp 5.2 will read the file with, decided the way ReadFile decides: the one
// importer that lists the file's extension, or the first of several that accepts the content.
// Where none does, ReadFile would fall back to guessing from the content among all ~50 importers
// (a .gltf that is not JSON reaches the PLY or OpenGEX reader, which loop or overrun their
// buffers on it): that file is refused here instead.
bool listsExtension(const Assimp::BaseImporter* reader, const std::string& extension) {
    std::istringstream extensions(reader->GetInfo()->mFileExtensions);
    for (std::string e; extensions >> e;)
        if (e == extension) return true;
    return false;
}

const Assimp::BaseImporter* importerFor(Assimp::Importer& importer, const std::string& path) {
    std::string extension = fs::path(path).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (extension.size() > 1) extension = extension.substr(1);
    std::vector<const Assimp::BaseImporter*> listing;
    for (std::size_t i = 0; i < importer.GetImporterCount(); ++i)
        if (listsExtension(importer.GetImporter(i), extension)) listing.push_back(importer.GetImporter(i));
    if (listing.empty()) throw InputError(path + ": unknown mesh format '." + extension + "'");
    if (listing.size() == 1) return listing[0];
    for (const Assimp::BaseImporter* candidate : listing)
        if (candidate->CanRead(path, importer.GetIOHandler(), false)) return candidate;
    throw InputError(path + ": cannot load mesh (not a ." + extension + " file that assimp recognises)");
}

}  // namespace

MeshImportStats importMeshFile(const std::string& path, const glm::mat4& transform, Scene& scene,
                               int materialOverride) {
    if (!fs::exists(path)) throw InputError(path + ": mesh file not found");
    Assimp::Importer importer;
    const Assimp::BaseImporter* reader = importerFor(importer, path);
    if (listsExtension(reader, "ply")) checkPlyFile(path);
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    importer.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, 60.0f);
    // Read and validate first (indices in range, counts consistent), check what assimp's
    // post-processing asserts on, and only then post-process: a malformed file is an error
    // message, never a crash inside assimp.
    const aiScene* ai = importer.ReadFile(path, aiProcess_ValidateDataStructure);
    auto fail = [&](const std::string& why) {
        throw InputError(path + ": cannot load mesh (" + (why.empty() ? "unknown format" : why) + ")");
    };
    if (!ai || !ai->mRootNode) fail(importer.GetErrorString());
    for (unsigned mi = 0; mi < ai->mNumMeshes; ++mi) {
        const aiMesh* am = ai->mMeshes[mi];
        if (!(am->mPrimitiveTypes & (aiPrimitiveType_TRIANGLE | aiPrimitiveType_POLYGON))) continue;
        for (unsigned f = 0; f < am->mNumFaces; ++f)
            if (am->mFaces[f].mNumIndices < 3 || !am->mFaces[f].mIndices)
                fail("mesh " + std::to_string(mi) + " face " + std::to_string(f) + " has " +
                     std::to_string(am->mFaces[f].mNumIndices) + " indices among polygons; truncated or malformed file");
    }
    ai = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_GenSmoothNormals |
                                      aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
    if (!ai || !ai->mRootNode) fail(importer.GetErrorString());
    MeshImportStats stats;
    Importer imp{ai, fs::path(path).parent_path(), scene, {}};
    std::vector<std::uint32_t> materialMap(ai->mNumMaterials, 0);
    if (materialOverride < 0) {
        std::size_t texturesBefore = scene.textures.size();
        for (unsigned i = 0; i < ai->mNumMaterials; ++i) materialMap[i] = imp.material(ai->mMaterials[i]);
        stats.materials = ai->mNumMaterials;
        stats.textures = scene.textures.size() - texturesBefore;
    }
    glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    for (unsigned mi = 0; mi < ai->mNumMeshes; ++mi) {
        const aiMesh* am = ai->mMeshes[mi];
        if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        Mesh mesh;
        mesh.name = fs::path(path).stem().string() + "/" + am->mName.C_Str();
        std::uint32_t mat = materialOverride >= 0 ? std::uint32_t(materialOverride)
                                                  : materialMap[am->mMaterialIndex];
        for (unsigned v = 0; v < am->mNumVertices; ++v) {
            const aiVector3D& p = am->mVertices[v];
            mesh.positions.push_back(glm::vec3(transform * glm::vec4(p.x, p.y, p.z, 1.0f)));
            if (am->mNormals) {
                const aiVector3D& n = am->mNormals[v];
                glm::vec3 wn = normalMatrix * glm::vec3(n.x, n.y, n.z);
                float len = glm::length(wn);
                mesh.normals.push_back(len > 0.0f ? wn / len : glm::vec3(0, 1, 0));
            }
            if (am->mTextureCoords[0])
                mesh.uvs.emplace_back(am->mTextureCoords[0][v].x, am->mTextureCoords[0][v].y);
        }
        for (unsigned f = 0; f < am->mNumFaces; ++f) {
            const aiFace& face = am->mFaces[f];
            if (face.mNumIndices != 3) continue;
            mesh.indices.insert(mesh.indices.end(), {face.mIndices[0], face.mIndices[1], face.mIndices[2]});
            mesh.materialIds.push_back(mat);
        }
        stats.triangles += mesh.triangleCount();
        if (mesh.triangleCount() > 0) scene.meshes.push_back(std::move(mesh));
    }
    if (stats.triangles == 0) throw InputError(path + ": mesh has no triangles");
    return stats;
}

}  // namespace voxgi
