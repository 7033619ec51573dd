// glTF 2.0 reader (.gltf with external files or data URIs, .glb), on top of tinygltf's JSON and buffer
// loading. Accessor decoding, Draco decoding and every range check are ours: tinygltf does not check
// that accessors stay inside their buffers.
#include "gltf_reader.hpp"
#include "common/mime_type.hpp"
#include "file_metadata.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>

namespace symcompress {
namespace fs = std::filesystem;

namespace {

// How deep the node forest of a glTF file may nest: as deep as X3D's (the X3D reader's limit), so that what
// is read can be written as X3D, nested, and read back.
constexpr std::size_t kMaxNodeDepth = 256;

// The cycle `start` is on (each node's parent in `parentOf`) from parent to child: "node 0 has child 1, which has
// child 0", its first few links.
std::string cycleThrough(int start, const std::vector<int>& parentOf) {
    std::vector<int> cycle{start};  // child to parent
    for (int n = parentOf[std::size_t(start)]; n != start; n = parentOf[std::size_t(n)]) cycle.push_back(n);
    if (cycle.size() == 1) return "node " + std::to_string(start) + " is its own child";
    std::reverse(cycle.begin(), cycle.end());  // parent to child, ending with `start`
    std::rotate(cycle.begin(), cycle.end() - 1, cycle.end());
    cycle.push_back(start);
    constexpr std::size_t kLinksNamed = 6;
    std::string text = "node " + std::to_string(cycle[0]);
    for (std::size_t i = 1; i < cycle.size() && i <= kLinksNamed; ++i)
        text += std::string(i == 1 ? " has" : ", which has") + " child " + std::to_string(cycle[i]);
    return cycle.size() > kLinksNamed + 1 ? text + ", and so on round to node " + std::to_string(cycle[0]) : text;
}

// What is wrong with the node forest of `nodes` (with one parent at most each, in `parentOf`): nodes nested too deep,
// or a cycle; nothing where it is right. Walked level by level without recursion, before any code that walks the
// hierarchy recursively sees it. With one parent at most, a node no walk down from a parentless node reaches is on
// a cycle or below one, and its ancestors lead round the cycle.
std::string hierarchyProblem(const std::vector<Node>& nodes, const std::vector<int>& parentOf) {
    std::vector<char> reached(parentOf.size(), 0);
    std::vector<int> level;
    for (int n = 0; n < static_cast<int>(parentOf.size()); ++n)
        if (parentOf[std::size_t(n)] < 0) level.push_back(n);
    for (std::size_t depth = 1; !level.empty(); ++depth) {
        if (depth > kMaxNodeDepth) return "nodes nested deeper than " + std::to_string(kMaxNodeDepth) + " levels";
        std::vector<int> next;
        for (int n : level) {
            reached[std::size_t(n)] = 1;
            next.insert(next.end(), nodes[std::size_t(n)].children.begin(), nodes[std::size_t(n)].children.end());
        }
        level = std::move(next);
    }
    const auto unreached = std::find(reached.begin(), reached.end(), 0);
    if (unreached == reached.end()) return "";
    std::vector<char> seen(parentOf.size(), 0);
    int n = int(unreached - reached.begin());
    for (; !seen[std::size_t(n)]; n = parentOf[std::size_t(n)]) seen[std::size_t(n)] = 1;
    return "the node hierarchy has a cycle: " + cycleThrough(n, parentOf);
}

}  // namespace

void GltfReader::readPrimitive(const tinygltf::Primitive& source, Mesh& mesh, Scene& scene, const std::string& where) {
    const int mode = source.mode < 0 ? TINYGLTF_MODE_TRIANGLES : source.mode;
    auto draco = source.extensions.find("KHR_draco_mesh_compression");
    const bool triangles =
        mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
    if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
        ++skippedModes_["primitives of unknown mode"];
        return;
    }
    if (!triangles && draco != source.extensions.end()) {  // the extension holds triangles only
        ++skippedModes_["Draco-compressed points or lines"];
        return;
    }
    Primitive out;
    std::vector<std::uint32_t> indices;
    if (draco != source.extensions.end()) {
        decodeDracoPrimitive(source, draco->second, out, indices, where);
    } else {
        auto attribute = [&](const char* name) {
            auto found = source.attributes.find(name);
            return found == source.attributes.end() ? -1 : found->second;
        };
        if (attribute("POSITION") < 0) fail(where + ": primitive has no POSITION");
        out.positions = toVectors<Eigen::Vector3d>(readAccessor(attribute("POSITION"), 3, "POSITION"), 3);
        if (attribute("NORMAL") >= 0)
            out.normals = toVectors<Eigen::Vector3d>(readAccessor(attribute("NORMAL"), 3, "NORMAL"), 3);
        if (attribute("TEXCOORD_0") >= 0)
            out.texcoords = toVectors<Eigen::Vector2d>(readAccessor(attribute("TEXCOORD_0"), 2, "TEXCOORD_0"), 2);
        if (const int colors = attribute("COLOR_0"); colors >= 0) {
            // An index out of range is refused by readAccessor, by its name.
            const int components =
                colors < static_cast<int>(model_.accessors.size()) ? componentCount(model_.accessors[colors].type) : 3;
            if (components != 3 && components != 4) fail(where + ": COLOR_0 must be VEC3 or VEC4");
            out.colors = toColors(readAccessor(attribute("COLOR_0"), components, "COLOR_0"), components);
        }
        for (const auto& [name, accessor] : source.attributes)
            if (!isCoreAttribute(name))
                if (const int components = vertexAttributeComponents(accessor, name, where); components > 0)
                    out.attributes.push_back({name, components, readAccessor(accessor, components, name.c_str())});
        if (source.indices >= 0) {
            indices = readIndices(source.indices);
        } else {
            indices.resize(out.positions.size());
            for (std::uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
        }
    }
    const std::size_t vertexCount = out.positions.size();
    for (const Eigen::Vector3d& p : out.positions)
        if (!p.allFinite()) fail(where + ": POSITION contains NaN or infinite values");
    // A broken attribute is dropped rather than the whole file refused: the geometry is still right.
    auto dropIfNotFinite = [&](auto& attribute, const char* name) {
        for (const auto& value : attribute)
            if (!value.allFinite()) {
                warnAbout(std::string(name) + " with NaN or infinite values dropped (" + where + ")");
                attribute.clear();
                return;
            }
    };
    dropIfNotFinite(out.normals, "NORMAL");
    dropIfNotFinite(out.texcoords, "TEXCOORD_0");
    dropIfNotFinite(out.colors, "COLOR_0");
    auto finite = [](const VertexAttribute& attribute) {
        return std::all_of(attribute.values.begin(), attribute.values.end(), [](double v) { return std::isfinite(v); });
    };
    for (auto attribute = out.attributes.begin(); attribute != out.attributes.end();)
        if (finite(*attribute)) {
            ++attribute;
        } else {
            warnAbout(attribute->name + " with NaN or infinite values dropped (" + where + ")");
            attribute = out.attributes.erase(attribute);
        }
    auto sameCount = [&](auto& attribute, const char* name) {
        if (!attribute.empty() && attribute.size() != vertexCount)
            fail(where + ": " + name + " has " + std::to_string(attribute.size()) + " elements for " +
                 std::to_string(vertexCount) + " positions");
    };
    sameCount(out.normals, "NORMAL");
    sameCount(out.texcoords, "TEXCOORD_0");
    sameCount(out.colors, "COLOR_0");
    for (const VertexAttribute& attribute : out.attributes)
        if (attribute.count() != vertexCount)
            fail(where + ": " + attribute.name + " has " + std::to_string(attribute.count()) + " elements for " +
                 std::to_string(vertexCount) + " positions");
    out.targets = readMorphTargets(source, vertexCount, where);
    for (std::uint32_t index : indices)
        if (index >= vertexCount)
            fail(where + ": index " + std::to_string(index) + " out of range (" + std::to_string(vertexCount) +
                 " vertices)");
    if (triangles) {
        out.triangles = trianglesFromIndices(indices, mode);
    } else if (mode == TINYGLTF_MODE_POINTS) {
        out.topology = Topology::Points;
        // Each index draws its vertex: the vertices in that order (a vertex no index names draws nothing).
        if (source.indices >= 0) keepVertices(out, indices);
    } else {
        out.topology = Topology::Lines;
        out.lines = segmentsFromIndices(indices, mode);
    }
    const bool material = source.material >= 0 && source.material < static_cast<int>(model_.materials.size());
    if (source.material != -1 && !material)  // only its look is lost
        warnAbout(referenceProblem(where, "material", source.material, model_.materials.size()) +
                  ": drawn with the default material");
    out.material = materialUnderVariants(material ? source.material : -1, source.extensions_json_string, scene, where);
    mesh.primitives.push_back(std::move(out));
}

namespace {

// Whether `name` is one of glTF's attribute semantics beyond the core ones (TANGENT, TEXCOORD_n, COLOR_n,
// JOINTS_n, WEIGHTS_n) or an application's (_NAME); anything else would make the file written invalid.
bool isGltfAttributeName(const std::string& name) {
    if (name.size() > 1 && name[0] == '_') return true;
    if (name == "TANGENT") return true;
    for (const char* prefix : {"TEXCOORD_", "COLOR_", "JOINTS_", "WEIGHTS_"}) {
        const std::string start(prefix);
        if (name.size() > start.size() && name.compare(0, start.size(), start) == 0 &&
            name.find_first_not_of("0123456789", start.size()) == std::string::npos)
            return true;
    }
    return false;
}

}  // namespace

int GltfReader::vertexAttributeComponents(int accessor, const std::string& name, const std::string& where) {
    if (!isGltfAttributeName(name) && !isCoreAttribute(name)) {
        warnAbout("attribute " + name + " not carried through: glTF has no such attribute (" + where + ")");
        return 0;
    }
    if (accessor < 0 || accessor >= static_cast<int>(model_.accessors.size()))
        fail(where + ": " + name + ": accessor " + std::to_string(accessor) + " does not exist");
    const int components = componentCount(model_.accessors[std::size_t(accessor)].type);
    if (components >= 1 && components <= 4) return components;
    warnAbout("attribute " + name + " of a matrix or unknown type not carried through (" + where + ")");
    return 0;
}

// Morph targets as read; when one has an attribute of another count than the base's vertices (a Draco
// primitive whose encoder merged vertices) or with NaN or infinite values, all are left out with a warning
// (a primitive's targets are numbered together, and match its mesh's weights).
std::vector<MorphTarget> GltfReader::readMorphTargets(const tinygltf::Primitive& source, std::size_t vertices,
                                                      const std::string& where) {
    std::vector<MorphTarget> targets;
    for (std::size_t t = 0; t < source.targets.size(); ++t) {
        MorphTarget target;
        for (const auto& [name, accessor] : source.targets[t]) {
            const std::string what = where + " morph target " + std::to_string(t) + " " + name;
            const int components = vertexAttributeComponents(accessor, name, what);
            if (components == 0) continue;
            VertexAttribute attribute{name, components, readAccessor(accessor, components, what.c_str())};
            const bool finite = std::all_of(attribute.values.begin(), attribute.values.end(),
                                            [](double v) { return std::isfinite(v); });
            if (attribute.count() != vertices || !finite) {
                warnAbout("morph targets left out (" + where + "): " + name + " of target " + std::to_string(t) +
                          (finite ? " has " + std::to_string(attribute.count()) + " elements for " +
                                        std::to_string(vertices) + " vertices"
                                  : " has NaN or infinite values"));
                return {};
            }
            target.push_back(std::move(attribute));
        }
        targets.push_back(std::move(target));
    }
    return targets;
}

Eigen::Matrix4d GltfReader::nodeTransform(const tinygltf::Node& node) const {
    Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();
    if (node.matrix.size() == 16) {
        for (int i = 0; i < 16; ++i) transform(i % 4, i / 4) = node.matrix[i];  // column-major
    } else {
        Eigen::Affine3d trs = Eigen::Affine3d::Identity();
        if (node.translation.size() == 3)
            trs.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
        if (node.rotation.size() == 4)
            trs.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2])
                           .normalized());
        if (node.scale.size() == 3) trs.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
        transform = trs.matrix();
    }
    if (!transform.allFinite()) fail("node '" + node.name + "': transform contains NaN or infinite values");
    return transform;
}

