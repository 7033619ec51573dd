#include "symcompress/scene_ops.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>

namespace symcompress {

namespace {

template <typename Vector>
bool allFinite(const std::vector<Vector>& values) {
    for (const auto& value : values)
        if (!value.allFinite()) return false;
    return true;
}

void validatePrimitive(const Primitive& primitive, const std::string& where, std::size_t materialCount) {
    const std::size_t n = primitive.positions.size();
    auto checkSize = [&](std::size_t size, const char* attribute) {
        if (size != 0 && size != n)
            throw std::invalid_argument(where + ": " + attribute + " has " + std::to_string(size) + " entries for " +
                                        std::to_string(n) + " vertices");
    };
    checkSize(primitive.normals.size(), "NORMAL");
    checkSize(primitive.texcoords.size(), "TEXCOORD_0");
    checkSize(primitive.colors.size(), "COLOR_0");
    if (!allFinite(primitive.positions) || !allFinite(primitive.normals) || !allFinite(primitive.texcoords) ||
        !allFinite(primitive.colors))
        throw std::invalid_argument(where + ": a coordinate or attribute is NaN or infinite");
    auto checkAttribute = [&](const VertexAttribute& attribute) {
        if (attribute.components < 1 || attribute.components > 4 ||
            attribute.values.size() != n * std::size_t(attribute.components))
            throw std::invalid_argument(where + ": " + attribute.name + " has " +
                                        std::to_string(attribute.values.size()) + " values for " + std::to_string(n) +
                                        " vertices of " + std::to_string(attribute.components) + " components");
        if (!std::all_of(attribute.values.begin(), attribute.values.end(), [](double v) { return std::isfinite(v); }))
            throw std::invalid_argument(where + ": " + attribute.name + " is NaN or infinite");
    };
    for (const VertexAttribute& attribute : primitive.attributes) checkAttribute(attribute);
    for (const MorphTarget& target : primitive.targets)
        for (const VertexAttribute& attribute : target) checkAttribute(attribute);
    for (const Triangle& triangle : primitive.triangles)
        for (std::uint32_t index : triangle)
            if (index >= n)
                throw std::invalid_argument(where + ": triangle index " + std::to_string(index) + " out of range (" +
                                            std::to_string(n) + " vertices)");
    for (const Segment& segment : primitive.lines)
        for (std::uint32_t index : segment)
            if (index >= n)
                throw std::invalid_argument(where + ": line index " + std::to_string(index) + " out of range (" +
                                            std::to_string(n) + " vertices)");
    if ((primitive.topology != Topology::Triangles && !primitive.triangles.empty()) ||
        (primitive.topology != Topology::Lines && !primitive.lines.empty()))
        throw std::invalid_argument(where + ": triangles or lines in a primitive of another topology");
    if (primitive.material < -1 || primitive.material >= static_cast<int>(materialCount))
        throw std::invalid_argument(where + ": material " + std::to_string(primitive.material) + " out of range");
}

}  // namespace

std::size_t morphTargetCount(const Mesh& mesh) {
    return mesh.primitives.empty() ? 0 : mesh.primitives.front().targets.size();
}

namespace {

// Depth-first over the node forest; `visit(node, world)` is called for every reachable node.
template <typename Visit>
void traverse(const Scene& scene, Visit&& visit) {
    struct Pending {
        int node;
        Eigen::Matrix4d parent;
    };
    std::vector<Pending> stack;
    for (auto root = scene.roots.rbegin(); root != scene.roots.rend(); ++root)
        stack.push_back({*root, Eigen::Matrix4d::Identity()});
    while (!stack.empty()) {
        Pending pending = stack.back();
        stack.pop_back();
        const Node& node = scene.nodes[pending.node];
        const Eigen::Matrix4d world = pending.parent * node.transform;
        visit(pending.node, world);
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
            stack.push_back({*child, world});
    }
}


}  // namespace

// (A morph target's displacements are turned approximately for a transform that is not rigid.)
void transformAttribute(VertexAttribute& attribute, const Eigen::Matrix3d& linear, const Eigen::Matrix3d& normalMatrix,
                        bool displacement) {
    const bool normal = attribute.name == "NORMAL", direction = attribute.name == "TANGENT" || normal;
    if (attribute.components < 3 || !(direction || (displacement && attribute.name == "POSITION"))) return;
    const Eigen::Matrix3d& matrix = normal ? normalMatrix : linear;
    for (std::size_t v = 0; v < attribute.count(); ++v) {
        Eigen::Map<Eigen::Vector3d> value(&attribute.values[v * std::size_t(attribute.components)]);
        value = matrix * value;
        if (!displacement && value.norm() > 0) value.normalize();
    }
}

Primitive transformPrimitive(Primitive local, const Eigen::Matrix4d& world) {
    Primitive out = std::move(local);
    const Eigen::Matrix3d linear = world.topLeftCorner<3, 3>();
    const Eigen::Vector3d translation = world.topRightCorner<3, 1>();
    for (Eigen::Vector3d& p : out.positions) p = linear * p + translation;
    // Normals transform by the inverse transpose, so that they stay perpendicular to sheared surfaces.
    const Eigen::Matrix3d normalMatrix = linear.inverse().transpose();
    for (Eigen::Vector3d& normal : out.normals) {
        normal = normalMatrix * normal;
        const double length = normal.norm();
        if (length > 0) normal /= length;
    }
    for (VertexAttribute& attribute : out.attributes) transformAttribute(attribute, linear, normalMatrix, false);
    for (MorphTarget& target : out.targets)
        for (VertexAttribute& attribute : target) transformAttribute(attribute, linear, normalMatrix, true);
    // A mirroring transform turns counter-clockwise triangles clockwise: flip them back.
    if (linear.determinant() < 0)
        for (Triangle& triangle : out.triangles) std::swap(triangle[1], triangle[2]);
    return out;
}

void keepVertices(Primitive& primitive, const std::vector<std::uint32_t>& kept) {
    auto keep = [&](auto& values) {
        if (values.empty()) return;
        std::remove_reference_t<decltype(values)> out;
        out.reserve(kept.size());
        for (std::uint32_t v : kept) out.push_back(values[v]);
        values = std::move(out);
    };
    auto keepAttribute = [&](VertexAttribute& attribute) {
        VertexAttribute out = attribute.withoutValues();
        out.values.reserve(kept.size() * std::size_t(attribute.components));
        for (std::uint32_t v : kept) out.appendVertex(attribute, v);
        attribute = std::move(out);
    };
    keep(primitive.positions);
    keep(primitive.normals);
    keep(primitive.texcoords);
    keep(primitive.colors);
    for (VertexAttribute& attribute : primitive.attributes) keepAttribute(attribute);
    for (MorphTarget& target : primitive.targets)
        for (VertexAttribute& attribute : target) keepAttribute(attribute);
}

std::optional<ZeroAreaTriangles> zeroAreaTrianglesOf(const Primitive& primitive) {
    std::optional<ZeroAreaTriangles> zeroArea;
    for (const Triangle& t : primitive.triangles)
        if (hasTwoCornersAtOnePoint(primitive.positions, t)) {
            if (!zeroArea) zeroArea = ZeroAreaTriangles{0, t[0]};
            ++zeroArea->count;
        }
    return zeroArea;
}

std::optional<std::pair<Primitive, ZeroAreaTriangles>> withoutZeroAreaTriangles(const Primitive& primitive) {
    const std::vector<Eigen::Vector3d>& p = primitive.positions;
    const std::optional<ZeroAreaTriangles> zeroArea = zeroAreaTrianglesOf(primitive);
    if (!zeroArea) return std::nullopt;
    std::pair<Primitive, ZeroAreaTriangles> split{primitive, *zeroArea};
    std::vector<Triangle>& drawing = split.first.triangles;
    drawing.erase(std::remove_if(drawing.begin(), drawing.end(),
                                 [&](const Triangle& t) { return hasTwoCornersAtOnePoint(p, t); }),
                  drawing.end());
    std::vector<std::uint32_t> newIndex(p.size(), 0), kept;
    for (const Triangle& t : drawing)
        for (std::uint32_t v : t) newIndex[v] = 1;
    for (std::uint32_t v = 0; v < p.size(); ++v)
        if (newIndex[v]) newIndex[v] = std::uint32_t(kept.size()), kept.push_back(v);
    keepVertices(split.first, kept);
    for (Triangle& t : drawing)
        for (std::uint32_t& v : t) v = newIndex[v];
    return split;
}

void appendPrimitive(Primitive& into, const Primitive& part) {
    const auto offset = static_cast<std::uint32_t>(into.positions.size());
    into.material = part.material;
    into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
    into.normals.insert(into.normals.end(), part.normals.begin(), part.normals.end());
    into.texcoords.insert(into.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
    into.colors.insert(into.colors.end(), part.colors.begin(), part.colors.end());
    if (into.attributes.empty())
        for (const VertexAttribute& attribute : part.attributes) into.attributes.push_back(attribute.withoutValues());
    for (std::size_t a = 0; a < part.attributes.size(); ++a)
        into.attributes[a].values.insert(into.attributes[a].values.end(), part.attributes[a].values.begin(),
                                         part.attributes[a].values.end());
    for (const Triangle& t : part.triangles) into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

std::uint64_t trianglePositionsHash(const Primitive& primitive) {
    std::uint64_t hash = 14695981039346656037ull;  // FNV-1a over the coordinates' bits
    for (const Triangle& t : primitive.triangles)
        for (std::uint32_t v : t)
            for (int c = 0; c < 3; ++c) {
                std::uint64_t bits = 0;
                const double x = primitive.positions[v][c];
                std::memcpy(&bits, &x, sizeof bits);
                for (int byte = 0; byte < 8; ++byte) hash = (hash ^ ((bits >> (8 * byte)) & 0xff)) * 1099511628211ull;
            }
    return hash;
}

std::string attributeSignature(const Primitive& primitive) {
    std::string signature;
    for (const VertexAttribute& attribute : primitive.attributes)
        signature += attribute.name + ":" + std::to_string(attribute.components) + ";";
    return signature;
}

void validateScene(const Scene& scene) {
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        for (const TextureRef* use : scene.materials[m].textureRefs())
            if (use->texture < -1 || use->texture >= static_cast<int>(scene.textures.size()) || use->texCoord < 0)
                throw std::invalid_argument("material " + std::to_string(m) + ": texture index out of range");
        const std::vector<int>& variants = scene.materials[m].variants;
        if ((!variants.empty() && variants.size() != scene.materialVariants.size()) ||
            std::any_of(variants.begin(), variants.end(), [&](int v) {
                return v < -1 || v >= static_cast<int>(scene.materials.size()) ||
                       (v >= 0 && !scene.materials[std::size_t(v)].variants.empty());
            }))
            throw std::invalid_argument("material " + std::to_string(m) + ": variant material out of range");
    }
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            validatePrimitive(mesh.primitives[p], "mesh " + std::to_string(m) + " primitive " + std::to_string(p),
                              scene.materials.size());
            if (mesh.primitives[p].targets.size() != morphTargetCount(mesh))
                throw std::invalid_argument("mesh " + std::to_string(m) + ": primitives with different numbers of morph targets");
        }
        if (!mesh.weights.empty() && mesh.weights.size() != morphTargetCount(mesh))
            throw std::invalid_argument("mesh " + std::to_string(m) + ": more or fewer weights than morph targets");
    }
    for (std::size_t k = 0; k < scene.skins.size(); ++k) {
        const Skin& skin = scene.skins[k];
        auto isNode = [&](int n) { return n >= 0 && std::size_t(n) < scene.nodes.size(); };
        if (skin.joints.empty() || !std::all_of(skin.joints.begin(), skin.joints.end(), isNode) ||
            (skin.skeleton != -1 && !isNode(skin.skeleton)))
            throw std::invalid_argument("skin " + std::to_string(k) + ": no joints, or a joint or skeleton out of range");
        if (!skin.inverseBindMatrices.empty() && skin.inverseBindMatrices.size() != skin.joints.size())
            throw std::invalid_argument("skin " + std::to_string(k) + ": inverse bind matrices and joints differ in number");
    }
    const int nodeCount = static_cast<int>(scene.nodes.size());
    std::vector<int> parents(scene.nodes.size(), 0);
    for (int n = 0; n < nodeCount; ++n) {
        const Node& node = scene.nodes[n];
        if (node.mesh < -1 || node.mesh >= static_cast<int>(scene.meshes.size()))
            throw std::invalid_argument("node " + std::to_string(n) + ": mesh index out of range");
        if (!node.transform.allFinite())
            throw std::invalid_argument("node " + std::to_string(n) + ": transform is NaN or infinite");
        if (node.camera < -1 || node.camera >= static_cast<int>(scene.cameras.size()))
            throw std::invalid_argument("node " + std::to_string(n) + ": camera index out of range");
        if (node.light < -1 || node.light >= static_cast<int>(scene.lights.size()))
            throw std::invalid_argument("node " + std::to_string(n) + ": light index out of range");
        if (node.skin < -1 || node.skin >= static_cast<int>(scene.skins.size()))
            throw std::invalid_argument("node " + std::to_string(n) + ": skin index out of range");
        if (!node.weights.empty() && (node.mesh < 0 || node.weights.size() != morphTargetCount(scene.meshes[node.mesh])))
            throw std::invalid_argument("node " + std::to_string(n) + ": morph weights that its mesh has no targets for");
        for (int child : node.children) {
            if (child < 0 || child >= nodeCount)
                throw std::invalid_argument("node " + std::to_string(n) + ": child index out of range");
            if (++parents[child] > 1)
                throw std::invalid_argument("node " + std::to_string(child) + " has more than one parent");
        }
    }
    std::vector<char> listed(scene.nodes.size(), 0);  // a root drawn twice: the writers name each node once
    for (int root : scene.roots) {
        if (root < 0 || root >= nodeCount) throw std::invalid_argument("root node index out of range");
        if (parents[root] != 0) throw std::invalid_argument("root node " + std::to_string(root) + " has a parent");
        if (listed[root]++) throw std::invalid_argument("root node " + std::to_string(root) + " listed twice");
    }
    // With one parent at most per node, a cycle is a set of nodes never reached from a parentless node.
    std::vector<char> reached(scene.nodes.size(), 0);
    std::vector<int> stack;
    for (int n = 0; n < nodeCount; ++n)
        if (parents[n] == 0) stack.push_back(n);
    while (!stack.empty()) {
        int n = stack.back();
        stack.pop_back();
        reached[n] = 1;
        for (int child : scene.nodes[n].children) stack.push_back(child);
    }
    for (int n = 0; n < nodeCount; ++n)
        if (!reached[n]) throw std::invalid_argument("node " + std::to_string(n) + " is part of a cycle");
    for (std::size_t a = 0; a < scene.animations.size(); ++a)
        for (std::size_t c = 0; c < scene.animations[a].channels.size(); ++c) {
            const AnimationChannel& channel = scene.animations[a].channels[c];
            const std::string where = "animation " + std::to_string(a) + " channel " + std::to_string(c) + ": ";
            if (const std::string problem = animationChannelProblem(channel, scene.nodes.size()); !problem.empty())
                throw std::invalid_argument(where + problem);
            const int mesh = scene.nodes[std::size_t(channel.node)].mesh;
            if (channel.path == AnimationChannel::Path::Weights &&
                (mesh < 0 || std::size_t(channel.weights) != morphTargetCount(scene.meshes[std::size_t(mesh)])))
                throw std::invalid_argument(where + "morph weights for another number of targets than its node's mesh has");
        }
    for (std::size_t c = 0; c < scene.cameras.size(); ++c)
        if (const std::string problem = cameraProblem(scene.cameras[c]); !problem.empty())
            throw std::invalid_argument("camera " + std::to_string(c) + ": " + problem);
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
        if (const std::string problem = lightProblem(scene.lights[l]); !problem.empty())
            throw std::invalid_argument("light " + std::to_string(l) + ": " + problem);
}

