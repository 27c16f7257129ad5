// Import of every format Assimp reads. Assimp triangulates (ear clipping) and validates; the
// node hierarchy is walked here so each mesh instance lands in world space, once per use.
#include "importers.h"

#include "declared_counts.h"
#include "gltf_facts.h"
#include "material_mapping.h"
#include "mesh_builder.h"
#include "polygon.h"

#include <kdray/error.h>
#include <kdray/util.h>

#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <utility>

namespace kdray {
namespace {

// Formats whose readers already share vertices between faces. Joining identical vertices is
// what makes the others (STL, 3DS, FBX, ...) indexed, but on an indexed 1M-triangle PLY it
// costs three quarters of the conversion time for nothing.
bool is_indexed_format(const std::string& path) {
  const std::string extension = lowercase_extension(path);
  return extension == ".ply" || extension == ".off" || extension == ".gltf" || extension == ".glb";
}

unsigned post_processing_for(const std::string& path) {
  const unsigned always = aiProcess_Triangulate | aiProcess_ValidateDataStructure;
  return is_indexed_format(path) ? always : always | aiProcess_JoinIdenticalVertices;
}

Vec3 to_vec3(const aiVector3D& v) { return {v.x, v.y, v.z}; }
Vec3 to_vec3(const aiColor3D& c) { return {c.r, c.g, c.b}; }

Vec3 normalized(const aiVector3D& v) {
  const float length = v.Length();
  return length > 0 ? Vec3{v.x / length, v.y / length, v.z / length} : Vec3{};
}

// An authored tangent frame in world space as the scene stores it: the unit tangent and the
// side of cross(n, t) its bitangent lies on (a zero tangent counts as absent in MeshBuilder).
Tangent world_tangent(const aiVector3D& normal, const aiVector3D& tangent, const aiVector3D& bitangent) {
  const Vec3 t = normalized(tangent);
  const float w = ((normal ^ tangent) * bitangent) < 0 ? -1.0f : 1.0f;
  return {t.x, t.y, t.z, w};
}

// Watts per lumen at 555 nm, the factor between glTF's photometric light units (candela, lux) and
// the radiometric ones kdray renders in (W/sr, W/m^2).
constexpr float kWattsPerLumen = 1.0f / 683.0f;

// `emissive_strength` multiplies the emission where Assimp gives no intensity of its own (its glTF
// importer drops KHR_materials_emissive_strength).
SourceMaterial source_material(const aiMaterial& material, float emissive_strength) {
  SourceMaterial source;
  aiString name;
  if (material.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) source.name = name.C_Str();
  aiColor3D color;
  if (material.Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS) source.diffuse = to_vec3(color);
  aiColor4D base_color;
  if (material.Get(AI_MATKEY_BASE_COLOR, base_color) == AI_SUCCESS)
    source.diffuse = {base_color.r, base_color.g, base_color.b};
  if (material.Get(AI_MATKEY_COLOR_SPECULAR, color) == AI_SUCCESS) source.specular = to_vec3(color);
  if (material.Get(AI_MATKEY_COLOR_EMISSIVE, color) == AI_SUCCESS) source.emission = to_vec3(color);
  float intensity = emissive_strength;
  material.Get(AI_MATKEY_EMISSIVE_INTENSITY, intensity);
  source.emission = {source.emission.x * intensity, source.emission.y * intensity, source.emission.z * intensity};
  material.Get(AI_MATKEY_SHININESS, source.shininess);
  material.Get(AI_MATKEY_REFRACTI, source.ior);
  material.Get(AI_MATKEY_OPACITY, source.opacity);
  material.Get(AI_MATKEY_TRANSMISSION_FACTOR, source.transmission);
  float value = 0;
  if (material.Get(AI_MATKEY_METALLIC_FACTOR, value) == AI_SUCCESS) source.metallic = value;
  if (material.Get(AI_MATKEY_ROUGHNESS_FACTOR, value) == AI_SUCCESS) source.roughness = value;
  // Assimp's OBJ and 3DS importers record a mirror or glass illumination model as the shading mode.
  int shading = 0;
  if (material.Get(AI_MATKEY_SHADING_MODEL, shading) == AI_SUCCESS && shading == aiShadingMode_Fresnel) source.illum = 5;
  aiString texture;
  if (material.GetTexture(aiTextureType_BASE_COLOR, 0, &texture) == AI_SUCCESS ||
      material.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS)
    source.diffuse_texture = texture.C_Str();
  if (material.GetTexture(AI_MATKEY_GLTF_PBRMETALLICROUGHNESS_METALLICROUGHNESS_TEXTURE, &texture) == AI_SUCCESS)
    source.metal_rough_texture = texture.C_Str();
  if (material.GetTexture(aiTextureType_NORMALS, 0, &texture) == AI_SUCCESS) source.normal_texture = texture.C_Str();
  if (material.GetTexture(aiTextureType_EMISSIVE, 0, &texture) == AI_SUCCESS) source.emissive_texture = texture.C_Str();
  aiString alpha_mode;
  if (material.Get(AI_MATKEY_GLTF_ALPHAMODE, alpha_mode) == AI_SUCCESS) {
    const std::string mode = alpha_mode.C_Str();
    source.alpha_mode = mode == "MASK" ? AlphaMode::Mask : mode == "BLEND" ? AlphaMode::Blend : AlphaMode::Opaque;
    material.Get(AI_MATKEY_GLTF_ALPHACUTOFF, source.alpha_cutoff);
  }
  return source;
}

aiMatrix4x4 global_transform(const aiNode* node) {
  aiMatrix4x4 transform;
  for (; node != nullptr; node = node->mParent) transform = node->mTransformation * transform;
  return transform;
}

class AssimpConverter {
 public:
  AssimpConverter(const std::string& path, const aiScene& source, Scene& scene)
      : path_(path), source_(source), scene_(scene), builder_(scene.import_stats) {
    if (is_gltf_path(path)) gltf_ = read_gltf_facts(path);
  }

