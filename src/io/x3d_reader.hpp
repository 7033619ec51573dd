// The X3D reader's parts (x3d_reader.cpp: the document, the scene graph and its fields; x3d_scene_nodes.cpp:
// animations, viewpoints, lights, the environment; x3d_appearance.cpp: materials and textures;
// x3d_geometry.cpp: geometry nodes) and what they share.
#pragma once

#include "common/image_alpha.hpp"
#include "symcompress/io.hpp"
#include "x3d_faces.hpp"
#include "x3d_fields.hpp"

#include <Eigen/Geometry>

#include <filesystem>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace symcompress {

// An SFRotation (axis x y z, angle) as an angle-axis; the identity where it has fewer than 4 numbers.
Eigen::AngleAxisd rotationField(const std::vector<double>& values);

// A line or point set's Coordinate points and Color (or ColorRGBA) colours, as numbers.
struct X3dPointsAndColors {
    std::vector<double> points, colors;
    int colorComponents = 3;
    std::size_t pointCount() const { return points.size() / 3; }
    std::size_t colorCount() const { return colors.size() / std::size_t(colorComponents); }
};

class X3dReader {
public:
    X3dReader(const std::filesystem::path& file, Scene& scene, std::set<std::filesystem::path>& inlineStack)
        : file_(file), scene_(scene), inlineStack_(inlineStack) {}

    // Reads the file's Scene element into new nodes; returns the root nodes.
    std::vector<int> read();

private:
    [[noreturn]] void fail(const pugi::xml_node& node, const std::string& problem) const {
        throw FileError(file_,
                        "<" + std::string(node.name()) +
                            (node.attribute("DEF") ? " DEF='" + std::string(node.attribute("DEF").value()) + "'" : "") +
                            ">: " + problem);
    }
    pugi::xml_node resolve(const pugi::xml_node& node) const;
    std::vector<double> numbers(const pugi::xml_node& node, const char* field) const;
    std::vector<std::int64_t> integers(const pugi::xml_node& node, const char* field) const;
    Eigen::Vector2d vector2(const pugi::xml_node& node, const char* field, const Eigen::Vector2d& fallback) const;
    Eigen::Vector3d vector3(const pugi::xml_node& node, const char* field, const Eigen::Vector3d& fallback) const;
    double scalar(const pugi::xml_node& node, const char* field, double fallback) const;
    bool boolean(const pugi::xml_node& node, const char* field, bool fallback) const;
    Eigen::Matrix4d transformOf(const pugi::xml_node& node) const;