std::string cameraProblem(const Camera& camera) {
    const double numbers[] = {camera.yfov, camera.aspectRatio, camera.xmag, camera.ymag, camera.znear, camera.zfar};
    if (!std::all_of(std::begin(numbers), std::end(numbers), [](double v) { return std::isfinite(v); }))
        return "NaN or infinite values";
    if (camera.projection == Camera::Projection::Perspective) {
        if (!(camera.yfov > 0) || !(camera.znear > 0)) return "a perspective camera needs yfov and znear above 0";
        if (camera.aspectRatio < 0) return "negative aspect ratio";
        if (camera.zfar != 0 && !(camera.zfar > camera.znear)) return "zfar is not beyond znear";
    } else {
        if (camera.xmag == 0 || camera.ymag == 0) return "an orthographic camera needs xmag and ymag other than 0";
        if (camera.znear < 0 || !(camera.zfar > camera.znear)) return "an orthographic camera needs 0 <= znear < zfar";
    }
    return "";
}

std::string lightProblem(const Light& light) {
    const double numbers[] = {light.color.x(), light.color.y(), light.color.z(), light.intensity,
                              light.range, light.innerConeAngle, light.outerConeAngle};
    if (!std::all_of(std::begin(numbers), std::end(numbers), [](double v) { return std::isfinite(v); }))
        return "NaN or infinite values";
    if (light.intensity < 0 || light.range < 0 || (light.color.array() < 0).any()) return "negative colour, intensity or range";
    if (light.type == Light::Type::Spot &&
        !(0 <= light.innerConeAngle && light.innerConeAngle < light.outerConeAngle && light.outerConeAngle <= std::acos(0.0)))  // pi/2
        return "a spot light needs 0 <= innerConeAngle < outerConeAngle <= pi/2";
    if (light.x3dAttenuation && (!light.x3dAttenuation->allFinite() || (light.x3dAttenuation->array() < 0).any()))
        return "an attenuation with NaN, infinite or negative values";
    return "";
}

