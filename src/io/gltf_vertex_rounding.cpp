#include "gltf_vertex_rounding.hpp"

#include "geometry/bounds.hpp"
#include "geometry/hilbert_curve.hpp"
#include "gltf_instance_encoding.hpp"
#include "gltf_integer_positions.hpp"
#include "symcompress/scene_ops.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>

namespace symcompress {
namespace {

// `values` (of `components` each) through the exponential filter at `bits`, a vertex's components sharing one
// exponent.
RoundedAttribute exponentialRounded(const std::vector<float>& values, int components, int bits, bool liftZeros) {
    const std::vector<std::uint32_t> encoded = exponentialFiltered(values, std::size_t(components), bits, liftZeros);
    RoundedAttribute out;
    out.filtered.resize(encoded.size() * 4);
    std::memcpy(out.filtered.data(), encoded.data(), out.filtered.size());
    out.elementBytes = std::size_t(components) * 4;
    out.decoded = exponentialDecoded(encoded, std::size_t(components));
    out.bits = bits;
    out.components = components;
    return out;
}

// The largest distance between a vertex as read and as decoded: Euclidean over a position's or a direction's
// components (`euclidean`), else the largest of any component.
double largestError(const std::vector<float>& values, const RoundedAttribute& rounded, int components, bool euclidean) {
    double largest = 0;
    for (std::size_t v = 0; v < values.size(); v += std::size_t(components)) {
        double squared = 0, most = 0;
        for (int c = 0; c < components; ++c) {
            const double error = std::abs(double(rounded.decoded[v + c]) - double(values[v + c]));
            squared += error * error;
            most = std::max(most, error);
        }
        largest = std::max(largest, euclidean ? std::sqrt(squared) : most);
    }
    return largest;
}

// The fewest bits that keep `values` within `allowed`, with zeros lifted or not (exponentialFiltered), whichever
// meshopt codes smaller; none (stays as read) where even the filter's most bits do not.
std::optional<RoundedAttribute> roundedWithin(const std::vector<float>& values, int components, double allowed,
                                              bool euclidean) {
    if (!(allowed > 0) || values.empty() || components * 4 > 256) return std::nullopt;
    std::optional<RoundedAttribute> kept;
    std::size_t keptBytes = 0;
    for (const bool liftZeros : {false, true}) {
        const int bits = fewestBits(1, kMostExponentialBits, [&](int b) {
            return largestError(values, exponentialRounded(values, components, b, liftZeros), components, euclidean) <=
                   allowed;
        });
        if (bits == 0) continue;
        RoundedAttribute rounded = exponentialRounded(values, components, bits, liftZeros);
        const std::size_t bytes = meshoptEncoded(rounded.filtered, rounded.elementBytes).size();
        if (!kept || bytes < keptBytes) kept = std::move(rounded), keptBytes = bytes;
    }
    return kept;
}

// `values` (each within 0 to 1) as normalized unsigned bytes, else shorts, where each component stays within `allowed`
// (as glTF stores colours: a byte for each of 8 bits); none where neither does or a value lies outside.
std::optional<RoundedAttribute> normalizedWithin(const std::vector<float>& values, int components, double allowed) {
    if (values.empty() || std::any_of(values.begin(), values.end(), [](float x) { return !(x >= 0 && x <= 1); }))
        return std::nullopt;
    for (const int bytes : {1, 2}) {
        const double largest = bytes == 1 ? 255 : 65535;
        RoundedAttribute out;
        out.componentType = bytes == 1 ? kUnsignedByte : kUnsignedShort;
        out.normalized = true;
        out.filter = "NONE";
        out.components = components;
        out.bits = 8 * bytes;
        out.elementBytes = (std::size_t(components * bytes) + 3) / 4 * 4;  // vertex strides are multiples of 4
        out.filtered.assign(values.size() / std::size_t(components) * out.elementBytes, 0);
        bool within = true;
        for (std::size_t i = 0; i < values.size() && within; ++i) {
            const auto q = static_cast<std::uint32_t>(std::lround(double(values[i]) * largest));
            out.decoded.push_back(float(q / largest));
            within = std::abs(double(out.decoded.back()) - double(values[i])) <= allowed;
            unsigned char* at = out.filtered.data() + i / std::size_t(components) * out.elementBytes +
                                i % std::size_t(components) * std::size_t(bytes);
            for (int b = 0; b < bytes; ++b) at[b] = static_cast<unsigned char>(q >> (8 * b));  // little-endian
        }
        if (within) return out;
    }
    return std::nullopt;
}

// Unit vectors (`components` 3: normals, 4: tangents, whose w meshopt keeps) through meshopt's octahedral filter at the
// fewest bits that keep each within `allowed` (Euclidean, as a viewer reads the normalized integers), in bytes (a
// stride of 4) or shorts (8), whichever meshopt codes smaller; none where neither holds them.
std::optional<RoundedAttribute> octahedralWithin(const std::vector<float>& values, int components, double allowed) {
    const std::size_t count = values.size() / std::size_t(components);
    std::vector<float> padded(count * 4, 0.0f);  // the filter's input: 4 floats a vector
    for (std::size_t v = 0; v < count; ++v)
        for (int c = 0; c < components; ++c)
            padded[4 * v + std::size_t(c)] = values[v * std::size_t(components) + std::size_t(c)];
    auto rounded = [&](int stride, int bits) {
        RoundedAttribute out;
        out.filtered.resize(count * std::size_t(stride));
        meshopt_encodeFilterOct(out.filtered.data(), count, std::size_t(stride), bits, padded.data());
        std::vector<unsigned char> decoded = out.filtered;
        meshopt_decodeFilterOct(decoded.data(), count, std::size_t(stride));
        const double largest = stride == 4 ? 127 : 32767;
        for (std::size_t v = 0; v < count; ++v)
            for (int c = 0; c < components; ++c) {
                const unsigned char* at = decoded.data() + v * std::size_t(stride) + std::size_t(c * stride / 4);
                std::int16_t value = 0;
                if (stride == 4)
                    value = static_cast<std::int8_t>(at[0]);
                else
                    std::memcpy(&value, at, 2);
                out.decoded.push_back(float(std::max(value / largest, -1.0)));
            }
        out.elementBytes = std::size_t(stride);
        out.bits = bits;
        out.components = components;
        out.componentType = stride == 4 ? kByte : kShort;
        out.normalized = true;
        out.filter = "OCTAHEDRAL";
        return out;
    };
    std::optional<RoundedAttribute> kept;
    std::size_t keptBytes = 0;
    for (const int stride : {4, 8}) {
        const int bits = fewestBits(4, stride == 4 ? 8 : 16, [&](int b) {
            return largestError(values, rounded(stride, b), components, true) <= allowed;
        });
        if (bits == 0) continue;
        RoundedAttribute out = rounded(stride, bits);
        const std::size_t bytes = meshoptEncoded(out.filtered, out.elementBytes).size();
        if (!kept || bytes < keptBytes) kept = std::move(out), keptBytes = bytes;
    }
    return kept;
}

template <typename Vector>
std::vector<float> floatsOf(const std::vector<Vector>& vectors, int components) {
    std::vector<float> flat;
    flat.reserve(vectors.size() * std::size_t(components));
    for (const Vector& vector : vectors)
        for (int c = 0; c < components; ++c) flat.push_back(float(vector[c]));
    return flat;
}

// Half a step of Draco's quantization of values spanning `span` at `bits`.
double halfStep(double span, int bits) { return bits > 0 ? span / (2.0 * ((1 << bits) - 1)) : 0; }

double span(const std::vector<float>& values) {
    if (values.empty()) return 0;
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    return double(*hi) - double(*lo);
}

// What Draco's quantization allows attribute `name` (values `ownValues`, the primitive's own: a displacement's
// allowance comes from the values it displaces), and whether it is measured as a vector (Euclidean); 0: none.
std::pair<double, bool> allowance(const std::string& name, const std::vector<float>& ownValues,
                                  const Primitive& primitive, const WriteOptions& options) {
    auto startsWith = [&](const char* prefix) { return name.rfind(prefix, 0) == 0; };
    // Draco's octahedral normals at normalBits are within about 2^-normalBits of a unit vector as read.
    if (name == "NORMAL" || name == "TANGENT") return {std::ldexp(1.0, -options.normalBits), true};
    if (startsWith("TEXCOORD_")) return {halfStep(span(ownValues), options.texcoordBits), false};
    if (startsWith("COLOR_")) return {halfStep(span(ownValues), colorBitsFor(primitive, options)), false};
    if (startsWith("WEIGHTS_")) return {halfStep(span(ownValues), options.weightBits), false};
    return {0, false};
}

}  // namespace

RoundedVertices roundedPlainVertices(const Primitive& primitive, const WriteOptions& options,
                                     const std::vector<double>& largestWeights,
                                     const IntegerPositionGrid* integerGrid) {
    RoundedVertices out;
    const double positionBound = positionErrorBound(primitive, options);
    if (!(positionBound > 0)) return out;
    double weightSum = 0;
    for (double weight : largestWeights) weightSum += std::abs(weight);
    // Half to the vertices as read, half to the displacements, which add up over the targets.
    const double displacementShare = 0.5 / std::max(weightSum, 1.0);

    std::map<std::string, std::pair<std::vector<float>, int>> own;  // each attribute's values and components
    own["POSITION"] = {floatsOf(primitive.positions, 3), 3};
    if (!primitive.normals.empty()) own["NORMAL"] = {floatsOf(primitive.normals, 3), 3};
    if (!primitive.texcoords.empty()) own["TEXCOORD_0"] = {floatsOf(primitive.texcoords, 2), 2};
    if (!primitive.colors.empty()) own["COLOR_0"] = {floatsOf(primitive.colors, 4), 4};
    for (const VertexAttribute& attribute : primitive.attributes)
        if (!attribute.isJoints())
            own[attribute.name] = {std::vector<float>(attribute.values.begin(), attribute.values.end()),
                                   attribute.components};

    if (integerGrid) {
        out[{-1, "POSITION"}] = integerPositions(primitive, *integerGrid);
        own.erase("POSITION");
    }
    for (const auto& [name, values] : own) {
        auto [allowed, euclidean] = allowance(name, values.first, primitive, options);
        if (name == "POSITION") allowed = positionBound, euclidean = true;
        // A TANGENT's w (its handedness, +-1) is kept exactly at any bits: the largest component sets the exponent.
        // Half of it where morph targets' displacements take the other half.
        const double share = primitive.targets.empty() ? allowed : allowed / 2;
        std::optional<RoundedAttribute> rounded = roundedWithin(values.first, values.second, share, euclidean);
        // Colours as normalized integers, normals and tangents through the octahedral filter, where they hold them
        // within the share and meshopt codes them smaller by more than the JSON of a view of their own.
        std::optional<RoundedAttribute> other;
        std::size_t overhead = kOwnViewBytes;
        if (name.rfind("COLOR_", 0) == 0) other = normalizedWithin(values.first, values.second, share);
        if (name == "NORMAL" || name == "TANGENT") {
            other = octahedralWithin(values.first, values.second, share);
            overhead += kQuantizationNamesBytes;
        }
        if (other && (!rounded || meshoptEncoded(other->filtered, other->elementBytes).size() + overhead <
                                      meshoptEncoded(rounded->filtered, rounded->elementBytes).size()))
            rounded = std::move(other);
        if (rounded) out[{-1, name}] = std::move(*rounded);
    }
    for (std::size_t t = 0; t < primitive.targets.size(); ++t)
        for (const VertexAttribute& displacement : primitive.targets[t]) {
            const auto found = own.find(displacement.name);
            if (found == own.end()) continue;  // a TANGENT's displacements have no w: its allowance holds all the same
            auto [allowed, euclidean] = allowance(displacement.name, found->second.first, primitive, options);
            if (displacement.name == "POSITION") allowed = positionBound, euclidean = true;
            const std::vector<float> values(displacement.values.begin(), displacement.values.end());
            if (auto rounded = roundedWithin(values, displacement.components, allowed * displacementShare, euclidean))
                out[{int(t), displacement.name}] = std::move(*rounded);
        }
    return out;
}

std::optional<RoundedAttribute> exponentialPositions(const Primitive& primitive, double bound) {
    return roundedWithin(floatsOf(primitive.positions, 3), 3, bound, true);
}

bool needsMeshQuantization(const RoundedVertices& rounded) {
    return std::any_of(rounded.begin(), rounded.end(), [](const auto& entry) {
        const std::string& name = entry.first.second;
        return entry.second.componentType != kFloat && (name == "POSITION" || name == "NORMAL" || name == "TANGENT");
    });
}

Primitive spatiallySorted(const Primitive& primitive, const IntegerPositionGrid* grid) {
    // The cells of the grid, else of 2^16 a side over the points' box.
    constexpr int kCellBits = 16;
    const Eigen::AlignedBox3d box = boundsOf(primitive.positions);
    const double side = box.sizes().maxCoeff();
    auto cell = [&](const Eigen::Vector3d& p, int axis) -> std::uint32_t {
        if (grid) return grid->coordinate(p, axis);
        if (!(side > 0)) return 0;
        const double largest = (1 << kCellBits) - 1;
        return std::uint32_t(std::clamp(std::round((p[axis] - box.min()[axis]) / side * largest), 0.0, largest));
    };
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(primitive.positions.size());  // along the curve, vertex
    for (std::size_t v = 0; v < keyed.size(); ++v) {
        const Eigen::Vector3d& p = primitive.positions[v];
        keyed[v] = {hilbertIndex({cell(p, 0), cell(p, 1), cell(p, 2)}, kCellBits), std::uint32_t(v)};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::uint32_t> order(keyed.size()), renumbered(keyed.size());  // new vertex -> old, old -> new
    for (std::size_t v = 0; v < keyed.size(); ++v) order[v] = keyed[v].second, renumbered[keyed[v].second] = v;
    Primitive sorted = primitive;
    keepVertices(sorted, order);
    // Each segment from its earlier vertex, the segments in order: meshopt's index codec codes each index as its
    // difference from one before.
    for (Segment& segment : sorted.lines) {
        segment = {renumbered[segment[0]], renumbered[segment[1]]};
        if (segment[1] < segment[0]) std::swap(segment[0], segment[1]);
    }
    std::sort(sorted.lines.begin(), sorted.lines.end());
    return sorted;
}

std::vector<double> largestMorphWeights(const Scene& scene, std::size_t mesh) {
    std::size_t targets = 0;
    for (const Primitive& primitive : scene.meshes[mesh].primitives)
        targets = std::max(targets, primitive.targets.size());
    std::vector<double> largest(targets, 0.0);
    auto take = [&](std::size_t k, double weight) {
        if (k < targets) largest[k] = std::max(largest[k], std::abs(weight));
    };
    for (std::size_t k = 0; k < scene.meshes[mesh].weights.size(); ++k) take(k, scene.meshes[mesh].weights[k]);
    std::vector<char> draws(scene.nodes.size(), 0);
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        const Node& node = scene.nodes[n];
        if (node.mesh != int(mesh)) continue;
        draws[n] = 1;
        for (std::size_t k = 0; k < node.weights.size(); ++k) take(k, node.weights[k]);
    }
    for (const Animation& animation : scene.animations)
        for (const AnimationChannel& channel : animation.channels) {
            if (channel.path != AnimationChannel::Path::Weights || channel.node < 0 ||
                std::size_t(channel.node) >= draws.size() || !draws[std::size_t(channel.node)])
                continue;
            const std::size_t components = channel.components();
            if (components == 0) continue;
            if (channel.interpolation != AnimationChannel::Interpolation::CubicSpline) {
                for (std::size_t i = 0; i < channel.values.size(); ++i) take(i % components, channel.values[i]);
                continue;
            }
            // Between two keys a Hermite spline is its values' blend (basis weights summing to 1 in magnitude at
            // most) plus its tangents times the interval, each weighted 4/27 at most.
            double longest = 0;
            for (std::size_t k = 1; k < channel.times.size(); ++k)
                longest = std::max(longest, channel.times[k] - channel.times[k - 1]);
            std::vector<double> value(components, 0.0), tangent(components, 0.0);
            for (std::size_t i = 0; i < channel.values.size(); ++i) {
                const std::size_t c = i % components, part = (i / components) % 3;  // in-tangent, value, out-tangent
                double& most = part == 1 ? value[c] : tangent[c];
                most = std::max(most, std::abs(channel.values[i]));
            }
            for (std::size_t c = 0; c < components; ++c) take(c, value[c] + 2 * 4.0 / 27 * longest * tangent[c]);
        }
    return largest;
}

}  // namespace symcompress