  void convert() {
    if (gltf_)
      for (const std::string& extension : unmodelled_gltf_extensions(gltf_->extensions_used))
        scene_.import_stats.warnings.push_back("glTF extension " + extension +
                                               " is not modelled by kdray: the asset renders without it");
    convert_materials();
    // Iterative walk: a hostile file's deep hierarchy must not exhaust the stack.
    std::vector<std::pair<const aiNode*, aiMatrix4x4>> pending = {{source_.mRootNode, source_.mRootNode->mTransformation}};
    while (!pending.empty()) {
      auto [node, transform] = pending.back();
      pending.pop_back();
      for (unsigned i = 0; i < node->mNumMeshes; ++i) add_mesh_instance(*source_.mMeshes[node->mMeshes[i]], transform);
      for (unsigned i = 0; i < node->mNumChildren; ++i)
        pending.emplace_back(node->mChildren[i], transform * node->mChildren[i]->mTransformation);
    }
    builder_.finish(scene_);
    convert_cameras();
    convert_lights();
  }

 private:
  void convert_materials() {
    TextureCache textures(scene_);
    const std::filesystem::path directory = std::filesystem::path(path_).parent_path();
    for (unsigned i = 0; i < source_.mNumMaterials; ++i) {
      const float emissive_strength = gltf_ && i < gltf_->emissive_strength.size() ? gltf_->emissive_strength[i] : 1;
      const SourceMaterial source = source_material(*source_.mMaterials[i], emissive_strength);
      Material material = map_material(source);
      material.diffuse_texture = texture_index(textures, directory, source.diffuse_texture);
      material.normal_texture = texture_index(textures, directory, source.normal_texture);
      if (material.type == MaterialType::MetallicRoughness)
        material.metal_rough_texture = texture_index(textures, directory, source.metal_rough_texture);
      if (material.type == MaterialType::Emissive)
        material.emissive_texture = texture_index(textures, directory, source.emissive_texture);
      scene_.materials.push_back(material);
    }
  }

  // The decoded texture a material names (embedded or a file beside the asset), or -1.
  int32_t texture_index(TextureCache& textures, const std::filesystem::path& directory, const std::string& reference) {
    if (reference.empty()) return -1;
    if (const aiTexture* embedded = source_.GetEmbeddedTexture(reference.c_str()))
      return embedded_texture(textures, reference, *embedded);
    return textures.from_file((directory / reference).string(), reference);
  }

  int32_t embedded_texture(TextureCache& textures, const std::string& key, const aiTexture& texture) {
    if (texture.mHeight == 0)  // compressed image file bytes (PNG, JPEG...)
      return textures.from_memory(key, texture.pcData, texture.mWidth, texture.achFormatHint);
    return textures.from_texels(key, [&] {
      Texture decoded;  // raw BGRA texels
      decoded.name = key;
      decoded.width = texture.mWidth;
      decoded.height = texture.mHeight;
      decoded.rgba.resize(uint64_t(texture.mWidth) * texture.mHeight * 4);
      for (uint64_t i = 0; i < uint64_t(texture.mWidth) * texture.mHeight; ++i) {
        const aiTexel& texel = texture.pcData[i];
        uint8_t* out = &decoded.rgba[i * 4];
        out[0] = texel.r, out[1] = texel.g, out[2] = texel.b, out[3] = texel.a;
      }
      return decoded;
    });
  }

