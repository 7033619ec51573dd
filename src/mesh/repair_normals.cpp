#include "symcompress/scene_ops.hpp"

#include <Eigen/Geometry>

namespace symcompress {

std::size_t repairNormals(Scene& scene) {
    std::size_t replaced = 0;
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives) {
            if (primitive.normals.empty()) continue;
            std::vector<Eigen::Vector3d> faceNormals;  // computed only when needed
            for (std::size_t v = 0; v < primitive.normals.size(); ++v) {
                Eigen::Vector3d& normal = primitive.normals[v];
                const double length = normal.norm();
                if (std::isfinite(length) && length > 1e-12) {
                    normal /= length;
                    continue;
                }
                if (faceNormals.empty()) {
                    faceNormals.assign(primitive.positions.size(), Eigen::Vector3d::Zero());
                    for (const Triangle& t : primitive.triangles) {
                        const Eigen::Vector3d twiceArea = (primitive.positions[t[1]] - primitive.positions[t[0]])
                                                              .cross(primitive.positions[t[2]] - primitive.positions[t[0]]);
                        for (std::uint32_t corner : t) faceNormals[corner] += twiceArea;
                    }
                }
                const double faceLength = faceNormals[v].norm();
                normal = faceLength > 0 ? Eigen::Vector3d(faceNormals[v] / faceLength) : Eigen::Vector3d::UnitZ();
                ++replaced;
            }
        }
    return replaced;
}

}  // namespace symcompress
