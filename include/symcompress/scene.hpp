// The scene model: what every reader produces and every writer consumes.
//
// Invariants (checked by validateScene):
// - every Primitive has positions.size() vertices; normals, texcoords and colors are either empty or
//   have exactly positions.size() entries; every triangle index is < positions.size();
// - every coordinate and attribute value is finite;
// - Primitive::material is -1 (default material) or an index into Scene::materials;
// - a Material's variants are empty or one per Scene::materialVariants, each -1 or an index into Scene::materials
//   of a material without variants;
// - Node::mesh is -1 or an index into Scene::meshes; Node::children index into Scene::nodes and the
//   node graph is a forest (a node is the child of at most one node, no cycles);
// - every TextureRef of a Material (Material::textureRefs) has a texture of -1 or an index into
//   Scene::textures;
// - Node::camera and Node::light are -1 or indices into Scene::cameras and Scene::lights, whose numbers are
//   finite (a perspective camera's yfov and znear > 0, an orthographic one's xmag and ymag != 0);
// - every AnimationChannel targets a node of Scene::nodes, has finite, increasing times and finite values,
//   as many as its times, path and interpolation ask for;
// - every VertexAttribute of a Primitive (and of each of its morph targets) has `components` of 1 to 4 and
//   that many values per vertex; every morph target of a mesh's primitives is there in each (as glTF asks);
// - Node::skin is -1 or an index into Scene::skins, whose joints index Scene::nodes, with no or one inverse
//   bind matrix per joint.
// Geometry is double precision; readers convert whatever the file stores.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace symcompress {

using Triangle = std::array<std::uint32_t, 3>;

// Positions and triangles only: the input of the geometry stages (moments, symmetry, congruence).
struct TriangleMesh {
    std::vector<Eigen::Vector3d> positions;
    std::vector<Triangle> triangles;  // counter-clockwise seen from outside
};

// How a texture is sampled, as glTF's sampler holds it (its enums: 9728 NEAREST, 9729 LINEAR, 9984 to 9987 the
// mipmap filters; 10497 REPEAT, 33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT). A filter of 0 is left to the viewer.
struct TextureSampler {
    int magFilter = 0, minFilter = 0;
    int wrapS = 10497, wrapT = 10497;
    std::string name;
    bool operator==(const TextureSampler& o) const {
        return magFilter == o.magFilter && minFilter == o.minFilter && wrapS == o.wrapS && wrapT == o.wrapT &&
               name == o.name;
    }
};

// An image file as a reader found it (Texture's fields of the same names).
struct ImageFile {
    std::string uri, mimeType;
    std::vector<std::uint8_t> bytes;
    bool operator==(const ImageFile& o) const { return uri == o.uri && mimeType == o.mimeType && bytes == o.bytes; }
};

// An image used by a material with its sampler, the image kept as the bytes of the file so that writers can
// embed it unchanged. Textures of the same image share it in the output (firstTextureOfSameImage).
struct Texture {
    std::string name;
    std::string uri;                  // the image file, as the reader found or looked for it; empty when embedded
    std::string mimeType;             // "image/png", "image/jpeg", "image/webp", "image/ktx2", ... (may be empty)
    std::vector<std::uint8_t> bytes;  // empty when the image file could not be read (a warning says so)
    TextureSampler sampler;
    // Where the image is an extension's (glTF's EXT_texture_webp, KHR_texture_basisu) and the file gave a core image
    // beside it, that one: what viewers without the extension draw, so that the extension stays optional for them.
    std::optional<ImageFile> fallback;
};

