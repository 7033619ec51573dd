// X3D nodes that are not geometry: animations (TimeSensor-driven interpolators ROUTEd to Transforms),
// viewpoints, lights, and the environment nodes kept as XML text.
#include "symcompress/scene_ops.hpp"
#include "x3d_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace symcompress {
namespace fs = std::filesystem;

// π/4, the default of Viewpoint's fieldOfView and SpotLight's cutOffAngle, as the SFFloat (float32) it is.
constexpr double kQuarterTurnAsSFFloat = static_cast<float>(0.7853981633974483);

// A ROUTE from a Position- or OrientationInterpolator's value to a Transform's translation, rotation or
// scale, the interpolator driven by a TimeSensor's fraction, becomes a channel of that TimeSensor's
// animation: key times the cycleInterval (nudged to increase strictly where keys repeat, as glTF asks),
// axis-angle values as quaternions. Routes that do not fit (other interpolators, a Transform with a
// center or scaleOrientation, which glTF's translation-rotation-scale cannot hold) are left out with a note.
void X3dReader::readAnimations() {
    std::map<std::string, pugi::xml_node> byDef;
    for (const pugi::xpath_node& found : document_.select_nodes("//*[@DEF]"))
        byDef[found.node().attribute("DEF").value()] = found.node();
    const pugi::xpath_node_set routes = document_.select_nodes("//ROUTE");
    auto attribute = [](const pugi::xml_node& node, const char* name) {
        return std::string(node.attribute(name).value());
    };
    // "set_rotation", "rotation" and "rotation_changed" name one field.
    auto field = [&](const pugi::xml_node& route, const char* name) {
        std::string value = attribute(route, name);
        if (value.rfind("set_", 0) == 0) value.erase(0, 4);
        if (value.size() > 8 && value.compare(value.size() - 8, 8, "_changed") == 0) value.erase(value.size() - 8);
        return value;
    };
    auto defined = [&](const std::string& def, const char* type) {
        const auto found = byDef.find(def);
        return found != byDef.end() && std::strcmp(found->second.name(), type) == 0 ? found->second : pugi::xml_node();
    };
    std::map<std::string, std::size_t> animationOf;  // TimeSensor DEF -> index into Scene::animations
    std::size_t leftOut = 0;
    for (const pugi::xpath_node& found : routes) {
        const pugi::xml_node route = found.node();
        const std::string to = field(route, "toField");
        if (field(route, "fromField") != "value" || (to != "translation" && to != "rotation" && to != "scale"))
            continue;
        const std::string source = attribute(route, "fromNode");
        const pugi::xml_node interpolator =
            defined(source, to == "rotation" ? "OrientationInterpolator" : "PositionInterpolator");
        const pugi::xml_node transform = defined(attribute(route, "toNode"), "Transform");
        const auto targets = nodesOfTransform_.find(attribute(route, "toNode"));
        pugi::xml_node clock;
        for (const pugi::xpath_node& other : routes)
            if (attribute(other.node(), "toNode") == source && field(other.node(), "toField") == "fraction" &&
                field(other.node(), "fromField") == "fraction")
                clock = defined(attribute(other.node(), "fromNode"), "TimeSensor");
        if (!interpolator || !transform || targets == nodesOfTransform_.end() || !clock ||
            !vector3(transform, "center", Eigen::Vector3d::Zero()).isZero() ||
            rotationField(numbers(transform, "scaleOrientation")).angle() != 0) {
            ++leftOut;
            continue;
        }
        const bool rotation = to == "rotation";
        const std::vector<double> keys = numbers(interpolator, "key"), values = numbers(interpolator, "keyValue");
        const std::size_t components = rotation ? 4 : 3;
        if (keys.empty() || values.size() != keys.size() * components || !std::is_sorted(keys.begin(), keys.end())) {
            ++leftOut;
            continue;
        }
        AnimationChannel channel;
        channel.path = rotation        ? AnimationChannel::Path::Rotation
                       : to == "scale" ? AnimationChannel::Path::Scale
                                       : AnimationChannel::Path::Translation;
        const double cycle = scalar(clock, "cycleInterval", 1);
        // Times are nudged as floats below: each must be one (a cycle of 1e300 makes none). glTF's times
        // start at 0 or later; a key before the cycle's start is never reached anyway.
        const bool timesFit = cycle > 0 && std::all_of(keys.begin(), keys.end(), [cycle](double key) {
            return key >= 0 && key * cycle < std::numeric_limits<float>::max();
        });
        if (!timesFit) {
            ++leftOut;
            continue;
        }
        for (std::size_t k = 0; k < keys.size(); ++k) {
            double time = keys[k] * cycle;
            if (k > 0 && !(time > channel.times.back()))
                time = std::nextafter(static_cast<float>(channel.times.back()), std::numeric_limits<float>::infinity());
            channel.times.push_back(time);
            const double* value = values.data() + k * components;
            if (rotation) {
                const Eigen::Quaterniond q(rotationField({value[0], value[1], value[2], value[3]}));
                channel.values.insert(channel.values.end(), {q.x(), q.y(), q.z(), q.w()});
            } else {
                channel.values.insert(channel.values.end(), value, value + 3);
            }
        }
        auto [entry, added] = animationOf.emplace(attribute(clock, "DEF"), scene_.animations.size());
        if (added) scene_.animations.push_back({attribute(clock, "DEF"), {}});
        for (int node : targets->second) {
            channel.node = node;
            scene_.animations[entry->second].channels.push_back(channel);
        }
    }
    if (leftOut)
        notes_.insert(std::to_string(leftOut) +
                      " animation ROUTEs left out (read: Position and Orientation interpolators " +
                      "driven by a TimeSensor, on Transforms without center or scaleOrientation)");
}