std::string animationChannelProblem(const AnimationChannel& channel, std::size_t nodes) {
    if (channel.node < 0 || std::size_t(channel.node) >= nodes) return "node index out of range";
    if (channel.path == AnimationChannel::Path::Weights && channel.weights <= 0) return "morph weights of no targets";
    if (channel.times.empty() || channel.values.size() != channel.times.size() * channel.valuesPerKey())
        return std::to_string(channel.values.size()) + " values for " + std::to_string(channel.times.size()) + " keys";
    const auto finite = [](double v) { return std::isfinite(v); };
    if (!std::all_of(channel.times.begin(), channel.times.end(), finite) || !std::all_of(channel.values.begin(), channel.values.end(), finite))
        return "NaN or infinite values";
    if (channel.times.front() < 0) return "negative key times";  // glTF 2.0: time[0] >= 0
    if (std::adjacent_find(channel.times.begin(), channel.times.end(), std::greater_equal<double>()) != channel.times.end())
        return "key times do not increase";
    return "";
}

Eigen::Vector2d baseColorTexcoord(const Scene& scene, const Primitive& primitive, std::size_t v) {
    if (primitive.material < 0) return primitive.texcoords[v];
    const TextureRef& use = scene.materials[std::size_t(primitive.material)].baseColorTexture;
    Eigen::Vector2d t = primitive.texcoords[v];
    const std::string set = "TEXCOORD_" + std::to_string(use.texCoordSet());
    for (const VertexAttribute& attribute : primitive.attributes)
        if (attribute.name == set && attribute.components >= 2)
            t = {attribute.values[v * std::size_t(attribute.components)], attribute.values[v * std::size_t(attribute.components) + 1]};
    return use.transform ? Eigen::Vector2d(use.transform->matrix() * t.homogeneous()) : t;
}