// KHR_texture_transform on one use of a texture: uv' = T(offset) R(rotation) S(scale) uv, on texCoord set
// `texCoord` where that is not -1 (it then overrides the use's own set).
struct TextureTransform {
    Eigen::Vector2d offset{0, 0};
    double rotation = 0;  // radians, counter-clockwise in glTF's uv (v down)
    Eigen::Vector2d scale{1, 1};
    int texCoord = -1;
    bool operator==(const TextureTransform& o) const {
        return offset == o.offset && rotation == o.rotation && scale == o.scale && texCoord == o.texCoord;
    }
    // The transform as a matrix on (u, v, 1).
    Eigen::Matrix<double, 2, 3> matrix() const;
};

// One use of a texture by a material: glTF's textureInfo (and normalTextureInfo, occlusionTextureInfo).
struct TextureRef {
    int texture = -1;  // index into Scene::textures, -1: none
    int texCoord = 0;  // the TEXCOORD_n set it reads
    double scale = 1;  // normalTexture.scale, occlusionTexture.strength; 1 elsewhere
    std::optional<TextureTransform> transform;
    bool operator==(const TextureRef& o) const {
        return texture == o.texture && texCoord == o.texCoord && scale == o.scale && transform == o.transform;
    }
    // The texture coordinate set it reads, once its transform's override is applied.
    int texCoordSet() const { return transform && transform->texCoord >= 0 ? transform->texCoord : texCoord; }
};

// A material extension kept as the file had it (KHR_materials_clearcoat, _unlit, _pbrSpecularGlossiness, ...):
// its JSON object without its textures, which are held apart so that stages that renumber or count textures
// see them. A writer puts each texture back under its key.
struct MaterialExtension {
    std::string name;
    std::string json = "{}";
    std::vector<std::pair<std::string, TextureRef>> textures;  // key in the object, texture
    bool required = false;  // in the file's extensionsRequired: a viewer without it must not draw a fallback
    bool operator==(const MaterialExtension& o) const {
        return name == o.name && json == o.json && textures == o.textures && required == o.required;
    }
};

// X3D's Phong Material fields (colours sRGB-encoded, as X3D browsers draw them), kept when the source was X3D so
// that an X3D writer gives them back.
struct PhongMaterial {
    Eigen::Vector3d diffuseColor{0.8, 0.8, 0.8};
    Eigen::Vector3d specularColor{0, 0, 0};
    Eigen::Vector3d emissiveColor{0, 0, 0};
    double ambientIntensity = 0.2;
    double shininess = 0.2;
    double transparency = 0;
    bool operator==(const PhongMaterial& o) const {
        return diffuseColor == o.diffuseColor && specularColor == o.specularColor && emissiveColor == o.emissiveColor &&
               ambientIntensity == o.ambientIntensity && shininess == o.shininess && transparency == o.transparency;
    }
};

// glTF's metallic-roughness material, its factors linear; X3D's Phong materials are mapped onto it (diffuseColor,
// sRGB-decoded, -> baseColor, 1 - transparency -> alpha; docs/scene-model.md, "Colour spaces") and keep their
// Phong fields in `phong`; X3D 4's PhysicalMaterial fills it as it is.
struct Material {
    std::string name;
    Eigen::Vector4d baseColorFactor{1, 1, 1, 1};
    double metallicFactor = 1;
    double roughnessFactor = 1;
    Eigen::Vector3d emissiveFactor{0, 0, 0};
    enum class AlphaMode { Opaque, Mask, Blend } alphaMode = AlphaMode::Opaque;
    double alphaCutoff = 0.5;
    bool doubleSided = false;
    TextureRef baseColorTexture, metallicRoughnessTexture, normalTexture, occlusionTexture, emissiveTexture;
    std::vector<MaterialExtension> extensions;
    std::string extrasJson;  // glTF extras as read (JSON text), empty for none
    std::optional<PhongMaterial> phong;
    // KHR_materials_variants: under variant v of Scene::materialVariants, what this material draws draws
    // materials[variants[v]] instead (-1: this material itself); empty where no variant changes it. The table is
    // part of the material, so that primitives drawn alike under every variant, and only those, share one.
    std::vector<int> variants;
    bool operator==(const Material& o) const {
        return name == o.name && sameButName(o);
    }
    bool sameButName(const Material& o) const { return sameButNameAndVariants(o) && variants == o.variants; }
    bool sameButNameAndVariants(const Material& o) const {
        return extrasJson == o.extrasJson && baseColorFactor == o.baseColorFactor && metallicFactor == o.metallicFactor &&
               roughnessFactor == o.roughnessFactor && emissiveFactor == o.emissiveFactor && alphaMode == o.alphaMode &&
               alphaCutoff == o.alphaCutoff && doubleSided == o.doubleSided && baseColorTexture == o.baseColorTexture &&
               metallicRoughnessTexture == o.metallicRoughnessTexture && normalTexture == o.normalTexture &&
               occlusionTexture == o.occlusionTexture && emissiveTexture == o.emissiveTexture &&
               extensions == o.extensions && phong == o.phong;
    }
    // Every use of a texture, the core slots' and the extensions' (those without a texture too).
    std::vector<TextureRef*> textureRefs();
    std::vector<const TextureRef*> textureRefs() const;
};