// glTF asks every primitive of a mesh for the same number of morph targets, and as many weights: a mesh that
// breaks it keeps none (with a warning), which its nodes' weights then lose too.
void GltfReader::keepConsistentMorphTargets(Mesh& mesh, const std::string& where) {
    const std::size_t targets = mesh.primitives.empty() ? 0 : mesh.primitives.front().targets.size();
    bool consistent = mesh.weights.empty() || mesh.weights.size() == targets;
    for (const Primitive& primitive : mesh.primitives) consistent = consistent && primitive.targets.size() == targets;
    for (double weight : mesh.weights) consistent = consistent && std::isfinite(weight);
    if (consistent) return;
    warnAbout(where + ": morph targets ignored: its primitives have different numbers of them, or of weights");
    for (Primitive& primitive : mesh.primitives) primitive.targets.clear();
    mesh.weights.clear();
}

// Skins with their joints and inverse bind matrices; a broken one is left out with a warning (its meshes are
// then drawn by their nodes, in the bind pose), as are node weights that do not match their mesh.
void GltfReader::readSkins(Scene& scene) {
    std::vector<int> skinIndex(model_.skins.size(), -1);
    for (std::size_t k = 0; k < model_.skins.size(); ++k) {
        const tinygltf::Skin& source = model_.skins[k];
        const std::string where = "skin " + std::to_string(k);
        Skin skin;
        skin.name = source.name;
        skin.joints = source.joints;
        skin.skeleton = source.skeleton;
        auto isNode = [&](int n) { return n >= 0 && n < static_cast<int>(model_.nodes.size()); };
        const auto badJoint = std::find_if_not(skin.joints.begin(), skin.joints.end(), isNode);
        const std::string problem =
            skin.joints.empty()             ? where + " has no joints"
            : badJoint != skin.joints.end() ? referenceProblem(where, "node", *badJoint, model_.nodes.size(), "joints")
            : skin.skeleton != -1 && !isNode(skin.skeleton)
                ? referenceProblem(where, "node", skin.skeleton, model_.nodes.size(), "skeleton")
            : source.inverseBindMatrices < -1 || source.inverseBindMatrices >= static_cast<int>(model_.accessors.size())
                ? referenceProblem(where, "accessor", source.inverseBindMatrices, model_.accessors.size(),
                                   "inverseBindMatrices")
                : "";
        if (!problem.empty()) {
            warnAbout(problem + ": the skin ignored");
            continue;
        }
        if (source.inverseBindMatrices >= 0) {
            const std::vector<double> values = readAccessor(source.inverseBindMatrices, 16, "inverseBindMatrices");
            if (values.size() < 16 * skin.joints.size() ||
                !std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); })) {
                warnAbout(where + " ignored: fewer inverse bind matrices than joints, or NaN or infinite ones");
                continue;
            }
            for (std::size_t j = 0; j < skin.joints.size(); ++j)
                skin.inverseBindMatrices.push_back(Eigen::Map<const Eigen::Matrix4d>(&values[16 * j]));
        }
        skinIndex[k] = int(scene.skins.size());
        scene.skins.push_back(std::move(skin));
    }
    for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
        Node& node = scene.nodes[n];
        if (node.skin < -1 || node.skin >= static_cast<int>(skinIndex.size()))
            warnAbout(referenceProblem("node " + std::to_string(n), "skin", node.skin, skinIndex.size()) +
                      ": the skin ignored");
        node.skin = node.skin >= 0 && node.skin < static_cast<int>(skinIndex.size()) ? skinIndex[node.skin] : -1;
        if (node.skin >= 0 && node.mesh < 0) {  // glTF: a skin needs the node's mesh
            warnAbout("node " + std::to_string(n) + ": a skin without a mesh ignored");
            node.skin = -1;
        }
        const std::size_t targets = node.mesh < 0 || scene.meshes[std::size_t(node.mesh)].primitives.empty()
                                        ? 0
                                        : scene.meshes[std::size_t(node.mesh)].primitives.front().targets.size();
        if (!node.weights.empty() &&
            (node.weights.size() != targets ||
             !std::all_of(node.weights.begin(), node.weights.end(), [](double v) { return std::isfinite(v); }))) {
            warnAbout("node " + std::to_string(n) + ": morph weights that do not match its mesh's targets ignored");
            node.weights.clear();
        }
    }
}