std::vector<const Material*> materialsDrawnWith(const Scene& scene, int m) {
    std::vector<const Material*> out;
    if (m < 0) return out;
    out.push_back(&scene.materials[std::size_t(m)]);
    for (int v : scene.materials[std::size_t(m)].variants)
        if (v >= 0 && std::find(out.begin(), out.end(), &scene.materials[std::size_t(v)]) == out.end())
            out.push_back(&scene.materials[std::size_t(v)]);
    return out;
}

bool drawnBlended(const Scene& scene, int m) {
    const std::vector<const Material*> drawn = materialsDrawnWith(scene, m);
    return std::any_of(drawn.begin(), drawn.end(),
                       [](const Material* material) { return material->alphaMode == Material::AlphaMode::Blend; });
}

void copyNodeNotes(const Node& from, Node& to) {
    to.name = from.name;
    to.extrasJson = from.extrasJson;
    to.extensionsJson = from.extensionsJson;
}

void copyFileMetadata(const Scene& from, Scene& to) {
    to.extrasJson = from.extrasJson;
    to.copyright = from.copyright;
    to.name = from.name;
    to.sceneExtrasJson = from.sceneExtrasJson;
    to.rootExtrasJson = from.rootExtrasJson;
    to.extensionsJson = from.extensionsJson;
    to.assetExtensionsJson = from.assetExtensionsJson;
    to.sceneExtensionsJson = from.sceneExtensionsJson;
}