// Triangles of one material with their per-vertex attributes.
// A Draco-style quantization grid: value = origin + q * range / (2^bits - 1), q in [0, 2^bits - 1]
// (draco::Encoder::SetAttributeExplicitQuantization takes origin and range as floats).
struct QuantizationGrid {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    double range = 1;
    int bits = 14;
};

// A vertex attribute that the stages carry through as it is: TANGENT (x, y, z and the handedness w),
// TEXCOORD_n and COLOR_n after the first, JOINTS_n, WEIGHTS_n, an application's _NAME; in a morph target, the
// displacements of POSITION, NORMAL, TANGENT (3 components) or another attribute. `components` values a
// vertex, as glTF's accessor held them (normalized integers as their values in [0, 1], JOINTS as indices).
struct VertexAttribute {
    std::string name;  // glTF's attribute semantic
    int components = 0;
    std::vector<double> values;
    std::size_t count() const { return components > 0 ? values.size() / std::size_t(components) : 0; }
    bool isJoints() const { return name.rfind("JOINTS_", 0) == 0; }  // skin joint indices, whole numbers
    const double* vertex(std::size_t v) const { return values.data() + v * std::size_t(components); }
    VertexAttribute withoutValues() const { return {name, components, {}}; }  // to append vertices to
    // Vertex v of `from` (an attribute of the same name and size) appended.
    void appendVertex(const VertexAttribute& from, std::size_t v) {
        values.insert(values.end(), from.vertex(v), from.vertex(v) + from.components);
    }
    bool operator==(const VertexAttribute& o) const {
        return name == o.name && components == o.components && values == o.values;
    }
};

// A glTF morph target: displaced attributes of its primitive, one value per vertex each.
using MorphTarget = std::vector<VertexAttribute>;

// What a primitive draws: triangles; line segments (glTF's LINES, line strips and loops as their segments; X3D's
// line sets; OBJ's l); or each vertex as a point (glTF's POINTS, X3D's PointSet, a PLY file of vertices only).
enum class Topology { Triangles, Lines, Points };

// A pair of vertex indices: one line segment.
using Segment = std::array<std::uint32_t, 2>;

// The X3D geometry node a primitive was read from, where the node makes its points from a few numbers (Box,
// Sphere, Cylinder, Cone, ElevationGrid, Extrusion): its XML, self-contained (USEs inlined, no DEFs). X3D output
// keeps such a primitive whole and writes the node again, far shorter than its triangles, while its triangles
// are still those the node made (`cornerHash`: trianglePositionsHash when read).
struct X3dGeometrySource {
    std::string xml;
    std::uint64_t cornerHash = 0;
};