  void add_mesh_instance(const aiMesh& mesh, const aiMatrix4x4& transform) {
    const aiMatrix3x3 linear(transform);
    aiMatrix3x3 normal_transform(transform);
    normal_transform.Inverse().Transpose();
    std::vector<uint32_t> vertex(mesh.mNumVertices);
    const bool has_uvs = mesh.HasTextureCoords(0);
    // glTF's TANGENT attribute arrives this way (Assimp 5.2 sets the bitangent to
    // w * cross(normal, tangent)); other formats' importers fill them only when asked to compute.
    const bool has_tangents = mesh.HasNormals() && mesh.HasTangentsAndBitangents();
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      std::optional<Vec3> normal;
      if (mesh.HasNormals()) normal = normalized(normal_transform * mesh.mNormals[i]);
      std::optional<Vec2> uv;
      if (has_uvs) uv = Vec2{mesh.mTextureCoords[0][i].x, mesh.mTextureCoords[0][i].y};
      std::optional<Tangent> tangent;
      if (has_tangents) tangent = world_tangent(normal_transform * mesh.mNormals[i], linear * mesh.mTangents[i],
                                                linear * mesh.mBitangents[i]);
      vertex[i] = builder_.add_vertex(to_vec3(transform * mesh.mVertices[i]), normal, uv, tangent);
    }
    std::vector<uint32_t> polygon;
    std::vector<Vec3> corners;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      for (unsigned i = 0; i < face.mNumIndices; ++i)
        if (face.mIndices[i] >= mesh.mNumVertices) throw Error(path_, "a face refers to a vertex that does not exist");
      if (face.mNumIndices == 1) ++scene_.import_stats.ignored_points;
      if (face.mNumIndices == 2) ++scene_.import_stats.ignored_lines;
      if (face.mNumIndices == 3) {
        builder_.add_triangle(vertex[face.mIndices[0]], vertex[face.mIndices[1]], vertex[face.mIndices[2]],
                              mesh.mMaterialIndex);
        continue;
      }
      // Triangulate normally leaves only triangles; larger faces are ear-clipped as for OBJ.
      polygon.clear();
      corners.clear();
      for (unsigned i = 0; i < face.mNumIndices; ++i) {
        polygon.push_back(vertex[face.mIndices[i]]);
        corners.push_back(builder_.position(polygon.back()));
      }
      for (const auto& triangle : triangulate_polygon(corners))
        builder_.add_triangle(polygon[triangle[0]], polygon[triangle[1]], polygon[triangle[2]], mesh.mMaterialIndex);
    }
  }

  void convert_cameras() {
    for (unsigned i = 0; i < source_.mNumCameras; ++i) {
      const aiCamera& camera = *source_.mCameras[i];
      const aiMatrix4x4 transform = global_transform(source_.mRootNode->FindNode(camera.mName));
      const aiMatrix3x3 rotation(transform);
      Camera converted;
      converted.name = camera.mName.C_Str();
      // Assimp 5.2's glTF importer also copies the node's translation into mPosition, which the
      // node transform then applies a second time: such a position is the node's own.
      const aiNode* node = source_.mRootNode->FindNode(camera.mName);
      const aiVector3D local_translation = node ? aiVector3D(node->mTransformation.a4, node->mTransformation.b4,
                                                             node->mTransformation.c4)
                                                : aiVector3D();
      const bool position_is_node_translation = camera.mPosition != aiVector3D() && camera.mPosition == local_translation;
      const aiVector3D position = transform * (position_is_node_translation ? aiVector3D() : camera.mPosition);
      converted.position = to_vec3(position);
      converted.target = to_vec3(position + rotation * camera.mLookAt);
      converted.up = normalized(rotation * camera.mUp);
      if (gltf_ && i < gltf_->cameras.size())
        set_gltf_projection(converted, gltf_->cameras[i]);
      else
        set_projection(converted, camera);
      scene_.cameras.push_back(converted);
    }
  }

  // From Assimp's values. Assimp documents mHorizontalFOV as half the angle, but its 5.2 Collada
  // and FBX importers store the full horizontal angle; mOrthographicWidth is half the width.
  void set_projection(Camera& converted, const aiCamera& camera) {
    const float aspect = std::isfinite(camera.mAspect) && camera.mAspect > 0 ? camera.mAspect : 0;
    converted.aspect_ratio = aspect;
    if (camera.mOrthographicWidth > 0) {
      set_orthographic(converted, camera.mOrthographicWidth / (aspect > 0 ? aspect : 1));
      return;
    }
    const float horizontal = camera.mHorizontalFOV;
    set_vertical_fov(converted, aspect > 0 ? 2 * std::atan(std::tan(horizontal / 2) / aspect) : horizontal);
  }