void renumberVariantMaterials(Scene& scene, const std::vector<int>& newIndex) {
    for (Material& material : scene.materials)
        for (int& v : material.variants)
            if (v >= 0) v = newIndex[std::size_t(v)];
}

std::size_t removeMaterials(Scene& scene, const std::vector<bool>& keep) {
    std::vector<int> newIndex(scene.materials.size(), -1);
    std::vector<Material> kept;
    for (std::size_t m = 0; m < scene.materials.size(); ++m)
        if (keep[m]) {
            newIndex[m] = int(kept.size());
            kept.push_back(std::move(scene.materials[m]));
        }
    const std::size_t removed = scene.materials.size() - kept.size();
    scene.materials = std::move(kept);
    renumberVariantMaterials(scene, newIndex);
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives)
            if (primitive.material >= 0) primitive.material = newIndex[std::size_t(primitive.material)];
    return removed;
}

void renumberTextures(Scene& scene, const std::vector<int>& newIndex) {
    for (Material& material : scene.materials)
        for (TextureRef* use : material.textureRefs())
            if (use->texture >= 0 && (use->texture = newIndex[std::size_t(use->texture)]) < 0) *use = TextureRef{};
}

std::vector<int> firstTextureOfSameImage(const std::vector<Texture>& textures) {
    std::vector<int> first(textures.size());
    for (std::size_t i = 0; i < textures.size(); ++i) {
        first[i] = int(i);
        for (std::size_t j = 0; j < i; ++j)
            if (textures[j].bytes == textures[i].bytes && textures[j].mimeType == textures[i].mimeType &&
                (!textures[i].bytes.empty() || textures[j].uri == textures[i].uri) &&  // unread images: by URL
                textures[j].fallback == textures[i].fallback) {
                first[i] = first[j];
                break;
            }
    }
    return first;
}

