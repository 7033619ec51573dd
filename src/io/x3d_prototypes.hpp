// X3D prototypes expanded in place before the scene is read (X3D 4.0, 4.4.4 Prototype semantics): each
// ProtoInstance becomes a copy of the first node of its prototype's body, each IS connection given the instance's
// field value (or the declaration's default), the copy's DEF names its own. An ExternProtoDeclare takes its
// declaration from a local file its url names. The reader then reads the expanded nodes as any other.
#pragma once

#include <pugixml.hpp>

#include <filesystem>
#include <functional>
#include <set>
#include <string>

namespace symcompress::x3d {

struct PrototypeExpansion {
    std::size_t instances = 0;    // ProtoInstances expanded
    std::set<std::string> notes;  // what could not be expanded, for the reader's warnings
};

// Loads an X3D document from a local file (an ExternProtoDeclare's); false where it cannot.
using DocumentLoader = std::function<bool(const std::filesystem::path& file, pugi::xml_document& into)>;

// Expands every ProtoInstance under `scene` whose prototype is declared before it (ProtoDeclare, or an
// ExternProtoDeclare whose url names a local file, relative to `folder`), nested ones too, up to 32 levels.
// Throws std::length_error where the expansion would make more than 2^20 elements.
PrototypeExpansion expandPrototypes(pugi::xml_node scene, const std::filesystem::path& folder,
                                    const DocumentLoader& load);

}  // namespace symcompress::x3d