  // From the glTF's JSON: Assimp 5.2's importer keeps yfov x aspect, a linear product that no
  // conversion through tan undoes, and gives orthographic cameras no extent.
  void set_gltf_projection(Camera& converted, const GltfCamera& authored) {
    if (authored.orthographic) {
      converted.aspect_ratio = authored.xmag > 0 && authored.ymag > 0 ? authored.xmag / authored.ymag : 0;
      set_orthographic(converted, authored.ymag);
      return;
    }
    converted.aspect_ratio = std::isfinite(authored.aspect_ratio) && authored.aspect_ratio > 0 ? authored.aspect_ratio : 0;
    set_vertical_fov(converted, authored.yfov_radians);
  }

  void set_vertical_fov(Camera& converted, float radians) {
    if (std::isfinite(radians) && radians > 0 && radians < float(M_PI)) {
      converted.vertical_fov_degrees = radians * float(180.0 / M_PI);
      return;
    }
    scene_.import_stats.warnings.push_back("camera '" + converted.name + "' has no valid field of view: " +
                                           std::to_string(converted.vertical_fov_degrees) + " degrees used");
  }

  void set_orthographic(Camera& converted, float half_height) {
    if (!(std::isfinite(half_height) && half_height > 0)) {
      scene_.import_stats.warnings.push_back("orthographic camera '" + converted.name +
                                             "' has no valid extent: rendered as a perspective camera");
      return;
    }
    converted.projection = Projection::Orthographic;
    converted.orthographic_half_height = half_height;
  }

  // Point, spot and directional lights at their nodes. Assimp's glTF importer hands over the
  // colour times the intensity (candela for point and spot lights, lux for directional ones, as
  // KHR_lights_punctual defines them: converted to W/sr and W/m^2 here) and stores the spot cone's
  // half-angles, although aiLight documents full angles (checked with a KHR_lights_punctual file:
  // innerConeAngle 0.2 reads 0.2). Other formats' intensities are taken as radiometric. Other
  // kinds (ambient, area) are reported and skipped.
  void convert_lights() {
    for (unsigned i = 0; i < source_.mNumLights; ++i) {
      const aiLight& light = *source_.mLights[i];
      Light converted;
      converted.name = light.mName.C_Str();
      switch (light.mType) {
        case aiLightSource_POINT: converted.type = LightType::Point; break;
        case aiLightSource_SPOT: converted.type = LightType::Spot; break;
        case aiLightSource_DIRECTIONAL: converted.type = LightType::Directional; break;
        default:
          scene_.import_stats.warnings.push_back("light '" + converted.name + "' of a kind kdray does not render (" +
                                                 std::to_string(int(light.mType)) + ") was skipped");
          continue;
      }
      const aiNode* node = source_.mRootNode->FindNode(light.mName);
      const aiMatrix4x4 transform = node ? global_transform(node) : aiMatrix4x4();
      converted.position = to_vec3(transform * light.mPosition);
      const aiVector3D direction = aiMatrix3x3(transform) * light.mDirection;
      converted.direction = direction.Length() > 0 ? normalized(direction) : Vec3{0, 0, -1};
      const float to_watts = gltf_ ? kWattsPerLumen : 1;
      converted.color = {light.mColorDiffuse.r * to_watts, light.mColorDiffuse.g * to_watts,
                         light.mColorDiffuse.b * to_watts};
      if (converted.type == LightType::Spot) {
        converted.outer_cone_radians = std::clamp(light.mAngleOuterCone, 0.0f, float(M_PI));
        converted.inner_cone_radians = std::clamp(light.mAngleInnerCone, 0.0f, converted.outer_cone_radians);
      }
      const Vec3& c = converted.color;
      const Vec3& p = converted.position;
      if (!(std::isfinite(p.x + p.y + p.z) && std::isfinite(c.x + c.y + c.z) && c.x >= 0 && c.y >= 0 && c.z >= 0)) {
        scene_.import_stats.warnings.push_back("light '" + converted.name + "' with a non-finite or negative value was skipped");
        continue;
      }
      scene_.lights.push_back(converted);
    }
  }

  std::string path_;
  const aiScene& source_;
  Scene& scene_;
  MeshBuilder builder_;
  std::optional<GltfFacts> gltf_;
};

}  // namespace

Scene import_with_assimp(const std::string& path) {
  check_declared_counts(path);
  Assimp::Importer importer;
  const aiScene* source = importer.ReadFile(path, post_processing_for(path));
  if (source == nullptr || source->mRootNode == nullptr) {
    std::string message = importer.GetErrorString();
    while (!message.empty() && (message.back() == '\n' || message.back() == '\r')) message.pop_back();
    throw Error(path, "Assimp cannot read it: " + (message.empty() ? std::string("unknown error") : message));
  }
  Scene scene;
  scene.import_stats.importer = "assimp";
  AssimpConverter(path, *source, scene).convert();
  return scene;
}

}  // namespace kdray