std::vector<Eigen::Matrix4d> worldTransforms(const Scene& scene) {
    std::vector<Eigen::Matrix4d> world(scene.nodes.size(), Eigen::Matrix4d::Identity());
    traverse(scene, [&](int node, const Eigen::Matrix4d& transform) { world[node] = transform; });
    return world;
}

std::vector<WorldPrimitive> flattenScene(const Scene& scene) {
    std::vector<WorldPrimitive> out;
    traverse(scene, [&](int node, const Eigen::Matrix4d& world) {
        const int mesh = scene.nodes[node].mesh;
        if (mesh < 0) return;
        for (const Primitive& primitive : scene.meshes[mesh].primitives)
            out.push_back({transformPrimitive(primitive, world), node, mesh});
    });
    return out;
}

std::vector<WorldPrimitive> flattenSceneTaking(Scene& scene, const std::vector<char>& takeMesh) {
    std::vector<std::size_t> drawingsLeft(scene.meshes.size(), 0);
    traverse(scene, [&](int node, const Eigen::Matrix4d&) {
        if (const int mesh = scene.nodes[node].mesh; mesh >= 0) ++drawingsLeft[std::size_t(mesh)];
    });
    std::vector<WorldPrimitive> out;
    traverse(scene, [&](int node, const Eigen::Matrix4d& world) {
        const int mesh = scene.nodes[node].mesh;
        if (mesh < 0) return;
        const bool last = --drawingsLeft[std::size_t(mesh)] == 0 && takeMesh[std::size_t(mesh)];
        for (Primitive& primitive : scene.meshes[std::size_t(mesh)].primitives)
            out.push_back(
                {last ? transformPrimitive(std::move(primitive), world) : transformPrimitive(primitive, world), node,
                 mesh});
    });
    for (std::size_t m = 0; m < scene.meshes.size(); ++m)
        if (takeMesh[m])
            for (Primitive& primitive : scene.meshes[m].primitives) {
                Primitive emptied;
                emptied.material = primitive.material;
                primitive = std::move(emptied);
            }
    return out;
}

