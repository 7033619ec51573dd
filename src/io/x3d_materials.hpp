// How the X3D writer draws a material: which node (X3D 3.3's Phong Material, or X3D 4's PhysicalMaterial),
// which of its texture fields, and which texture coordinates each reads. The colour spaces are in
// docs/scene-model.md ("Colour spaces").
#pragma once

#include "symcompress/scene.hpp"

#include <optional>
#include <string>
#include <vector>

namespace symcompress::x3d {

// KHR_materials_unlit (not read from X3D's Phong Material): X3D 4's UnlitMaterial, whose emissive colour and
// texture are the colour drawn (sRGB-encoded, as Phong's: X_ITE draws it so).
bool isUnlit(const Material& material);

// An unlit white material whose only texture, if any, is the base colour's: X3D's Appearance without a material
// (X3D 3.3), or no Appearance at all where it has no texture and no alpha mode to state; as X3D draws those.
bool drawnWithoutMaterial(const Material& material);

// The alpha mode an Appearance must state (X3D 4's alphaMode) where X3D's AUTO, X3D 3's only rule, would draw
// the material otherwise: AUTO blends where the material is transparent or what it draws is translucent
// (`translucentContent`: its base texture's pixels, imageHasTranslucentPixels, or every shape's vertex colours),
// and never cuts out.
std::optional<Material::AlphaMode> statedAlphaMode(const Material& material, bool translucentContent);

// A PhysicalMaterial where Phong cannot draw the material (and it is not unlit): no Phong fields kept from an X3D
// input, and metal, or a texture other than the base colour's. Otherwise X3D 3.3's Material, as symcompress always
// wrote it.
bool needsPhysicalMaterial(const Material& material);

// The Phong fields written for a material: those it was read with, else its glTF factors sRGB-encoded.
PhongMaterial phongOf(const Material& material);

// The Phong fields written for a material that draws lines or points: X3D draws those unlit, in the emissive
// colour, glTF's viewers in the base colour; so that colour (sRGB-encoded as phongOf's diffuse colour) is the
// emissive colour, with phongOf's transparency, of a Material that reflects nothing.
PhongMaterial unlitPhongOf(const Material& material);

// One texture field the writer fills: the X3D field, the texture use, and the texture coordinates it reads (an
// index into texcoordChannels).
struct TextureField {
    const char* field;  // "baseTexture", "diffuseTexture", "normalTexture", ...
    const TextureRef* use;
    std::size_t channel = 0;
};

// A set of texture coordinates as the writer writes it: the set, with the use's transform applied, and its
// mapping (empty where the material reads one set only: then a plain TextureCoordinate).
struct TexcoordChannel {
    int set = 0;
    std::optional<TextureTransform> transform;
    std::string mapping;
};

struct MaterialTextures {
    std::vector<TextureField> fields;       // in the order written; the base colour's first
    std::vector<TexcoordChannel> channels;  // at least one
    bool x3d4Fields = false;                // a texture field of X3D 4's Material or PhysicalMaterial is written
};

// The texture fields of `material` as written (a Phong material keeps its base colour in the Appearance's
// texture unless it has X3D 4 texture fields; it has no field for a metallic-roughness texture).
MaterialTextures materialTextures(const Material& material);

// Whether writing `material` needs X3D 4.0 (PhysicalMaterial, Material's texture fields, texture mappings).
bool needsX3d4(const Material& material);

// glTF's samplers as X3D's TextureProperties (Texturing component, X3D 3.0 on): boundary modes and filters by
// name. The sampler's enums (scene.hpp); 0, a filter left to the viewer, is X3D's NICEST (what X_ITE uses
// without TextureProperties).
std::string boundaryModeName(int wrap);
int boundaryModeOf(const std::string& name);  // CLAMP, CLAMP_TO_EDGE and CLAMP_TO_BOUNDARY: CLAMP_TO_EDGE
std::string minificationFilterName(int filter);
std::string magnificationFilterName(int filter);
int filterOf(const std::string& name);  // NICEST, FASTEST, DEFAULT: 0

}  // namespace symcompress::x3d