// Lines and points are kept as they are: never tiled, classified or cut; only triangles carry the method.
struct Primitive {
    Topology topology = Topology::Triangles;
    std::vector<Eigen::Vector3d> positions;
    std::vector<Eigen::Vector3d> normals;    // empty or one per vertex
    std::vector<Eigen::Vector2d> texcoords;  // TEXCOORD_0, glTF convention (v down); empty or one per vertex
    std::vector<Eigen::Vector4d> colors;     // COLOR_0 as linear RGBA; empty or one per vertex
    std::vector<Triangle> triangles;         // Topology::Triangles only
    std::vector<Segment> lines;              // Topology::Lines only
    std::vector<VertexAttribute> attributes;  // every other attribute (VertexAttribute), sorted by name
    std::vector<MorphTarget> targets;         // glTF morph targets, in the file's order
    int material = -1;  // index into Scene::materials, -1 for the default material
    // Where positions must be quantized on a given grid (the seams of a fundamental region's copies stay
    // closed on it; fundamental_region.hpp), else nothing: a compressing writer then fits its own grid.
    std::optional<QuantizationGrid> positionGrid;
    // > 0: how far a quantizing writer may move a corner (a distance in the primitive's frame): the share of
    // the error budget that the placements drawing it leave (positionBitsFor).
    double maxPositionError = 0;
    // > 0: the diagonal that the writer's close-up bound (WriteOptions::maxRelativePositionError) is a fraction
    // of, where not the primitive's own box's: a part stored turned from the world keeps the larger of its
    // world box's and its own, so that a frame never tightens the bound.
    double closeUpDiagonal = 0;
    // The fewest COLOR_0 quantization bits, where more than the writer's (WriteOptions::colorBits): materials' base
    // colours moved into COLOR_0 (joinByBaseColor) keep their precision where 8 bits would lighten a dark one.
    int colorBits = 0;
    std::shared_ptr<const X3dGeometrySource> x3dSource;  // X3D input only (X3dGeometrySource)

    bool drawsNothing() const {
        return topology == Topology::Triangles ? triangles.empty()
               : topology == Topology::Lines   ? lines.empty()
                                               : positions.empty();
    }
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
    std::string extrasJson;       // glTF extras as read (JSON text), empty for none
    std::vector<double> weights;  // the morph targets' default weights, empty for none (or 0 each)
};

// glTF's skin: the joints that move a skinned mesh's vertices (JOINTS_n and WEIGHTS_n), with the inverse bind
// matrix of each (none: identity). A skinned mesh is drawn by its joints, not by its node's transform.
struct Skin {
    std::string name;
    std::vector<int> joints;                           // indices into Scene::nodes
    std::vector<Eigen::Matrix4d> inverseBindMatrices;  // empty or one per joint
    int skeleton = -1;                                 // the skeleton's root node, -1 when the file names none
};

// A viewpoint, as glTF holds it: it looks down its node's -z, +y up (X3D's Viewpoint has the same frame).
struct Camera {
    std::string name;
    enum class Projection { Perspective, Orthographic } projection = Projection::Perspective;
    double yfov = 0.7853981633974483;  // perspective: vertical field of view, radians
    double aspectRatio = 0;            // perspective: width / height, 0 when left to the viewer
    double xmag = 1, ymag = 1;         // orthographic: half the width and height of the view
    double znear = 0.1;
    double zfar = 0;                   // 0: infinitely far (perspective only)
};

// A punctual light, as glTF's KHR_lights_punctual holds it: directional and spot lights shine down their
// node's -z, point and spot lights from its origin.
struct Light {
    std::string name;
    enum class Type { Directional, Point, Spot } type = Type::Point;
    Eigen::Vector3d color{1, 1, 1};
    double intensity = 1;  // glTF: candela (point, spot) or lux (directional); X3D: 0 to 1, taken as is
    double range = 0;      // 0: no limit
    double innerConeAngle = 0, outerConeAngle = 0.7853981633974483;  // spot, radians
    // X3D's attenuation (constant, linear, quadratic) of a point or spot light read from X3D, so that an X3D
    // writer gives it back; glTF's lights fall off with the inverse square (0 0 1), which is the default.
    std::optional<Eigen::Vector3d> x3dAttenuation;
};