// Node transform and morph weight channels are kept; a channel the scene model cannot hold (a target other
// than a node) or a broken one is left out with a warning.
void GltfReader::readAnimations(Scene& scene) {
    for (std::size_t a = 0; a < model_.animations.size(); ++a) {
        const tinygltf::Animation& source = model_.animations[a];
        Animation animation;
        animation.name = source.name;
        for (std::size_t c = 0; c < source.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = source.channels[c];
            const std::string where = "animation " + std::to_string(a) + " channel " + std::to_string(c);
            AnimationChannel out;
            out.node = channel.target_node;
            // The file's own nodes (the scene has the GPU instances' after them).
            if (out.node < 0 || out.node >= static_cast<int>(model_.nodes.size())) {
                warnAbout(out.node < 0 ? where + " ignored: it targets no node"
                                       : referenceProblem(where, "node", out.node, model_.nodes.size(), "target") +
                                             ": the channel ignored");
                continue;
            }
            if (channel.target_path == "weights") {
                out.path = AnimationChannel::Path::Weights;
                const int mesh = scene.nodes[std::size_t(out.node)].mesh;
                out.weights = mesh < 0 || scene.meshes[std::size_t(mesh)].primitives.empty()
                                  ? 0
                                  : int(scene.meshes[std::size_t(mesh)].primitives.front().targets.size());
                if (out.weights == 0) {
                    warnAbout(where + " ignored: it animates the morph weights of a node without morph targets");
                    continue;
                }
            } else if (channel.target_path == "translation")
                out.path = AnimationChannel::Path::Translation;
            else if (channel.target_path == "rotation")
                out.path = AnimationChannel::Path::Rotation;
            else if (channel.target_path == "scale")
                out.path = AnimationChannel::Path::Scale;
            else {
                warnAbout(where + " ignored: unknown path '" + channel.target_path + "'");
                continue;
            }
            if (channel.sampler < 0 || channel.sampler >= static_cast<int>(source.samplers.size())) {
                const std::size_t samplers = source.samplers.size();
                warnAbout(where + " ignored: it refers to sampler " + std::to_string(channel.sampler) +
                          ", but animation " + std::to_string(a) + " has " + std::to_string(samplers) +
                          (samplers == 1 ? " sampler" : " samplers"));
                continue;
            }
            const tinygltf::AnimationSampler& sampler = source.samplers[channel.sampler];
            const std::string samplerWhere =
                "animation " + std::to_string(a) + " sampler " + std::to_string(channel.sampler);
            auto isAccessor = [&](int accessor) {
                return accessor >= 0 && accessor < static_cast<int>(model_.accessors.size());
            };
            if (!isAccessor(sampler.input) || !isAccessor(sampler.output)) {
                const bool input = !isAccessor(sampler.input);
                warnAbout(referenceProblem(samplerWhere, "accessor", input ? sampler.input : sampler.output,
                                           model_.accessors.size(), input ? "input" : "output") +
                          ": channel " + std::to_string(c) + " ignored");
                continue;
            }
            if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR")
                out.interpolation = AnimationChannel::Interpolation::Linear;
            else if (sampler.interpolation == "STEP")
                out.interpolation = AnimationChannel::Interpolation::Step;
            else if (sampler.interpolation == "CUBICSPLINE")
                out.interpolation = AnimationChannel::Interpolation::CubicSpline;
            else {
                warnAbout(where + " ignored: unknown interpolation '" + sampler.interpolation + "'");
                continue;
            }
            out.times = readAccessor(sampler.input, 1, "animation input");
            // Morph weights are scalars, one per target a key.
            const bool weights = out.path == AnimationChannel::Path::Weights;
            out.values = readAccessor(sampler.output, weights ? 1 : int(out.components()), "animation output");
            if (const std::string problem = animationChannelProblem(out, scene.nodes.size()); !problem.empty())
                warnAbout(where + " ignored: " + problem);
            else
                animation.channels.push_back(std::move(out));
        }
        for (const AnimationChannel& channel : animation.channels) {
            // Written back, a node's transform is a rotation and a scale with the mirror on x: the same
            // rest pose, but not the same parts for a channel to replace when the file put it elsewhere.
            const std::vector<double>& scale = model_.nodes[std::size_t(channel.node)].scale;
            if (scale.size() == 3 && (scale[1] < 0 || scale[2] < 0))
                warnAbout("node " + std::to_string(channel.node) +
                          " is animated with a negative scale on y or z: its " +
                          "animation may play differently once written back");
        }
        if (!animation.channels.empty()) scene.animations.push_back(std::move(animation));
    }
}