    void readChildren(const pugi::xml_node& parent, std::vector<int>& into, int depth);
    int readNode(const pugi::xml_node& node, int depth);
    int readShape(const pugi::xml_node& shape);
    // `texcoordMappings`: the mapping of each texture coordinate set of the shape's geometry (x3d_geometry.cpp),
    // which the X3D 4 materials' *TextureMapping fields name. `geometry`: the primitive read, whose lines or points
    // X3D draws unlit (unlitMaterial).
    int readMaterial(const pugi::xml_node& shape, const std::vector<std::string>& texcoordMappings,
                     const Primitive& geometry);
    // The Appearance's TextureTransform baked into the texture coordinates it applies to; whether it changed them.
    bool applyTextureTransform(const pugi::xml_node& shape, const std::vector<std::string>& texcoordMappings,
                               Primitive& primitive);
    // The material of an Appearance as lines and points draw it: unlit, in the colour the browser gives them.
    Material unlitMaterial(const Material& read, bool physical, bool colored) const;
    void readMaterialTextures(const pugi::xml_node& node, Material& material,
                              const std::vector<std::string>& texcoordMappings);
    int readTexture(const pugi::xml_node& appearance);
    int readTextureNode(const pugi::xml_node& node, const std::string& where);  // -1 (and a note) if not an image
    TextureSampler readSampler(const pugi::xml_node& texture);
    bool knownUse(const pugi::xml_node& node, const std::string& where);        // a USE that names no DEF: a note
    int addTexture(int& index, Texture texture);  // sets `index` (the ImageTexture's) and returns it
    bool readGeometry(const pugi::xml_node& geometry, Primitive& out, std::vector<std::string>& texcoordMappings);
    // The face sets, triangle, strip, fan and quad sets, ElevationGrid and Extrusion (kFaceSets): their faces, and
    // the attributes of their corners.
    void readFaceSet(const pugi::xml_node& geometry, Primitive& out, std::vector<std::string>& texcoordMappings);
    // The faces of a face, triangle, strip, fan or quad set, over its Coordinate's `pointCount` points.
    std::vector<x3d::Face> listedFaces(const pugi::xml_node& geometry, std::size_t pointCount);
    // An ElevationGrid's or Extrusion's points and faces, made from its fields.
    x3d::Faces madeFaces(const pugi::xml_node& geometry);
    // An MFVec2f field's points (Geometry2D).
    std::vector<Eigen::Vector2d> points2D(const pugi::xml_node& geometry, const char* field) const;
    // A geometry node's XML as a node of its own: every USE in it replaced by what it names, without DEFs.
    std::string selfContainedXml(const pugi::xml_node& geometry) const;
    // The first child of `geometry` of one of `types`, its DEF known and a USE resolved; none: a null node.
    pugi::xml_node geometryChild(const pugi::xml_node& geometry, std::initializer_list<const char*> types);
    // IndexedLineSet and LineSet (their polylines as segments), PointSet (every point drawn); false where the node
    // has no coordinates. Bad indices and counts leave out what they name, with a note.
    bool readLineSet(const pugi::xml_node& geometry, Primitive& out, bool indexed);
    bool readPointSet(const pugi::xml_node& geometry, Primitive& out);
    // The points and colours of a line or point set (values beyond a whole point or colour left out, with a
    // note); false where it has no Coordinate.
    bool readPointsAndColors(const pugi::xml_node& geometry, X3dPointsAndColors& out);
    // A note about `node` of the file (a warning once the file is read).
    void noteAbout(const pugi::xml_node& node, const std::string& problem);
    // `material`, or the material that differs from it in its double-sidedness alone (found or added).
    int withSidedness(int material, bool doubleSided);
    // A shape's Color values as glTF's COLOR_0, once its material is known (docs/scene-model.md, "Colour spaces").
    void vertexColorsAsGltf(Primitive& primitive);
    void readInline(const pugi::xml_node& node, std::vector<int>& into);
    // Every ProtoInstance replaced by what it stands for (x3d_prototypes.hpp), before the scene is read.
    void expandPrototypes();
    void readAnimations();
    int readViewpoint(const pugi::xml_node& viewpoint);
    int readLight(const pugi::xml_node& light, int depth);
    void keepEnvironment(const pugi::xml_node& node);
    int addPlacedNode(const pugi::xml_node& source, const Eigen::Affine3d& placement, int camera, int light);

    std::filesystem::path file_;
    Scene& scene_;
    std::set<std::filesystem::path>& inlineStack_;
    pugi::xml_document document_;
    std::map<std::string, pugi::xml_node> definitions_;
    std::map<std::string, std::vector<int>> nodesOfTransform_;  // a DEF'd Transform's scene nodes (one per USE)
    std::map<const void*, int> meshOfShape_, textureOfNode_;
    // An Appearance's material for surfaces (0), and for lines and points, unlit (1; 2 with vertex colours); on
    // geometry with translucent vertex colours or not (X3D's alpha mode AUTO blends those).
    std::map<std::tuple<const void*, int, bool>, int> materialOfAppearance_;
    TranslucentTextures translucentTexture_{scene_.textures};
    std::set<int> physicalMaterials_;  // materials read from a PhysicalMaterial (vertexColorsAsGltf)
    std::set<int> usedMaterials_;      // materials a shape draws (withSidedness)
    std::map<std::string, int> skippedGeometry_;
    std::map<std::string, int> notKept_;  // other nodes with nothing to carry them in the scene model
    std::set<std::string> useStack_;
    std::set<std::string> notes_;
    std::size_t degenerateFaces_ = 0;  // faces with fewer than 3 corners, or cut by triangulatePolygon and of no area
};

}  // namespace symcompress
