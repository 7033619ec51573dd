// The faces of the X3D geometry nodes that do not list them face by face: triangle strips and fans, quads,
// the ElevationGrid and the Extrusion, cut and turned as X_ITE cuts them, so that the reader's faces draw what
// the browser draws (X3D 4.0, 11.4 Rendering, 13.3 Geometry3D, 32.4 CADGeometry). The reader (readFaceSet)
// reads their attributes onto these faces as it does for the face sets.
#pragma once

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace symcompress::x3d {

// A face's corners as indices of points, counter-clockwise where the node's ccw is TRUE.
using Face = std::vector<std::int64_t>;

// A geometry node's faces, and what it makes itself where it has no Coordinate or TextureCoordinate.
struct Faces {
    std::vector<double> points;  // x y z of each point the node makes (ElevationGrid, Extrusion)
    std::vector<Face> faces;
    // The index each face takes into per-face attributes (colorPerVertex or normalPerVertex FALSE); empty: the
    // face's own number. An ElevationGrid's square is two triangles with one colour.
    std::vector<std::int64_t> attributeFace;
    // Texture coordinates the node makes (s t each, X3D's t up), indexed by point, or where given, by
    // `texcoordOfCorner` (one per corner in face order: an Extrusion's seam has two at one point).
    std::vector<double> texcoords;
    std::vector<std::int64_t> texcoordOfCorner;
};

// IndexedTriangleStripSet's and IndexedTriangleFanSet's triangles: `index` holds strips (fans) ended by -1.
std::vector<Face> indexedStrips(const std::vector<std::int64_t>& index);
std::vector<Face> indexedFans(const std::vector<std::int64_t>& index);

// TriangleStripSet's and TriangleFanSet's triangles: strips (fans) of consecutive points, `counts` points each,
// of the first `pointCount` (the caller says where the counts name more). A count below 3 draws nothing.
std::vector<Face> countedStrips(const std::vector<std::int64_t>& counts, std::int64_t pointCount);
std::vector<Face> countedFans(const std::vector<std::int64_t>& counts, std::int64_t pointCount);

// IndexedQuadSet's quads (QuadSet's: `corners` 0, 1, 2, ...): each 4 corners one quad, the rest left out.
std::vector<Face> quads(const std::vector<std::int64_t>& corners);

// An ElevationGrid: xDimension by zDimension points at the spacings, y from `height` (0 where it is short), each
// square two triangles; texture coordinates from 0 to 1 across the grid. Fewer than 2 points on an axis: none.
Faces elevationGrid(std::int64_t xDimension, std::int64_t zDimension, double xSpacing, double zSpacing,
                    const std::vector<double>& height);

// An Extrusion's fields, X3D's defaults where the file has none.
struct ExtrusionFields {
    std::vector<Eigen::Vector3d> spine{{0, 0, 0}, {0, 1, 0}};
    std::vector<Eigen::Vector2d> crossSection{{1, 1}, {1, -1}, {-1, -1}, {-1, 1}, {1, 1}};
    std::vector<Eigen::Vector2d> scale{{1, 1}};
    std::vector<Eigen::AngleAxisd> orientation{Eigen::AngleAxisd::Identity()};
    bool beginCap = true, endCap = true;
};

// The Extrusion's surface (X3D 4.0, 13.3.5): the cross-section scaled, turned by its orientation and placed in
// each spine point's cross-section plane; a triangle between two coincident points left out; the caps as one
// face each over points of their own (so that smoothing never crosses their rim).
Faces extrusion(const ExtrusionFields& fields);

}  // namespace symcompress::x3d