// glTF's cameras and KHR_lights_punctual lights, with the nodes that carry them. One that breaks the
// rules of scene.hpp (a yfov of 0, an unknown light type) is left out with a warning.
void GltfReader::readCamerasAndLights(Scene& scene) {
    std::vector<int> cameraIndex(model_.cameras.size(), -1), lightIndex(model_.lights.size(), -1);
    // Adds `item` to `into`, its index to `indexOf[i]`, or leaves it out with a warning naming `problem`.
    auto keep = [&](const char* what, std::size_t i, const std::string& problem, auto item, auto& into,
                    std::vector<int>& indexOf) {
        if (!problem.empty()) {
            warnAbout(std::string(what) + " " + std::to_string(i) + " ignored: " + problem);
            return;
        }
        indexOf[i] = int(into.size());
        into.push_back(std::move(item));
    };
    for (std::size_t c = 0; c < model_.cameras.size(); ++c) {
        const tinygltf::Camera& source = model_.cameras[c];
        Camera camera;
        camera.name = source.name;
        if (source.type == "orthographic") {
            camera.projection = Camera::Projection::Orthographic;
            camera.xmag = source.orthographic.xmag;
            camera.ymag = source.orthographic.ymag;
            camera.znear = source.orthographic.znear;
            camera.zfar = source.orthographic.zfar;
        } else {
            camera.yfov = source.perspective.yfov;
            camera.aspectRatio = source.perspective.aspectRatio;
            camera.znear = source.perspective.znear;
            camera.zfar = source.perspective.zfar;
        }
        keep("camera", c,
             source.type == "orthographic" || source.type == "perspective" ? cameraProblem(camera)
                                                                           : "unknown type '" + source.type + "'",
             camera, scene.cameras, cameraIndex);
    }
    for (std::size_t l = 0; l < model_.lights.size(); ++l) {
        const tinygltf::Light& source = model_.lights[l];
        Light light;
        light.name = source.name;
        light.type = source.type == "directional" ? Light::Type::Directional
                     : source.type == "spot"      ? Light::Type::Spot
                                                  : Light::Type::Point;
        if (source.color.size() == 3) light.color = {source.color[0], source.color[1], source.color[2]};
        light.intensity = source.intensity;
        light.range = source.range;
        light.innerConeAngle = source.spot.innerConeAngle;
        light.outerConeAngle = source.spot.outerConeAngle;
        const bool known = source.type == "directional" || source.type == "spot" || source.type == "point";
        keep("light", l,
             !known                                              ? "unknown type '" + source.type + "'"
             : !source.color.empty() && source.color.size() != 3 ? "a colour needs 3 values"
                                                                 : lightProblem(light),
             light, scene.lights, lightIndex);
    }
    for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
        const tinygltf::Node& source = model_.nodes[n];
        if (source.camera >= 0 && std::size_t(source.camera) < cameraIndex.size())
            scene.nodes[n].camera = cameraIndex[source.camera];
        else if (source.camera != -1)
            warnAbout(referenceProblem("node " + std::to_string(n), "camera", source.camera, cameraIndex.size()) +
                      ": the camera ignored");
        const auto extension = source.extensions.find("KHR_lights_punctual");
        if (extension == source.extensions.end()) continue;
        const int light = indexIn(member(extension->second, "light"));
        if (light >= 0 && std::size_t(light) < lightIndex.size())
            scene.nodes[n].light = lightIndex[std::size_t(light)];
        else
            warnAbout("node " + std::to_string(n) +
                      ": KHR_lights_punctual light index missing or out of range, ignored");
    }
}

