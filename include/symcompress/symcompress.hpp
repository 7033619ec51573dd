// symcompress: makes 3D scenes smaller by finding what repeats in them. The entry points a library user
// needs; headers under detail/ are the stages' internals (docs/ARCHITECTURE.md).
//   readScene, writeScene           read and write glTF/GLB, X3D, OBJ, PLY, STL       (io.hpp)
//   worldMesh, flattenScene         a scene as one surface, or as placed primitives   (scene_ops.hpp)
//   detectSymmetries                the symmetry group of one shape                   (symmetry.hpp)
//   splitIntoTiles, classifyTiles   tiles and their congruence classes                (tiles.hpp, congruence.hpp)
//   assemblySymmetries              the symmetry group of an assembly of tiles        (assembly.hpp)
//   compressFile, compressToFile    the whole job, with its size report               (compress.hpp)
//   decompressFile, compareSurfaces rebuild, and verify against the original or digest (verify.hpp)
//   writeDetectionReport            the HTML page of a shape's symmetries              (html_report.hpp)
#pragma once

#include "symcompress/assembly.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/congruence.hpp"
#include "symcompress/html_report.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/symmetry.hpp"
#include "symcompress/tiles.hpp"
#include "symcompress/verify.hpp"