// A NavigationInfo, Background, Fog or WorldInfo as XML text for Scene::x3dEnvironment, without its DEF
// names (the writer makes its own; the ROUTEs that bind such nodes are not kept) and without a
// Background's image URLs, which are relative to the input's folder.
void X3dReader::keepEnvironment(const pugi::xml_node& node) {
    pugi::xml_document copy;
    pugi::xml_node kept = copy.append_copy(node);
    std::size_t images = 0;
    auto clean = [&](auto&& self, pugi::xml_node element) -> void {
        element.remove_attribute("DEF");
        std::vector<std::string> urls;
        for (const pugi::xml_attribute attribute : element.attributes()) {
            const std::string name = attribute.name();
            if (name.size() > 3 && name.compare(name.size() - 3, 3, "Url") == 0) urls.push_back(name);
        }
        for (const std::string& url : urls) element.remove_attribute(url.c_str());
        images += urls.size();
        for (pugi::xml_node child = element.first_child(); child;) {
            const pugi::xml_node next = child.next_sibling();
            if (child.type() == pugi::node_element && child.attribute("USE"))
                element.remove_child(child);
            else if (child.type() == pugi::node_element)
                self(self, child);
            child = next;
        }
    };
    clean(clean, kept);
    if (images) notes_.insert("Background images are not kept (their URLs are relative to the input's folder)");
    std::ostringstream text;
    kept.print(text, "", pugi::format_raw);
    scene_.x3dEnvironment.push_back(text.str());
}

// A Viewpoint (or OrthoViewpoint) as a node placed at its position and orientation holding a camera: both
// look down -z with +y up. fieldOfView becomes the vertical one (X3D's is the smaller of the two, the
// vertical one in a landscape window); the near and far planes come from the NavigationInfo (avatarSize[0] / 2
// and visibilityLimit), as an X3D browser sets them.
int X3dReader::readViewpoint(const pugi::xml_node& viewpoint) {
    const bool orthographic = std::strcmp(viewpoint.name(), "OrthoViewpoint") == 0;
    Camera camera;
    camera.name = viewpoint.attribute("description").value();
    const pugi::xml_node navigation = document_.select_node("//NavigationInfo").node();
    const std::vector<double> avatar = navigation ? numbers(navigation, "avatarSize") : std::vector<double>();
    camera.znear = !avatar.empty() && avatar[0] > 0 ? avatar[0] / 2 : 0.125;
    camera.zfar = navigation ? scalar(navigation, "visibilityLimit", 0) : 0;
    Eigen::Affine3d placement = Eigen::Affine3d::Identity();
    placement.translate(vector3(viewpoint, "position", Eigen::Vector3d(0, 0, 10)))
        .rotate(rotationField(numbers(viewpoint, "orientation")));
    if (orthographic) {
        // fieldOfView: minimum x, minimum y, maximum x, maximum y of the view; glTF's is centred.
        std::vector<double> field = numbers(viewpoint, "fieldOfView");
        if (field.size() != 4) field = {-1, -1, 1, 1};
        camera.projection = Camera::Projection::Orthographic;
        camera.xmag = (field[2] - field[0]) / 2;
        camera.ymag = (field[3] - field[1]) / 2;
        placement.translate(Eigen::Vector3d((field[0] + field[2]) / 2, (field[1] + field[3]) / 2, 0));
        if (!(camera.zfar > camera.znear)) camera.zfar = 1e4;  // glTF needs a far plane; X3D's may be infinite
    } else {
        camera.yfov = scalar(viewpoint, "fieldOfView", kQuarterTurnAsSFFloat);
    }
    if (const std::string problem = cameraProblem(camera); !problem.empty()) {
        notes_.insert("a " + std::string(viewpoint.name()) + " was left out: " + problem);
        return -1;
    }
    scene_.cameras.push_back(camera);
    return addPlacedNode(viewpoint, placement, int(scene_.cameras.size()) - 1, -1);
}