struct Node {
    std::string name;
    Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  // local, column vectors: parent * this
    int mesh = -1;                                            // index into Scene::meshes
    int camera = -1;                                          // index into Scene::cameras
    int light = -1;                                           // index into Scene::lights
    int skin = -1;                                            // index into Scene::skins, for a skinned mesh
    std::vector<double> weights;                              // morph weights replacing the mesh's, or empty
    std::vector<int> children;                                // indices into Scene::nodes
    std::string extrasJson;                                   // glTF extras as read (JSON text), empty for none
    std::string extensionsJson;  // glTF extensions passed through as read (Scene::extensionsJson), empty for none
};

// A keyframed transform of one node (glTF's animation channel with its sampler), kept as read so that a
// glTF writer gives it back. The node's own transform is its rest pose, what every other stage draws.
struct AnimationChannel {
    int node = -1;  // index into Scene::nodes
    enum class Path { Translation, Rotation, Scale, Weights } path = Path::Translation;
    int weights = 0;  // Path::Weights: the number of morph targets, the values of one key
    enum class Interpolation { Linear, Step, CubicSpline } interpolation = Interpolation::Linear;
    std::vector<double> times;   // seconds, increasing
    // Per key: 3 values (translation, scale), 4 (rotation quaternion x, y, z, w) or `weights` (morph weights);
    // cubic splines store in-tangent, value and out-tangent for each key.
    std::vector<double> values;

    std::size_t components() const {  // of one value
        return path == Path::Rotation ? 4 : path == Path::Weights ? std::size_t(std::max(weights, 0)) : 3;
    }
    std::size_t valuesPerKey() const { return components() * (interpolation == Interpolation::CubicSpline ? 3 : 1); }
};

struct Animation {
    std::string name;
    std::vector<AnimationChannel> channels;
};

// One of the variants a viewer may switch a scene's materials to (KHR_materials_variants; Material::variants).
struct MaterialVariant {
    std::string name;
    std::string extrasJson;  // glTF extras as read (JSON text), empty for none
    bool operator==(const MaterialVariant& o) const { return name == o.name && extrasJson == o.extrasJson; }
};

struct Scene {
    std::vector<Texture> textures;
    std::vector<Material> materials;
    std::vector<MaterialVariant> materialVariants;
    std::vector<Mesh> meshes;
    std::vector<Node> nodes;
    std::vector<int> roots;             // the nodes drawn, in order
    std::vector<Animation> animations;
    std::vector<Camera> cameras;
    std::vector<Light> lights;
    std::vector<Skin> skins;
    // X3D's NavigationInfo, Background, Fog and WorldInfo nodes as read (XML text), which the scene model and
    // glTF have no place for: an X3D writer gives them back.
    std::vector<std::string> x3dEnvironment;
    std::vector<std::string> warnings;  // what the reader could not carry through, one line each
    // What the file says about itself, as a JSON object (io/file_metadata.hpp): glTF's asset.extras, X3D's <head>
    // <meta> tags; where symcompress keeps its digest.
    std::string extrasJson;
    std::string copyright;        // glTF's asset.copyright; X3D's meta tag named "copyright"
    std::string name;             // glTF: the scene's name
    std::string sceneExtrasJson;  // glTF: the scene's extras (JSON text), empty for none
    std::string rootExtrasJson;   // glTF: the extras of the file's root object (JSON text), empty for none
    // glTF extensions of the file, its asset and its scene passed through as read (an extensions object as JSON
    // text, empty for none): those whose indices name only what the file's own object of them holds
    // (KHR_xmp_json_ld's packets; kPassedThroughExtensions).
    std::string extensionsJson, assetExtensionsJson, sceneExtensionsJson;
};

}  // namespace symcompress