namespace {

// The names symcompress keeps for a batch's instances (extras {"instanceNames": [...]}, one string per
// instance, or one string for every instance), taken out of the batch node's extras; none where the extras
// hold no such string or list of `count` strings.
std::vector<std::string> takeInstanceNames(Node& batch, std::size_t count) {
    nlohmann::json extras = nlohmann::json::parse(batch.extrasJson, nullptr, false);
    if (!extras.is_object() || !extras.contains("instanceNames")) return {};
    const nlohmann::json& list = extras["instanceNames"];
    std::vector<std::string> names;
    if (list.is_string())
        names.assign(count, list.get<std::string>());
    else if (list.is_array() && list.size() == count &&
             std::all_of(list.begin(), list.end(), [](const nlohmann::json& name) { return name.is_string(); }))
        names = list.get<std::vector<std::string>>();
    else
        return {};
    extras.erase("instanceNames");
    batch.extrasJson = extras.empty() ? std::string() : extras.dump();
    return names;
}

}  // namespace

// EXT_mesh_gpu_instancing (gltfpack -mi, glTF-Transform instance): each instance of a node's mesh becomes
// a child node of its own with the instance's translation, rotation and scale, which apply before the
// node's transform, as the extension says. The new nodes come after the file's, whose indices stay.
void GltfReader::expandGpuInstances(Scene& scene) {
    for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
        const auto found = model_.nodes[n].extensions.find("EXT_mesh_gpu_instancing");
        if (found == model_.nodes[n].extensions.end() || scene.nodes[n].mesh < 0) continue;
        const tinygltf::Value& attributes = member(found->second, "attributes");
        const std::string where = "node " + std::to_string(n) + " (EXT_mesh_gpu_instancing)";
        std::map<std::string, std::vector<double>> values;
        for (const std::string& name : attributes.Keys()) {
            const int components = name == "ROTATION" ? 4 : 3;
            if (name != "TRANSLATION" && name != "ROTATION" && name != "SCALE") {
                warnAbout("instance attribute " + name + " not carried through");
                continue;
            }
            if (!attributes.Get(name).IsNumber()) fail(where + ": " + name + " is not an accessor index");
            values[name] = readAccessor(indexIn(attributes.Get(name)), components, name.c_str());
        }
        std::size_t count = 0;
        for (const auto& [name, list] : values) count = std::max(count, list.size() / (name == "ROTATION" ? 4 : 3));
        for (const auto& [name, list] : values)
            if (list.size() / (name == "ROTATION" ? 4 : 3) != count) fail(where + ": attributes of different counts");
        auto component = [&](const char* name, std::size_t i, int c, double fallback) {
            const auto list = values.find(name);
            return list == values.end()
                       ? fallback
                       : list->second[i * (std::strcmp(name, "ROTATION") == 0 ? 4 : 3) + std::size_t(c)];
        };
        const std::vector<std::string> names = takeInstanceNames(scene.nodes[n], count);
        for (std::size_t i = 0; i < count; ++i) {
            Eigen::Affine3d trs = Eigen::Affine3d::Identity();
            trs.translate(Eigen::Vector3d(component("TRANSLATION", i, 0, 0), component("TRANSLATION", i, 1, 0),
                                          component("TRANSLATION", i, 2, 0)));
            const Eigen::Quaterniond rotation(component("ROTATION", i, 3, 1), component("ROTATION", i, 0, 0),
                                              component("ROTATION", i, 1, 0), component("ROTATION", i, 2, 0));
            if (!(rotation.norm() > 0)) fail(where + ": instance " + std::to_string(i) + " has a rotation of length 0");
            trs.rotate(rotation.normalized());
            trs.scale(
                Eigen::Vector3d(component("SCALE", i, 0, 1), component("SCALE", i, 1, 1), component("SCALE", i, 2, 1)));
            if (!trs.matrix().allFinite())
                fail(where + ": instance " + std::to_string(i) + " has NaN or infinite values");
            Node instance;
            if (!names.empty()) instance.name = names[i];
            instance.transform = trs.matrix();
            instance.mesh = scene.nodes[n].mesh;
            scene.nodes[n].children.push_back(int(scene.nodes.size()));
            scene.nodes.push_back(std::move(instance));
        }
        scene.nodes[n].mesh = -1;
    }
}