Scene expandInstances(const Scene& scene) {
    Scene flat;
    flat.textures = scene.textures;
    flat.materials = scene.materials;
    flat.materialVariants = scene.materialVariants;
    copyFileMetadata(scene, flat);
    flat.warnings = scene.warnings;
    std::vector<int> tops;
    const std::vector<bool> animated = markAnimatedSubtrees(scene, tops);
    Mesh mesh;
    mesh.name = "expanded";
    for (WorldPrimitive& world : flattenScene(scene))
        if (!animated[std::size_t(world.node)]) mesh.primitives.push_back(std::move(world.primitive));
    flat.meshes.push_back(std::move(mesh));
    Node root;
    root.name = "expanded";
    root.mesh = 0;
    flat.nodes.push_back(root);
    flat.roots.push_back(0);
    flat.cameras = scene.cameras;
    flat.lights = scene.lights;
    flat.x3dEnvironment = scene.x3dEnvironment;
    traverse(scene, [&](int node, const Eigen::Matrix4d& world) {
        const Node& from = scene.nodes[node];
        if ((from.camera < 0 && from.light < 0) || animated[std::size_t(node)]) return;
        Node placed;
        placed.name = from.name;
        placed.transform = world;
        placed.camera = from.camera;
        placed.light = from.light;
        flat.roots.push_back(int(flat.nodes.size()));
        flat.nodes.push_back(std::move(placed));
    });
    std::map<int, int> keptMesh;
    keepAnimatedSubtrees(scene, tops, flat, keptMesh);
    return flat;
}

SceneStatistics sceneStatistics(const Scene& scene) {
    SceneStatistics statistics;
    statistics.nodes = scene.nodes.size();
    statistics.meshes = scene.meshes.size();
    statistics.materials = scene.materials.size();
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& primitive : mesh.primitives) statistics.trianglesStored += primitive.triangles.size();
    traverse(scene, [&](int node, const Eigen::Matrix4d& world) {
        const int mesh = scene.nodes[node].mesh;
        if (mesh < 0) return;
        for (const Primitive& primitive : scene.meshes[mesh].primitives) {
            statistics.trianglesDrawn += primitive.triangles.size();
            // Only vertices used by a triangle count towards the bounding box.
            std::vector<char> used(primitive.positions.size(), 0);
            for (const Triangle& triangle : primitive.triangles)
                for (std::uint32_t index : triangle) used[index] = 1;
            for (std::size_t v = 0; v < primitive.positions.size(); ++v)
                if (used[v])
                    statistics.bounds.extend(
                        (world * primitive.positions[v].homogeneous()).head<3>());
        }
    });
    return statistics;
}

TriangleMesh worldMesh(const Scene& scene) {
    TriangleMesh mesh;
    for (const WorldPrimitive& placed : flattenScene(scene)) {
        const auto offset = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), placed.primitive.positions.begin(), placed.primitive.positions.end());
        for (const Triangle& t : placed.primitive.triangles) mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
    return mesh;
}

DrawnVertices worldPointsAndLineEnds(const Scene& scene) {
    DrawnVertices out;
    traverse(scene, [&](int node, const Eigen::Matrix4d& world) {
        const int mesh = scene.nodes[std::size_t(node)].mesh;
        if (mesh < 0) return;
        for (const Primitive& primitive : scene.meshes[std::size_t(mesh)].primitives) {
            auto add = [&](TriangleMesh& to, std::uint32_t v) {
                const auto index = static_cast<std::uint32_t>(to.positions.size());
                to.positions.push_back((world * primitive.positions[v].homogeneous()).head<3>());
                to.triangles.push_back({index, index, index});
            };
            for (const Segment& segment : primitive.lines) add(out.lineEnds, segment[0]), add(out.lineEnds, segment[1]);
            if (primitive.topology == Topology::Points)
                for (std::uint32_t v = 0; v < primitive.positions.size(); ++v) add(out.points, v);
        }
    });
    return out;
}

Scene sceneOfOneMesh(const std::string& name, Primitive primitive) {
    Scene scene;
    // Moved, not listed in braces: an initializer list copies its elements (a large STL's arrays, twice).
    // The node alone takes the name: a file of one unnamed mesh (STL, PLY) names it by itself, and the mesh's name
    // would only say it again in the output (20 bytes of the bunny's GLB).
    scene.meshes.emplace_back().primitives.push_back(std::move(primitive));
    Node node;
    node.name = name;
    node.mesh = 0;
    scene.nodes.push_back(node);
    scene.roots.push_back(0);
    return scene;
}

}  // namespace symcompress