// A node of its own at `placement`, named by the X3D node's DEF, carrying a camera or a light.
int X3dReader::addPlacedNode(const pugi::xml_node& source, const Eigen::Affine3d& placement, int camera, int light) {
    Node out;
    out.name = source.attribute("DEF").value();
    out.transform = placement.matrix();
    out.camera = camera;
    out.light = light;
    scene_.nodes.push_back(out);
    return int(scene_.nodes.size()) - 1;
}

// A light as a node at its location, turned so that its direction is -z (glTF's frame). What glTF's
// KHR_lights_punctual cannot hold is said in a note (ambient intensity, a light scoped to its group, a light
// that is off) or kept for X3D output (attenuation: glTF's lights fall off with the inverse square).
int X3dReader::readLight(const pugi::xml_node& source, int depth) {
    const std::string type = source.name();
    if (!boolean(source, "on", true)) {
        notes_.insert("lights that are off (on='false') left out");
        return -1;
    }
    Light light;
    light.type = type == "DirectionalLight" ? Light::Type::Directional
                 : type == "SpotLight"      ? Light::Type::Spot
                                            : Light::Type::Point;
    light.color = vector3(source, "color", Eigen::Vector3d::Ones());
    light.intensity = scalar(source, "intensity", 1);
    if (light.type != Light::Type::Directional) {
        light.range = scalar(source, "radius", 100);
        if (light.range >= std::numeric_limits<float>::max()) light.range = 0;  // how the writer says "no limit"
    }
    if (light.type == Light::Type::Spot) {
        light.outerConeAngle = std::min(scalar(source, "cutOffAngle", kQuarterTurnAsSFFloat), std::acos(0.0));
        light.innerConeAngle =
            std::min(scalar(source, "beamWidth", std::acos(0.0)), std::nextafter(light.outerConeAngle, 0.0));
    }
    if (light.type != Light::Type::Directional) {
        const Eigen::Vector3d attenuation = vector3(source, "attenuation", Eigen::Vector3d(1, 0, 0));
        if (attenuation != Eigen::Vector3d(0, 0, 1)) light.x3dAttenuation = attenuation;
    }
    if (scalar(source, "ambientIntensity", 0) != 0)
        notes_.insert("the ambientIntensity of lights is not kept (glTF's lights have none)");
    if (!boolean(source, "global", light.type != Light::Type::Directional) && depth > 1)
        notes_.insert("lights scoped to their group (global='false') light the whole scene once written");
    if (const std::string problem = lightProblem(light); !problem.empty()) {
        notes_.insert("a " + type + " was left out: " + problem);
        return -1;
    }
    Eigen::Affine3d placement = Eigen::Affine3d::Identity();
    if (light.type != Light::Type::Directional)
        placement.translate(vector3(source, "location", Eigen::Vector3d::Zero()));
    if (light.type != Light::Type::Point) {
        const Eigen::Vector3d direction = vector3(source, "direction", Eigen::Vector3d(0, 0, -1));
        if (direction.norm() > 0)
            placement.rotate(Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(0, 0, -1), direction));
    }
    scene_.lights.push_back(light);
    return addPlacedNode(source, placement, -1, int(scene_.lights.size()) - 1);
}

}  // namespace symcompress