Scene GltfReader::read() {
    Scene scene;
    readMaterials(scene);
    readMaterialVariants(scene);
    for (std::size_t m = 0; m < model_.meshes.size(); ++m) {
        Mesh mesh;
        mesh.name = model_.meshes[m].name;
        mesh.extrasJson = extrasOf(model_.meshes[m].extras_json_string);
        if (!passedThroughExtensions(model_.meshes[m].extensions_json_string).empty())
            warnAbout("mesh " + std::to_string(m) +
                      ": its KHR_xmp_json_ld metadata not kept (meshes are rebuilt from their tiles)");
        for (std::size_t p = 0; p < model_.meshes[m].primitives.size(); ++p) {
            const std::string where = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
            readPrimitive(model_.meshes[m].primitives[p], mesh, scene, where);
            if (!extrasOf(model_.meshes[m].primitives[p].extras_json_string).empty()) ++primitivesWithExtras_;
        }
        mesh.weights = model_.meshes[m].weights;
        keepConsistentMorphTargets(mesh, "mesh " + std::to_string(m));
        scene.meshes.push_back(std::move(mesh));
    }
    std::vector<int> parentOf(model_.nodes.size(), -1);  // -1: none
    for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
        const tinygltf::Node& source = model_.nodes[n];
        const std::string where = "node " + std::to_string(n);
        Node node;
        node.name = source.name;
        node.extrasJson = extrasOf(source.extras_json_string);
        node.extensionsJson = passedThroughExtensions(source.extensions_json_string);
        node.transform = nodeTransform(source);
        if (source.matrix.size() != 16 && source.rotation.size() == 4 &&
            std::all_of(source.rotation.begin(), source.rotation.end(), [](double v) { return v == 0; }))
            warnAbout(where + ": a rotation of (0, 0, 0, 0), which is no rotation glTF allows, read as none");
        // Indices in range: refuseBrokenStructure checked them before tinygltf parsed the file.
        node.mesh = source.mesh >= 0 && source.mesh < static_cast<int>(scene.meshes.size()) ? source.mesh : -1;
        for (int child : source.children) {
            if (child < 0 || child >= static_cast<int>(model_.nodes.size()))
                fail(referenceProblem(where, "node", child, model_.nodes.size(), "children"));
            if (parentOf[child] == int(n)) fail(where + " lists node " + std::to_string(child) + " as its child twice");
            if (parentOf[child] >= 0)
                fail("node " + std::to_string(child) + " is a child of two nodes, " + std::to_string(parentOf[child]) +
                     " and " + std::to_string(n) + ": glTF's nodes form trees, with one parent at most");
            parentOf[child] = int(n);
            node.children.push_back(child);
        }
        node.skin = source.skin;  // checked by readSkins
        node.weights = source.weights;
        scene.nodes.push_back(std::move(node));
    }
    if (const std::string problem = hierarchyProblem(scene.nodes, parentOf); !problem.empty()) fail(problem);
    readCamerasAndLights(scene);
    expandGpuInstances(scene);
    scene.rootExtrasJson = extrasOf(model_.extras_json_string);
    const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (sceneIndex < static_cast<int>(model_.scenes.size())) {
        scene.name = model_.scenes[sceneIndex].name;
        scene.sceneExtrasJson = extrasOf(model_.scenes[sceneIndex].extras_json_string);
        scene.sceneExtensionsJson = passedThroughExtensions(model_.scenes[sceneIndex].extensions_json_string);
        const std::string where = "scene " + std::to_string(sceneIndex);
        std::vector<char> listed(model_.nodes.size(), 0);
        for (int root : model_.scenes[sceneIndex].nodes) {
            if (root < 0 || root >= static_cast<int>(model_.nodes.size()))
                fail(referenceProblem(where, "node", root, model_.nodes.size()));
            if (parentOf[root] >= 0)  // glTF: a scene's nodes are roots
                fail(where + " lists node " + std::to_string(root) + " as a root, but it is a child of node " +
                     std::to_string(parentOf[root]));
            // glTF: a scene's nodes are unique (a root drawn twice left the X3D writer's DEFs inconsistent).
            if (listed[root]++) fail(where + " lists node " + std::to_string(root) + " as a root twice");
            scene.roots.push_back(root);
        }
    } else {
        // No scene: every node of the file without a parent is drawn (the GPU instances' have theirs).
        for (int n = 0; n < static_cast<int>(parentOf.size()); ++n)
            if (parentOf[n] < 0) scene.roots.push_back(n);
    }
    if (model_.scenes.size() > 1)
        warnAbout(std::to_string(model_.scenes.size() - 1) + " scenes besides the default one ignored");
    readSkins(scene);
    readAnimations(scene);
    for (const auto& [mode, count] : skippedModes_) warnAbout(std::to_string(count) + " " + mode + " skipped");
    if (primitivesWithExtras_ > 0)
        warnAbout("the extras of " + std::to_string(primitivesWithExtras_) +
                  " primitives not kept (primitives are cut into tiles and joined)");
    for (const std::string& warning : warnings_) scene.warnings.push_back(file_.filename().string() + ": " + warning);
    return scene;
}

Scene readGltf(const fs::path& file) {
    const tinygltf::Model model = loadGltfModel(file);
    Scene scene = GltfReader(file, model).read();
    scene.extrasJson = model.asset.extras_json_string;
    scene.copyright = model.asset.copyright;
    scene.extensionsJson = passedThroughExtensions(model.extensions_json_string);
    scene.assetExtensionsJson = passedThroughExtensions(model.asset.extensions_json_string);
    std::set<std::string> kept;  // on a material that was read
    for (const Material& material : scene.materials)
        for (const MaterialExtension& extension : material.extensions) kept.insert(extension.name);
    for (const std::string& used : model.extensionsUsed)
        if (!readExtension(used) && !kept.count(used))
            scene.warnings.push_back(file.filename().string() + ": extension " + used + " ignored");
    return scene;
}

}  // namespace symcompress
